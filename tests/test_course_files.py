"""Issue 48 for the course's commands (`python -m icm.course assign`, `lms`, `slides`,
and the command line of `grade`): nothing lost on bad input.

A corpus of bad destinations and numbers, run through the command line as a teacher
types it: for each, the command refuses before any work, with one line on the
standard error naming the option or the file, exit status 1, no traceback, and every
file and folder around it (and the book's sources) exactly as before, contents, links
and permissions. Then what must be accepted (an earlier run's own output, someone
else's folder with --force, a one-digit seed), and what a run that fails or is killed
half-way leaves (the old output whole, nothing half-written)."""

import argparse
import hashlib
import os
import pathlib
import signal
import stat
import subprocess
import sys
import time

import nbformat
import pytest

from conftest import ROOT

from icm import files, records
from icm.course import __main__ as course_cli
from icm.course import assign, grade, lms, slides

CHAPTER = "button_experiment"
"""The chapter the tests assign (one implement exercise: a few seconds of otter)."""
OTHER_CHAPTER = "goal_oriented_interest"
PNG = bytes.fromhex("89504e470d0a1a0a0000000d49484452000000010000000108000000003a7e9b55000000"
                    "0a49444154789c636000000002000148afa4710000000049454e44ae426082")
"""A PNG of one pixel (a figure of the fake book)."""
FOREIGN_XML = '<?xml version="1.0" encoding="UTF-8"?>\n<quiz>\n<!-- my own questions -->\n</quiz>\n'
"""A Moodle XML file that `lms` did not write."""


# --- the workshop: a fake built book, and what a teacher keeps around it -----------------

def fake_book(folder):
    """A built book as `lms` and `slides` read it: per chapter a page with its title, a
    figure and a "predict, then check" question, and the vendored scripts (stand-ins:
    the decks are not opened here)."""
    (folder / "_images").mkdir(parents=True)
    (folder / "book").mkdir()
    (folder / "_images" / "figure.png").write_bytes(PNG)
    reveal = folder / "_static" / "vendor" / "reveal" / "dist"
    reveal.mkdir(parents=True)
    (reveal / "reveal.js").write_text("/* reveal.js */")
    (folder / "_static" / "vendor" / "mathjax").mkdir()
    (folder / "_static" / "vendor" / "mathjax" / "tex-mml-chtml.js").write_text("/* */")
    for number, (name, _) in enumerate(assign.chapters(), 1):
        (folder / "book" / f"{name}.html").write_text(
            f'<html><body><main><h1>Chapter {name}</h1><figure><img src="../_images/'
            f'figure.png" alt="a plot"><figcaption><span class="caption-text">A figure'
            f'</span></figcaption></figure><div class="exercise admonition icm-quiz" '
            f'id="ex-quiz-{number}"><p class="admonition-title">Exercise {number}.1 '
            f'(Predict, then check: a guess)</p><section><p>Which?</p><div><fieldset '
            f'class="icm-quiz-choices"><div class="icm-quiz-option"><input data-correct='
            f'"true" data-hint=""><label>this</label></div><div class="icm-quiz-option">'
            f'<input data-correct="false" data-hint="Look again."><label>that</label></div>'
            f'</fieldset></div><div class="icm-quiz-explanation"><p>This, 3 of 4.</p></div>'
            f'</section></div></main></body></html>', encoding="utf-8")
    return folder


def marked_folder(folder, command):
    """A folder another of icm's commands wrote (its marker names `command`)."""
    folder.mkdir()
    (folder / files.MARKER).write_text(files.marker_text(command))
    (folder / "kept.txt").write_text("written by " + command)
    return folder


@pytest.fixture
def workshop(tmp_path):
    """A teacher's folder: the built book (HTML), a notebook, someone else's Moodle
    file, a plain file, someone else's folder, folders of icm's other commands, an
    empty read-only folder, links to a file, a folder and the book, a folder named like
    an XML file, a named pipe, and a folder of submissions."""
    fake_book(tmp_path / "HTML")
    nbformat.write(nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1")]),
                   tmp_path / "notes.ipynb")
    (tmp_path / "foreign.xml").write_text(FOREIGN_XML)
    (tmp_path / "file.txt").write_text("a plain file")
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "keep.txt").write_text("someone else's")
    marked_folder(tmp_path / "assign_out", assign.COMMAND)
    marked_folder(tmp_path / "slides_out", slides.COMMAND)
    (tmp_path / "ro").mkdir()
    (tmp_path / "ro").chmod(0o555)
    (tmp_path / "link_file.xml").symlink_to("notes.ipynb")
    (tmp_path / "link_dir").symlink_to("other")
    (tmp_path / "link_dir.xml").symlink_to("other")
    (tmp_path / "link_html").symlink_to("HTML")
    (tmp_path / "dangling").symlink_to("nowhere")
    # Links to the commands' own outputs: writing through them would change those.
    (tmp_path / "own_export.xml").write_text(f"{lms.DECLARATION}\n{lms.SIGNATURE}\n<quiz/>\n")
    (tmp_path / "link_own_export.xml").symlink_to("own_export.xml")
    marked_folder(tmp_path / "own_slides", slides.COMMAND)
    (tmp_path / "link_own_slides").symlink_to("own_slides")
    (tmp_path / "link_own_assign").symlink_to("assign_out")
    (tmp_path / "dir.xml").mkdir()
    os.mkfifo(tmp_path / "pipe.xml")
    (tmp_path / "subs").mkdir()
    (tmp_path / "subs" / "alice.ipynb").write_text("{}")
    bad = tmp_path / "bad_assignments" / "chapter" / "autograder"
    bad.mkdir(parents=True)
    (bad / grade.MANIFEST).write_text('{"chapter": "x", "number": ')
    return tmp_path


@pytest.fixture
def deadline():
    """Ends a test that waits more than 30 s (a named pipe read would wait forever)."""
    def too_long(*_):
        raise TimeoutError("waited more than 30 s")
    previous = signal.signal(signal.SIGALRM, too_long)
    signal.alarm(30)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, previous)


def tree(*roots):
    """Everything under `roots` (folders or files), links not followed: {path: (kind,
    permissions, and a file's SHA-256 or a link's target)}."""
    found = {}
    for root in roots:
        paths = [pathlib.Path(root)] if not os.path.isdir(root) else \
            [pathlib.Path(folder) / name for folder, names, file_names in os.walk(root)
             for name in [""] + names + file_names]
        for path in paths:
            info = path.lstat()
            mode = stat.S_IMODE(info.st_mode)
            if stat.S_ISLNK(info.st_mode):
                found[str(path)] = ("link", os.readlink(path))
            elif stat.S_ISREG(info.st_mode):
                found[str(path)] = ("file", mode, hashlib.sha256(path.read_bytes()).hexdigest())
            else:
                found[str(path)] = (stat.S_IFMT(info.st_mode), mode)
    return found


def course(monkeypatch, capsys, cwd, *args):
    """Runs `python -m icm.course ARGS` in this process (as its `main`), in `cwd`:
    (exit status, standard output, standard error). An exception that escapes `main`
    (a traceback) fails the test."""
    monkeypatch.chdir(cwd)
    try:
        status = course_cli.main([str(arg) for arg in args])
    except SystemExit as exit_:  # argparse's errors
        status = exit_.code
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def assert_refused(result, named):
    """Exit status 1, and one line on the standard error that names `named`."""
    status, _, err = result
    assert status == 1, result
    assert err.endswith("\n") and err.count("\n") == 1, err
    assert "Traceback" not in err and named in err, (named, err)


# --- the corpus of bad input ---------------------------------------------------------------

ASSIGN = ("--chapters", CHAPTER, "--no-run-tests")
"""What every assign of the corpus adds: one chapter, its solutions not graded."""
DESTINATIONS = {
    # case: (arguments, what the error must name); paths relative to the workshop
    "lms: a notebook": (("lms", "HTML", "--out", "notes.ipynb"), "notes.ipynb"),
    "lms: someone else's Moodle file": (("lms", "HTML", "--out", "foreign.xml"), "foreign.xml"),
    "lms: the book itself": (("lms", "HTML", "--out", "HTML"), "HTML"),
    "lms: inside the book": (("lms", "HTML", "--out", "HTML/book/q.xml"), "HTML/book/q.xml"),
    "lms: inside the book, through a link": (("lms", "HTML", "--out", "link_html/q.xml"),
                                             "link_html/q.xml"),
    "lms: the book, through a link": (("lms", "link_html", "--out", "HTML/q.xml"),
                                      "HTML/q.xml"),
    "lms: a link to a file": (("lms", "HTML", "--out", "link_file.xml"), "link_file.xml"),
    "lms: a link to its own export": (("lms", "HTML", "--out", "link_own_export.xml"),
                                      "link_own_export.xml"),
    "lms: a new file that is not XML": (("lms", "HTML", "--out", "new.ipynb"), "new.ipynb"),
    "lms: a link to a folder": (("lms", "HTML", "--out", "link_dir.xml"), "link_dir.xml"),
    "lms: a folder for the file": (("lms", "HTML", "--out", "dir.xml"), "dir.xml"),
    "lms: a file for a folder on the way": (("lms", "HTML", "--out", "file.txt/q.xml"),
                                            "file.txt is a file"),
    "lms: a file for the book": (("lms", "notes.ipynb", "--out", "q.xml"), "notes.ipynb"),
    "lms: no book": (("lms", "nothing", "--out", "q.xml"), "nothing"),
    "lms: a broken link on the way": (("lms", "HTML", "--out", "dangling/q.xml"), "dangling"),
    "lms: a read-only folder": (("lms", "HTML", "--out", "ro/q.xml"), "ro is read-only"),
    "lms: a named pipe": (("lms", "HTML", "--out", "pipe.xml"), "pipe.xml"),
    "slides: a notebook": (("slides", "HTML", "--out", "notes.ipynb"), "notes.ipynb"),
    "slides: the book itself": (("slides", "HTML", "--out", "HTML"), "HTML"),
    "slides: inside the book": (("slides", "HTML", "--out", "HTML/_static/s"), "HTML/_static/s"),
    "slides: holding the book": (("slides", "HTML", "--out", "."), "--out"),
    "slides: the book, through a link": (("slides", "HTML", "--out", "link_html"), "link_html"),
    "slides: inside the book, through a link": (("slides", "link_html", "--out", "HTML/s"),
                                                "HTML/s"),
    "slides: a link to a file": (("slides", "HTML", "--out", "link_file.xml"), "link_file.xml"),
    "slides: a link to a folder": (("slides", "HTML", "--out", "link_dir"), "link_dir"),
    "slides: a link to its own folder": (("slides", "HTML", "--out", "link_own_slides"),
                                         "link_own_slides"),
    "slides: a file for the folder": (("slides", "HTML", "--out", "file.txt"), "file.txt"),
    "slides: a file for the book": (("slides", "notes.ipynb", "--out", "s"), "notes.ipynb"),
    "slides: someone else's folder": (("slides", "HTML", "--out", "other"), "other"),
    "slides: the assignments' folder": (("slides", "HTML", "--out", "assign_out"), "assign_out"),
    "slides: a broken link on the way": (("slides", "HTML", "--out", "dangling/s"), "dangling"),
    "slides: in a read-only folder": (("slides", "HTML", "--out", "ro/s"), "ro is read-only"),
    "slides: a read-only folder": (("slides", "HTML", "--out", "ro"), "ro is read-only"),
    "slides: a named pipe": (("slides", "HTML", "--out", "pipe.xml"), "pipe.xml"),
    "assign: a notebook": (("assign", "notes.ipynb", *ASSIGN), "notes.ipynb"),
    "assign: the book's sources": (("assign", ROOT / "book", *ASSIGN), str(ROOT / "book")),
    "assign: inside the book's sources": (("assign", ROOT / "book" / "out", *ASSIGN),
                                          str(ROOT / "book" / "out")),
    "assign: holding the book's sources": (("assign", ROOT, *ASSIGN), str(ROOT)),
    "assign: a link to a file": (("assign", "link_file.xml", *ASSIGN), "link_file.xml"),
    "assign: a link to a folder": (("assign", "link_dir", *ASSIGN), "link_dir"),
    "assign: a link to its own folder": (("assign", "link_own_assign", *ASSIGN),
                                         "link_own_assign"),
    "assign: a file for the folder": (("assign", "file.txt", *ASSIGN), "file.txt"),
    "assign: a file on the way": (("assign", "file.txt/a", *ASSIGN), "file.txt is a file"),
    "assign: someone else's folder": (("assign", "other", *ASSIGN), "other"),
    "assign: the slides' folder": (("assign", "slides_out", *ASSIGN), "slides_out"),
    "assign: a broken link on the way": (("assign", "dangling/a", *ASSIGN), "dangling"),
    "assign: in a read-only folder": (("assign", "ro/a", *ASSIGN), "ro is read-only"),
    "assign: an unknown chapter": (("assign", "a", "--chapters", "nothing"), "nothing"),
    "grade: a notebook for the sheet": (("grade", "subs", "--out", "subs/alice.ipynb"),
                                        "subs/alice.ipynb"),
    "grade: the submissions for the feedback": (("grade", "subs", "--out", "g.csv",
                                                 "--feedback", "subs"), "subs"),
    "grade: someone else's folder for the feedback": (("grade", "subs", "--out", "g.csv",
                                                       "--feedback", "other"), "other"),
    "grade: the slides' folder for the feedback": (("grade", "subs", "--out", "g.csv",
                                                    "--feedback", "slides_out"), "slides_out"),
    "grade: a folder for the sheet": (("grade", "subs", "--out", "dir.xml"), "dir.xml"),
    "grade: a link for the sheet": (("grade", "subs", "--out", "link_file.xml"), "link_file.xml"),
    "grade: a read-only folder": (("grade", "subs", "--out", "ro/g.csv"), "ro is read-only"),
    "grade: a malformed manifest": (("grade", "subs", "--out", "g.csv", "--assignments",
                                     "bad_assignments", "--trusted"),
                                    "bad_assignments/chapter/autograder/assignment.json"),
}
BAD_NUMBERS = ("nan", "0", "-1", "1e300", "x", "inf", "")
NUMBERS = {"assign": ("--seed", "--jobs"),
           "grade": ("--time-limit", "--memory-limit", "--cell-timeout", "--jobs")}
BAD_INTEGERS = {"--seed": ("1.5", str(2 ** 63)),
                "--jobs": ("1.5", str(course_cli.CORES + 1))}
"""Beyond `BAD_NUMBERS`: what only an integer option refuses (a fraction, one past its
end: a seed of 64 bits, more jobs than the machine's cores)."""
NUMBER_CASES = [(command, option, value) for command, options in NUMBERS.items()
                for option in options
                for value in BAD_NUMBERS + BAD_INTEGERS.get(option, ())
                if not (option == "--seed" and value == "0")]  # (a seed may be 0)


def _no_work(*_, **__):
    raise AssertionError("the command began its work before it refused")


@pytest.mark.parametrize("case", sorted(DESTINATIONS))
def test_a_bad_destination_is_refused_before_any_work_and_nothing_changes(
        case, workshop, monkeypatch, capsys, deadline):
    arguments, named = DESTINATIONS[case]
    for module, name in ((lms, "_soup"), (slides, "_soup"), (assign, "assign_chapter"),
                         (grade, "grade_submission")):  # the work: never begun
        monkeypatch.setattr(module, name, _no_work)
    around = (workshop, ROOT / "book") if arguments[0] == "assign" else (workshop,)
    before = tree(*around)
    result = course(monkeypatch, capsys, workshop, *arguments)
    assert_refused(result, named)
    assert tree(*around) == before


@pytest.mark.parametrize("command, option, value", NUMBER_CASES)
def test_a_bad_number_is_refused_naming_its_option_when_read(
        command, option, value, workshop, monkeypatch, capsys):
    arguments = ("assign", "a", *ASSIGN) if command == "assign" else ("grade", "subs", "--out",
                                                                     "g.csv", "--trusted")
    before = tree(workshop)
    result = course(monkeypatch, capsys, workshop, *arguments, option, value)
    assert_refused(result, f"argument {option}: must be ")
    assert f"got {value!r}" in result[2]
    assert tree(workshop) == before


def test_the_stated_ranges_are_grades_own():
    # The command line refuses what grade() refuses, and accepts what it accepts: at
    # each end of each range, and just past it.
    assert course_cli.CORES == grade.MAX_JOBS == assign.MAX_JOBS
    names = {"--time-limit": "time_limit", "--memory-limit": "memory_limit",
             "--cell-timeout": "cell_timeout", "--jobs": "jobs"}
    for option, name in names.items():
        kind, low, high, _ = course_cli.NUMBERS[option]
        parse = course_cli.number(option)
        step = 1 if kind is int else 1e-6
        for value, inside in ((low, True), (high, True), (low - step, False),
                              (high + step, False)):
            text = str(value)
            if inside:
                assert parse(text) == value
            else:
                with pytest.raises(argparse.ArgumentTypeError, match="must be"):
                    parse(text)
            # grade() checks its limits first; a folder that does not exist comes next.
            with pytest.raises(ValueError) as raised:
                grade.grade("no-such-folder", "g.csv", **{name: kind(value)})
            assert ("does not exist" in str(raised.value)) == inside, (option, value)


def test_the_real_command_says_one_line_and_exits_with_1(workshop):
    # As a teacher runs it: its own process, its standard error, its exit status.
    before = tree(workshop)
    for arguments, named in (DESTINATIONS["lms: a notebook"],
                             DESTINATIONS["grade: a malformed manifest"],
                             (("assign", "a", "--jobs", "nan"), "--jobs")):
        done = subprocess.run([sys.executable, "-m", "icm.course", *map(str, arguments)],
                              capture_output=True, text=True, cwd=workshop, timeout=120)
        assert_refused((done.returncode, done.stdout, done.stderr), named)
        assert done.stdout == ""
    assert tree(workshop) == before


# --- what the book's pages may not do ---------------------------------------------------------

@pytest.mark.parametrize("bad", ["a named pipe", "not UTF-8", "a folder", "a figure outside",
                                 "no title"])
def test_a_bad_page_of_the_book_is_refused_naming_it(bad, workshop, monkeypatch, capsys,
                                                     deadline):
    page = workshop / "HTML" / "book" / f"{assign.chapters()[-1][0]}.html"
    named = page.name
    if bad == "a named pipe":  # read, it would never end
        page.unlink()
        os.mkfifo(page)
    elif bad == "not UTF-8":
        page.write_bytes(b"<html>\xff\xfe</html>")
    elif bad == "a folder":
        page.unlink()
        page.mkdir()
    elif bad == "a figure outside":  # the decks would carry a copy of any file
        page.write_text(page.read_text().replace("../_images/figure.png", "../../file.txt"))
        named = "../../file.txt"
    else:
        page.write_text(page.read_text().replace("<h1>", "<h2>").replace("</h1>", "</h2>"))
    for command in (("slides", "HTML", "--out", "s"), ("lms", "HTML", "--out", "q.xml")):
        if bad in ("a figure outside", "no title") and command[0] == "lms":
            continue  # (the questions need neither)
        before = tree(workshop)
        result = course(monkeypatch, capsys, workshop, *command)
        assert_refused(result, named)
        assert tree(workshop) == before  # a failed run leaves no folder


# --- what must be accepted, and what it replaces ----------------------------------------------

def test_lms_replaces_its_own_export_and_someone_elses_only_with_force(
        workshop, monkeypatch, capsys):
    status, out, _ = course(monkeypatch, capsys, workshop, "lms", "HTML", "--out", "q.xml")
    assert status == 0 and "8 questions" in out
    first = (workshop / "q.xml").read_text()
    assert first.startswith(f"{lms.DECLARATION}\n{lms.SIGNATURE}\n")
    assert lms.is_export(workshop / "q.xml") and not lms.is_export(workshop / "foreign.xml")
    (workshop / "q.xml").write_text(first.replace("Look again.", "stale"))
    before = tree(workshop)
    status, _, _ = course(monkeypatch, capsys, workshop, "lms", "HTML", "--out", "q.xml")
    assert status == 0 and (workshop / "q.xml").read_text() == first  # its own: replaced
    changed = {path for path in set(before) | set(tree(workshop))
               if before.get(path) != tree(workshop).get(path)}
    assert changed == {str(workshop / "q.xml")}
    status, _, _ = course(monkeypatch, capsys, workshop, "lms", "HTML", "--out", "foreign.xml",
                          "--force")
    assert status == 0 and (workshop / "foreign.xml").read_text() == first
    assert not [p for p in workshop.iterdir() if p.name.startswith(".")]  # no temporary


def test_slides_replace_their_own_decks_and_keep_someone_elses_files_with_force(
        workshop, monkeypatch, capsys):
    status, out, _ = course(monkeypatch, capsys, workshop, "slides", "HTML", "--out", "s")
    assert status == 0 and "8 decks" in out
    assert files.is_ours(workshop / "s", slides.COMMAND)
    first = tree(workshop / "s")
    (workshop / "s" / "stale.html").write_text("a deck of a chapter since removed")
    status, _, _ = course(monkeypatch, capsys, workshop, "slides", "HTML", "--out", "s")
    assert status == 0 and tree(workshop / "s") == first  # replaced whole, nothing left over
    status, _, _ = course(monkeypatch, capsys, workshop, "slides", "HTML", "--out", "other",
                          "--force")
    assert status == 0 and (workshop / "other" / "keep.txt").read_text() == "someone else's"
    assert (workshop / "other" / "index.html").exists()
    assert files.is_ours(workshop / "other", slides.COMMAND)
    empty = workshop / "empty"
    empty.mkdir()  # an empty folder: taken without --force
    assert course(monkeypatch, capsys, workshop, "slides", "HTML", "--out", "empty")[0] == 0


def test_a_failed_slides_run_leaves_the_earlier_decks_whole(workshop, monkeypatch, capsys):
    assert course(monkeypatch, capsys, workshop, "slides", "HTML", "--out", "s")[0] == 0
    before = tree(workshop)
    page = workshop / "HTML" / "book" / f"{assign.chapters()[-1][0]}.html"
    page.write_text(page.read_text().replace("<h1>", "<h2>").replace("</h1>", "</h2>"))
    page_after = tree(page)
    result = course(monkeypatch, capsys, workshop, "slides", "HTML", "--out", "s")
    assert_refused(result, "no title")
    assert tree(workshop) == {**before, **page_after}


@pytest.fixture(scope="module")
def earlier_assignment(tmp_path_factory):
    """An assignment of one chapter written by an earlier run (seed 7), and its tree."""
    out = tmp_path_factory.mktemp("earlier") / "assignments"
    assign.assign(out, seed=7, names=[CHAPTER], run_tests=False, progress=lambda _: None)
    return out


def _copy(source, target):
    import shutil

    shutil.copytree(source, target, symlinks=True)
    return target


def test_assign_takes_its_own_folder_keeps_other_chapters_and_a_seed_of_0(
        earlier_assignment, tmp_path, monkeypatch, capsys):
    out = _copy(earlier_assignment, tmp_path / "assignments")
    kept = tree(out / CHAPTER)
    status, printed, _ = course(monkeypatch, capsys, tmp_path, "assign", "assignments",
                                "--chapters", OTHER_CHAPTER, "--no-run-tests", "--seed", "0")
    assert status == 0 and "1 assignments" in printed
    assert tree(out / CHAPTER) == kept  # the chapter not written is as it was
    student = out / OTHER_CHAPTER / "student" / f"{OTHER_CHAPTER}.ipynb"
    assert nbformat.read(student, as_version=4).metadata["otter"]["assignment_name"] == \
        OTHER_CHAPTER
    # A seed of one digit: the leak check looks for the chapter's seed, drawn from it.
    tests = "".join(path.read_text() for path in
                    (out / OTHER_CHAPTER / "autograder").glob("**/*.ipynb"))
    assert f"seed = {assign.chapter_seed(0, OTHER_CHAPTER)}" in tests
    assert sorted(p.name for p in out.iterdir()) == sorted([CHAPTER, OTHER_CHAPTER, files.MARKER])
    assert grade.load_assignments(out).keys() == {CHAPTER, OTHER_CHAPTER}


def test_assign_writes_into_someone_elses_folder_only_with_force(
        tmp_path, monkeypatch, capsys):
    other = tmp_path / "other"
    other.mkdir()
    (other / "keep.txt").write_text("someone else's")
    before = tree(tmp_path)
    assert_refused(course(monkeypatch, capsys, tmp_path, "assign", "other", *ASSIGN), "other")
    assert tree(tmp_path) == before
    status, _, _ = course(monkeypatch, capsys, tmp_path, "assign", "other", *ASSIGN,
                          "--force")
    assert status == 0 and (other / "keep.txt").read_text() == "someone else's"
    assert files.is_ours(other, assign.COMMAND)
    assert (other / CHAPTER / "autograder" / grade.MANIFEST).exists()


def _failing_chapters(monkeypatch, fail_on):
    """assign_chapter replaced by one that writes a small folder, and raises on the
    chapter `fail_on` (after the others are written)."""
    def write(name, path, out, seed, root=assign.ROOT):
        folder = pathlib.Path(out) / name / "student"
        folder.mkdir(parents=True)
        (folder / f"{name}.ipynb").write_text("{}")
        if name == fail_on:
            raise assign.AssignError(f"{name}: broken on purpose")
        return folder.parent
    monkeypatch.setattr(assign, "assign_chapter", write)


def test_a_failed_assign_leaves_the_earlier_assignment_whole_and_no_half_written_folder(
        earlier_assignment, tmp_path, monkeypatch):
    out = _copy(earlier_assignment, tmp_path / "assignments")
    before = tree(tmp_path)
    _failing_chapters(monkeypatch, fail_on=OTHER_CHAPTER)
    for folder in (out, tmp_path / "new" / "assignments"):
        with pytest.raises(assign.AssignError, match="broken on purpose"):
            assign.assign(folder, seed=0, names=[CHAPTER, OTHER_CHAPTER], run_tests=False,
                          progress=lambda _: None)
        assert tree(tmp_path) == before  # the new folder (and its parent) not left
    # The solutions failing their tests: the same.
    monkeypatch.undo()
    _failing_chapters(monkeypatch, fail_on=None)

    def solutions_fail(*_):
        raise assign.AssignError("the solutions fail their own tests: on purpose")
    monkeypatch.setattr(assign, "check_solutions", solutions_fail)
    with pytest.raises(assign.AssignError, match="on purpose"):
        assign.assign(out, seed=0, names=[CHAPTER], progress=lambda _: None)
    assert tree(tmp_path) == before


# --- killed half-way ---------------------------------------------------------------------------

KILLED_RUN = """
import pathlib, sys, time
from icm import files

folder = pathlib.Path(sys.argv[1])
with files.staged(folder) as staging:
    (staging / "chapter").mkdir()
    (staging / "chapter" / "new.txt").write_text("new")
    (staging / "ready").write_text("")
    time.sleep(60)
"""


def test_a_run_killed_half_way_leaves_the_old_output_whole_and_the_next_run_tidies(tmp_path):
    folder = tmp_path / "out"
    with files.staged(folder) as staging:
        (staging / "chapter").mkdir()
        (staging / "chapter" / "old.txt").write_text("old")
    before = tree(folder)
    process = subprocess.Popen([sys.executable, "-c", KILLED_RUN, str(folder)])
    try:
        deadline = time.monotonic() + 60
        while not list(folder.glob(f"{files.STAGING_PREFIX}*/ready")):
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.05)
    finally:
        process.send_signal(signal.SIGKILL)
        process.wait()
    left = tree(folder)
    assert {path: entry for path, entry in left.items()
            if files.STAGING_PREFIX not in path} == before  # the old output whole
    # Killed between the two renames of a folder's replacement: the old one aside.
    aside = folder / f"{files.ASIDE_PREFIX}0123abcd.chapter"
    (folder / "chapter").rename(aside)
    with files.staged(folder) as staging:  # the next run tidies, then writes
        assert (folder / "chapter" / "old.txt").read_text() == "old"  # put back
        assert list(folder.glob(f"{files.STAGING_PREFIX}*")) == [staging]
        (staging / "chapter").mkdir()
        (staging / "chapter" / "new.txt").write_text("new")
    assert sorted(p.name for p in folder.iterdir()) == sorted(["chapter", files.MARKER])
    assert [p.name for p in (folder / "chapter").iterdir()] == ["new.txt"]


def test_a_file_is_replaced_whole_or_not_at_all(tmp_path, monkeypatch):
    target = tmp_path / "q.xml"
    target.write_text("old")

    def fails(descriptor):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(os, "fsync", fails)
    with pytest.raises(OSError, match="No space"):
        files.write_text(target, "new " * 1000)
    assert target.read_text() == "old" and [p.name for p in tmp_path.iterdir()] == ["q.xml"]


def test_replacing_a_link_never_touches_what_it_points_to(tmp_path):
    target = tmp_path / "target"
    target.mkdir()
    (target / "precious.txt").write_text("keep")
    folder = tmp_path / "out"
    with files.staged(folder):
        pass
    (folder / "chapter").symlink_to(target)
    with files.staged(folder) as staging:
        (staging / "chapter").mkdir()
    assert (target / "precious.txt").read_text() == "keep"
    assert not (folder / "chapter").is_symlink() and (folder / "chapter").is_dir()


# --- what is read back --------------------------------------------------------------------------

def test_a_file_read_back_is_a_bounded_regular_file_named_in_every_error(tmp_path, deadline):
    os.mkfifo(tmp_path / "pipe.json")
    (tmp_path / "big.json").write_bytes(b" " * 2049)
    (tmp_path / "latin.html").write_bytes(b"caf\xe9")
    for path, message in ((tmp_path / "pipe.json", "not a file"),
                          (tmp_path, "not a file but a folder"),
                          (tmp_path / "none.json", "does not exist"),
                          (tmp_path / "big.json", "larger than")):
        with pytest.raises(records.RecordError, match=message) as raised:
            records.read_bytes(path, limit=2048)
        assert str(path) in str(raised.value)
    with pytest.raises(records.RecordError, match="latin.html: not UTF-8"):
        records.read_text(tmp_path / "latin.html")
    with pytest.raises(records.RecordError, match="is not a folder"):
        records.input_folder(tmp_path / "latin.html", "the built book's folder")


def test_assign_checks_its_manifest_with_the_graders_model(monkeypatch, tmp_path):
    # What assign writes, the grader reads with the same model: a manifest the model
    # refuses is never written.
    real = assign.manifest
    monkeypatch.setattr(assign, "manifest", lambda name, path: {**real(name, path),
                                                                "number": -1})
    before = tree(tmp_path)
    with pytest.raises(records.RecordError, match=f"{CHAPTER}'s manifest: number"):
        assign.assign(tmp_path / "a", seed=0, names=[CHAPTER], run_tests=False,
                      progress=lambda _: None)
    assert tree(tmp_path) == before  # refused before any work


def test_an_error_of_the_system_is_one_line_too(workshop, monkeypatch, capsys):
    def disk_full(*_, **__):
        raise OSError(28, "No space left on device", "q.xml")
    monkeypatch.setattr(lms, "export_moodle", disk_full)
    assert_refused(course(monkeypatch, capsys, workshop, "lms", "HTML", "--out", "q.xml"),
                   "q.xml: No space left on device")


def test_the_one_line_of_an_error():
    assert course_cli.one_line(FileNotFoundError(2, "No such file or directory", "x.csv")) == \
        "x.csv: No such file or directory"
    assert course_cli.one_line(ValueError("first\n  second\n")) == "first; second"
    assert course_cli.one_line(ValueError("")) == "ValueError"


def test_a_fresh_folder_empties_only_this_commands_own_folder(tmp_path):
    ours = files.fresh_folder(tmp_path / "ours", command="student_edition")
    assert files.marker_command(ours) == "student_edition"
    (ours / "old.txt").write_text("from an earlier run")
    (ours / "sub").mkdir()
    (ours / "sub" / "deep.txt").write_text("deeper")
    (tmp_path / "kept.txt").write_text("beside it")
    (ours / "link").symlink_to(tmp_path / "kept.txt")
    files.fresh_folder(ours, command="student_edition")
    assert sorted(p.name for p in ours.iterdir()) == [files.MARKER]
    assert (tmp_path / "kept.txt").read_text() == "beside it"  # a link removed, not followed
    # Another command's folder, or one of nobody's, keeps its files (it gains the marker).
    theirs = files.fresh_folder(tmp_path / "theirs", command="slides")
    (theirs / "deck.html").write_text("slides")
    files.fresh_folder(theirs, command="student_edition")
    assert (theirs / "deck.html").read_text() == "slides"
    assert files.marker_command(theirs) == "student_edition"
    plain = tmp_path / "plain"
    plain.mkdir()
    (plain / "notes.txt").write_text("mine")
    files.fresh_folder(plain)
    assert (plain / "notes.txt").read_text() == "mine" and files.is_ours(plain)


def test_a_file_whose_owner_cannot_be_read_is_not_the_commands(tmp_path):
    out = tmp_path / "grades.csv"
    out.write_text("id,name\n")

    def unreadable(path):
        raise OSError(13, "Permission denied")

    with pytest.raises(files.DestinationError, match="was not written by this command"):
        files.check_file(out, own=unreadable)
    assert files.check_file(out, own=lambda path: True) == out


@pytest.mark.parametrize("before", ["none", "made", "unmarked", "another command's"])
def test_a_staged_write_that_fails_leaves_the_folder_as_it_was(tmp_path, before):
    folder = tmp_path / "a" / "out"
    if before == "made":
        files.fresh_folder(folder, command="slides")
    elif before != "none":
        folder.mkdir(parents=True)
        (folder / "theirs.txt").write_text("kept")
        if before == "another command's":
            files.fresh_folder(folder, command="grade")
    state = lambda: sorted((str(p.relative_to(tmp_path)), p.read_bytes() if p.is_file()
                            else None) for p in tmp_path.rglob("*"))
    was = state()
    with pytest.raises(RuntimeError, match="half-way"):
        with files.staged(folder, command="slides") as staging:
            (staging / "deck.html").write_text("half a deck")
            (staging / "sub").mkdir()
            (staging / "sub" / "x").write_text("x")
            raise RuntimeError("stopped half-way")
    assert state() == was
    if before == "none":
        assert not (tmp_path / "a").exists()  # the folders made for it removed too


def test_each_refused_destination_says_exactly_why(tmp_path):
    def refusal(call):
        with pytest.raises(files.DestinationError) as error:
            call()
        return str(error.value)

    source = tmp_path / "subs"
    source.mkdir()
    (source / "a.ipynb").write_text("{}")
    assert refusal(lambda: files.check_folder(source, inputs=[source], what="--feedback")) \
        == f"--feedback {source} is the input {source}: choose a destination outside it"
    inner = source / "out"
    assert refusal(lambda: files.check_folder(inner, inputs=[source], what="--feedback")) \
        == f"--feedback {inner} is inside the input {source}: choose a destination outside it"
    assert refusal(lambda: files.check_folder(tmp_path, inputs=[source], what="--out")) \
        == f"--out {tmp_path} holds the input {source}: choose a destination that does not"
    assert refusal(lambda: files.check_file(source / "g.csv", inputs=[source], what="--out")) \
        == f"--out {source / 'g.csv'} is inside the input {source}: choose a destination " \
           f"outside it"
    ending = "is not empty and {}: choose another folder, or pass --force"
    theirs = tmp_path / "theirs"
    theirs.mkdir()
    (theirs / "notes.txt").write_text("mine")
    assert refusal(lambda: files.check_folder(theirs, what="--out")) == \
        f"--out {theirs} exists, " + ending.format(f"was not written by icm (it has no "
                                                   f"{files.MARKER})")
    slides = files.fresh_folder(tmp_path / "slides", command="slides")
    (slides / "deck.html").write_text("a deck")
    assert refusal(lambda: files.check_folder(slides, what="--out", command="grade")) == \
        f"--out {slides} exists, " + ending.format("was written by slides, not by this command")
    plain = files.fresh_folder(tmp_path / "plain")
    (plain / "x").write_text("x")
    assert refusal(lambda: files.check_folder(plain, what="--out", command="grade")) == \
        f"--out {plain} exists, " + ending.format("was written by another of icm's commands")
    # A file on the way there, and a read-only folder, named with the destination.
    (tmp_path / "a_file").write_text("x")
    assert refusal(lambda: files.check_file(tmp_path / "a_file" / "g.csv", what="--out")) \
        == f"--out {tmp_path / 'a_file' / 'g.csv'}: {tmp_path / 'a_file'} is a file, not a folder"


def test_a_marker_is_read_only_from_a_small_regular_file_that_starts_as_ours(tmp_path):
    folder = files.fresh_folder(tmp_path / "out", command="slides")
    assert files.marker_command(folder) == "slides"
    marker = folder / files.MARKER
    marker.write_text(files.marker_text("slides") + "x" * (4096 - len(
        files.marker_text("slides").encode())))
    assert marker.stat().st_size == 4096 and files.marker_command(folder) == "slides"
    marker.write_text(marker.read_text() + "x")  # 4097 bytes: not a marker
    assert files.marker_command(folder) is None
    marker.write_text("Signature: something else\nCommand: slides\n")
    assert files.marker_command(folder) is None
    marker.unlink()
    (tmp_path / "elsewhere").write_text(files.marker_text("slides"))
    marker.symlink_to(tmp_path / "elsewhere")
    assert files.marker_command(folder) is None
