"""The grader attacked a second time (issue 42's red team): what tests/test_grading_attacks.py
does not try. Each attack is a short notebook, graded confined beside honest notebooks
that give the same wrong answers without the attack. What each test asks of the grader:

- nothing a notebook returns, raises, prints or sends on the channel stops the run: the
  grade sheet and every feedback file are written (an answer too large for a float, an
  error raised where a check does not expect one, a default the grader cannot read, a
  notebook too large for the channel, a runner that stops reading its requests, a
  message the feedback cannot encode);
- nothing in the submissions' folder stops it either (a file name that is not UTF-8,
  a long name, a named pipe);
- a submission cannot change another's row or feedback (a name that folds to another's,
  a name whose feedback file is another's);
- nothing one submission leaves behind reaches the next (the kernel's keyring of the
  user the submissions run as);
- a submission cannot take the machine's processor from the one graded beside it;
- neither a reply the channel accepts nor a notebook the grader reads costs the grader
  gigabytes of its own memory;
- what a notebook says reaches the instructor as text: no Markdown or HTML of its own in
  the feedback, no terminal control characters in the progress lines.

The chapters' assignments are written here by hand, in the two files the grader reads
(`icm.course.grade.load_assignments`: the manifest and the student's notebook), so that
these tests need no otter run. Every notebook runs confined (never `trusted`); the
runs the hang test must set free are killed by their process ids (this process's own
runs, found by `sandbox.GRADER`), and a module fixture checks that none is left.
"""

import contextlib
import csv
import json
import os
import pathlib
import re
import secrets
import subprocess
import sys
import threading
import time

import nbformat
import psutil
import pytest

from grading_support import ROOT, SOLUTIONS, WRONG

from icm import records
from icm.course import grade, runner, sandbox

CONFINED = sandbox.probe()
pytestmark = pytest.mark.skipif(not CONFINED.available,
                                reason=f"no confinement here: {CONFINED.problem}")

CHAPTERS = {
    "goal_oriented_interest": (2, "Goal-oriented interest", [
        ("ex-least-squares-slope", "2.1", "the least-squares slope",
         "def least_squares_slope(values):"),
        ("ex-task-interest", "2.2", "the interest of a task",
         "def task_interest(history, others, window=5, new_task_factor=0.5):")]),
    "curiosity": (7, "Which curiosity?", [
        ("ex-curiosity-signal", "7.1", "a curiosity of your own",
         "def my_interest(history):")]),
    "forming_actions": (8, "Forming actions", [
        ("ex-goal-choice", "8.1", "the goal-choice rule",
         "def choose_region(interests, epsilon, rng):")]),
}
"""The chapters graded here: (number, title, [(label, number, title, definition)])."""
SETUP = ("import numpy as np\nimport otter\n\ngrader = otter.Notebook(\"{chapter}.ipynb\")\n")
"""The setup cell of a student's notebook (the grader replaces it)."""
OPTIONS = {"jobs": 2, "memory_limit": 1.0, "time_limit": 60, "cell_timeout": 10}
"""How the classes are graded: two at once, small limits."""
UNIFORM = ("def choose_region(interests, epsilon, rng):\n"
           "    return int(rng.integers(len(interests)))\n")
"""A wrong goal-choice rule: uniform whatever the interests."""
LENGTH = "def my_interest(history):\n    return float(len(history))\n"
"""A curiosity signal that meets the contract: the number of errors seen."""


def _write_assignments(folder):
    """The chapters' assignments, as `icm.course.assign` writes the files the grader
    reads: the manifest and the student's notebook (setup, answer cells tagged
    otter_answer_cell holding a placeholder, a check cell after each)."""
    for chapter, (number, title, exercises) in CHAPTERS.items():
        manifest = records.Manifest(chapter=chapter, number=number, title=title, exercises=[
            records.ManifestExercise(label=label, title=name, number=numbered,
                                     kind="implement", points=10,
                                     function=definition[4:].split("(")[0])
            for label, numbered, name, definition in exercises])
        autograder = folder / chapter / "autograder"
        autograder.mkdir(parents=True)
        (autograder / grade.MANIFEST).write_text(manifest.model_dump_json(indent=1))
        cells = [nbformat.v4.new_code_cell(SETUP.format(chapter=chapter))]
        for label, _, _, definition in exercises:
            answer = nbformat.v4.new_code_cell(
                f"{definition}\n    # Your code here.\n    raise NotImplementedError")
            answer.metadata["tags"] = ["otter_answer_cell"]
            cells += [answer, nbformat.v4.new_code_cell(f'grader.check("{label}")')]
        notebook = nbformat.v4.new_notebook(cells=cells)
        notebook.metadata["otter"] = {"assignment_name": chapter}
        student = folder / chapter / "student"
        student.mkdir(parents=True)
        nbformat.write(notebook, student / f"{chapter}.ipynb")
    return folder


@pytest.fixture(scope="module")
def tiny_assignments(tmp_path_factory):
    return _write_assignments(tmp_path_factory.mktemp("redteam-assignments"))


def _notebook(folder, filename, answers=None, extra=(), chapter="goal_oriented_interest",
              last=()):
    """Writes a submission named `filename` in `folder`: the student's notebook of
    `chapter` with its answer cells replaced by `answers` ({function: source}; a
    function not given keeps its placeholder), the cells `extra` after the setup cell
    and `last` at the end. Returns its path."""
    answers = dict(answers or {})
    number, title, exercises = CHAPTERS[chapter]
    cells = [nbformat.v4.new_code_cell(SETUP.format(chapter=chapter))]
    cells += [nbformat.v4.new_code_cell(source) for source in extra]
    for label, _, _, definition in exercises:
        function = definition[4:].split("(")[0]
        answer = nbformat.v4.new_code_cell(answers.get(function, (
            f"{definition}\n    # Your code here.\n    raise NotImplementedError")))
        answer.metadata["tags"] = ["otter_answer_cell"]
        cells += [answer, nbformat.v4.new_code_cell(f'grader.check("{label}")')]
    cells += [nbformat.v4.new_code_cell(source) for source in last]
    notebook = nbformat.v4.new_notebook(cells=cells)
    notebook.metadata["otter"] = {"assignment_name": chapter}
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / filename
    nbformat.write(notebook, path)
    return path


def _grade(folder, assignments, **options):
    """Grades a folder confined; fails the test, saying so, when grading raises (then
    no grade sheet is written for anyone). Returns (results by file, sheet rows by
    file, the feedback folder, the progress lines)."""
    folder = pathlib.Path(folder)
    sheet = folder.parent / f"{folder.name}-grades.csv"
    lines = []
    try:
        results = grade.grade(folder, sheet, assignments=assignments, progress=lines.append,
                              **{**OPTIONS, **options})
    except Exception as error:  # noqa: BLE001 (the test reports what stopped the run)
        pytest.fail(f"grading the class raised {type(error).__name__} ({str(error)[:300]}): "
                    + ("the grade sheet was written, the feedback files not all"
                       if sheet.exists() else "no grade sheet was written, for any student"))
    with open(sheet, newline="", encoding="utf-8") as file:
        table = {row["submission"]: row for row in csv.DictReader(file)}
    return ({r.submission: r for r in results}, table,
            sheet.parent / f"{sheet.stem}-feedback", lines)


def _points(row):
    return {key: float(value) for key, value in row.items()
            if key.startswith("ex-") and value not in ("", None)}


def _assert_gains_nothing(table, attack, honest="a_honest.ipynb", again="z_honest.ipynb"):
    """The attack's points are at most the honest notebook's (the same answers), and
    the honest rows, graded before and after it, are the same."""
    for label, points in _points(table[attack]).items():
        assert points <= _points(table[honest])[label], (attack, label, points)
    if again:
        assert _points(table[again]) == _points(table[honest])
        assert not table[honest]["problem"] and not table[again]["problem"]


def _feedback_files(feedback):
    """{the submission a feedback file is about: its file's name}."""
    found = {}
    for path in feedback.glob("*.md"):
        first = path.read_text(encoding="utf-8").splitlines()[0]
        found[first.removeprefix("# Feedback: ")] = path.name
    return found


def _confined_processes():
    """The processes of runs this test process graded that are still alive."""
    return [process for process in psutil.process_iter(["environ"])
            if (process.info["environ"] or {}).get(sandbox.GRADER) == str(os.getpid())]


@contextlib.contextmanager
def _in_a_thread(function):
    """Runs `function` in a thread; yields a dict that gets "result" (or "error") when it
    ends."""
    outcome = {}

    def target():
        try:
            outcome["result"] = function()
        except BaseException as error:  # noqa: BLE001 (reported by the test)
            outcome["error"] = error
    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    outcome["thread"] = thread
    yield outcome


# --- what a notebook returns or raises ---------------------------------------------------

def test_an_answer_too_large_for_a_float_costs_its_own_points_only(tiny_assignments,
                                                                    tmp_path):
    """`close` turns the answer into a float; 10 ** 400 overflows (OverflowError, which
    no caller catches)."""
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, "m_huge_int.ipynb", {
        **WRONG, "least_squares_slope": "def least_squares_slope(values):\n"
                                        "    return 10 ** 400\n"})
    _notebook(folder, "z_honest.ipynb", WRONG)
    _, table, feedback, _ = _grade(folder, tiny_assignments)
    _assert_gains_nothing(table, "m_huge_int.ipynb")
    assert len(_feedback_files(feedback)) == 3


GENERATOR_CASE_RAISES = '''import sys


class Boom(Exception):
    pass


def choose_region(interests, epsilon, rng):
    frame = sys._getframe(1)
    while frame is not None and "times" not in frame.f_locals:
        frame = frame.f_back
    if frame is not None and frame.f_locals["times"] == 40:  # the generator's case
        raise Boom("raised where the check does not catch it")
    return int(rng.integers(len(interests)))
'''
"""A uniform rule that raises in the goal-choice check's last case (40 draws from one
generator), which `_generator_verdict` runs outside any `try`."""
SECOND_LOOK_RAISES = '''seen = set()


class Boom(Exception):
    pass


def my_interest(history):
    if tuple(history) in seen:  # the check's second look at the same history
        raise Boom("raised where the check does not catch it")
    seen.add(tuple(history))
    return float(len(history))
'''
"""A curiosity signal that raises when the check calls it a second time on the same
history (`signal_verdict`'s determinism pass, outside any `try`)."""


@pytest.mark.parametrize("chapter, honest, attack", [
    ("forming_actions", {"choose_region": UNIFORM}, {"choose_region": GENERATOR_CASE_RAISES}),
    ("curiosity", {"my_interest": LENGTH}, {"my_interest": SECOND_LOOK_RAISES}),
], ids=["goal-choice generator case", "curiosity second look"])
def test_an_error_raised_where_a_check_does_not_expect_one_costs_its_own_points_only(
        tiny_assignments, tmp_path, chapter, honest, attack):
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", honest, chapter=chapter)
    _notebook(folder, "m_raises.ipynb", attack, chapter=chapter)
    _notebook(folder, "z_honest.ipynb", honest, chapter=chapter)
    _, table, feedback, _ = _grade(folder, tiny_assignments)
    _assert_gains_nothing(table, "m_raises.ipynb")
    assert len(_feedback_files(feedback)) == 3


FORGED_DEFAULT = '''import sys

runner = sys.modules["__main__"]  # the runner program, which the notebook may change
runner._plain_default = lambda value: {"$generator": {
    "bit_generator": "MT19937", "state": {"key": [1, 2, 3], "pos": 0}}}
'''
"""A description of the functions whose default decodes to an IndexError in the grader
(`runner.decode` lets NumPy's errors through; `Session.function` catches only
WireError, TypeError and ValueError)."""


def test_a_description_the_grader_cannot_decode_costs_its_own_row_only(tiny_assignments,
                                                                       tmp_path):
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, "m_forged_default.ipynb", WRONG, [FORGED_DEFAULT])
    _notebook(folder, "z_honest.ipynb", WRONG)
    _, table, _, _ = _grade(folder, tiny_assignments)
    _assert_gains_nothing(table, "m_forged_default.ipynb")


def test_every_generator_state_the_channel_carries_decodes_or_is_refused():
    """What `runner.decode` must do with any generator state a runner sends: decode it or
    raise WireError (no other error, which the grader's callers would not catch)."""
    states = [
        {"bit_generator": "MT19937", "state": {"key": [1, 2, 3], "pos": 0}},
        {"bit_generator": "PCG64", "state": {"state": -1, "inc": 1}, "has_uint32": 0,
         "uinteger": 0},
        {"bit_generator": "PCG64", "state": {"state": 2 ** 300, "inc": 1}, "has_uint32": 0,
         "uinteger": 0},
        {"bit_generator": "Philox", "state": {"counter": [1], "key": [2]}, "buffer": [1],
         "buffer_pos": 0, "has_uint32": 0, "uinteger": 0},
        {"bit_generator": "SFC64", "state": {"state": [2 ** 70, 2, 3, 4]}, "has_uint32": 0,
         "uinteger": 0},
    ]
    escaped = []
    for state in states:
        try:
            runner.decode({"$generator": state})
        except runner.WireError:
            continue
        except Exception as error:  # noqa: BLE001 (what the test is about)
            escaped.append((state["bit_generator"], type(error).__name__))
    assert escaped == []


def test_a_notebook_too_large_for_the_channel_costs_its_own_row_only(tiny_assignments,
                                                                     tmp_path):
    """A 6 MiB notebook whose cells, escaped as JSON (an emoji takes 12 bytes), make a
    job longer than `runner.MAX_LINE`: the runner refuses it, and the grader's `send`
    raises `sandbox.Ended` outside the `try` of `Session._start`."""
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, "m_large.ipynb", WRONG, ["# " + "\U0001F600" * 1_500_000 + "\n"])
    _notebook(folder, "z_honest.ipynb", WRONG)
    assert (folder / "m_large.ipynb").stat().st_size < records.MAX_JSON_BYTES
    _, table, _, _ = _grade(folder, tiny_assignments)
    _assert_gains_nothing(table, "m_large.ipynb")
    assert table["m_large.ipynb"]["problem"]


HANG = '''import fcntl
import sys

runner = sys.modules["__main__"]


def serve_without_reading(program, namespace):
    fcntl.fcntl(program.inbox.fileno(), 1031, 4096)  # F_SETPIPE_SZ: a page of requests
    for call in range(1, 10 ** 6):  # answers before the calls: the grader keeps calling
        program.send({"id": call, "value": 0.0, "args": []})


runner._serve = serve_without_reading
'''
"""A runner that answers every call in advance and never reads a request: the grader's
requests fill the pipe, and its blocking `send` waits for ever (no deadline applies)."""


def test_a_runner_that_stops_reading_cannot_hang_the_grader(tiny_assignments, tmp_path):
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, "m_hang.ipynb", WRONG, [HANG])
    limit = 8  # seconds for each submission
    with _in_a_thread(lambda: _grade(folder, tiny_assignments, time_limit=limit)) as run:
        run["thread"].join(3 * limit)
        hung = run["thread"].is_alive()
        if hung:  # set the grader free: end the run's processes (this process's own)
            for process in _confined_processes():
                with contextlib.suppress(psutil.Error):
                    process.kill()
            run["thread"].join(60)
    assert not hung, (f"grading had not ended {3 * limit} s after it started, with a time "
                      f"limit of {limit} s per submission: the grader waited for ever")
    if "error" in run:
        raise run["error"]
    _, table, _, _ = run["result"]
    _assert_gains_nothing(table, "m_hang.ipynb", again=None)


def test_a_message_the_feedback_cannot_encode_costs_nobody_their_feedback(tiny_assignments,
                                                                          tmp_path):
    """A cell's error text with a lone surrogate (JSON carries it, UTF-8 cannot): the
    sheet is written, then writing the feedback raises UnicodeEncodeError."""
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, "m_surrogate.ipynb", WRONG, ["raise ValueError('\\ud800')\n"])
    _notebook(folder, "z_honest.ipynb", WRONG)
    _, table, feedback, _ = _grade(folder, tiny_assignments)
    _assert_gains_nothing(table, "m_surrogate.ipynb")
    assert sorted(_feedback_files(feedback)) == sorted(table)


def _grown(folder, out, assignments):
    """How much the grader's memory grows while it grades `folder` (one notebook), in
    bytes, measured in a process of its own (grading an honest notebook there grows it
    by nothing), and what the grader said of the notebook's first case (or of the
    notebook, if no case ran)."""
    script = (
        "import json, resource, sys\n"
        "from icm.course import grade\n"
        "before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
        "graded, = grade.grade(sys.argv[1], sys.argv[2], assignments=sys.argv[3],\n"
        "                      memory_limit=2.0, time_limit=60, cell_timeout=10,\n"
        "                      progress=lambda _: None)\n"
        "after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
        "said = [case.message for grade in graded.exercises.values()\n"
        "        for test in grade.tests for case in test.cases][:1] or [graded.problem]\n"
        "print(json.dumps({'grown': (after - before) * 1024, 'said': said[0]}))\n")
    done = subprocess.run([sys.executable, "-c", script, str(folder), str(out),
                           str(assignments)], capture_output=True, text=True, cwd=ROOT,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    measured = json.loads(done.stdout.splitlines()[-1])
    return measured["grown"], measured["said"]


BLOAT = f'''import sys

runner = sys.modules["__main__"]
plain_encode = runner.encode
EMPTY_LISTS = [[]] * ({runner.MAX_LINE} // 12)  # "[]," each: a quarter of a line's most
runner.encode = lambda value, depth=0: (  # sent as it is (no time spent encoding it)
    value if value is EMPTY_LISTS else plain_encode(value, depth))
SENT = []


def least_squares_slope(values):
    if SENT:
        return 0.0
    SENT.append(True)
    return EMPTY_LISTS
'''
"""An answer, once, of empty lists: a quarter of the bytes a reply may hold."""


def test_a_reply_the_channel_accepts_cannot_cost_the_grader_gigabytes(tiny_assignments,
                                                                      tmp_path):
    """A reply of empty lists, a quarter of `runner.MAX_LINE` (4 MiB): about 50 bytes of
    the grader's memory for each byte of it, in `runner.loads`, `runner.decode` and the
    report's copy (`_core.show`); a reply of the whole line took 780 MiB and 12 s of the
    grader's processor (the grader has no memory limit of its own, and `jobs` replies
    are decoded at once)."""
    folder = tmp_path / "class"
    _notebook(folder, "m_bloat.ipynb", {**WRONG, "least_squares_slope": BLOAT})
    grown, said = _grown(folder, tmp_path / "grades.csv", tiny_assignments)
    if "given: [[]" not in said and "could not be read" not in said:
        pytest.skip(f"inconclusive: the reply did not reach the grader on this machine, "
                    f"which is too slow now ({said[:200]})")
    assert grown < 64 * 2 ** 20, f"the grader grew by {grown / 2 ** 20:.0f} MiB"


def test_a_notebook_the_grader_reads_cannot_cost_it_gigabytes(tiny_assignments, tmp_path):
    """A notebook of `records.MAX_JSON_BYTES` (64 MiB, the most a notebook may be) whose
    metadata holds empty lists: `json.loads` makes 22 million lists of it, 1.5 GB of the
    grader's memory and 6 s of its processor, before anything is confined (and `jobs`
    notebooks are read at once)."""
    folder = tmp_path / "class"
    folder.mkdir()
    lists = (records.MAX_JSON_BYTES - 200) // 3
    (folder / "m_nested.ipynb").write_bytes(
        b'{"cells": [], "metadata": {"otter": {"assignment_name": "goal_oriented_interest"},'
        b' "lists": [' + b"[]," * (lists - 1) + b"[]]}}")
    grown, _ = _grown(folder, tmp_path / "grades.csv", tiny_assignments)
    assert grown < 256 * 2 ** 20, f"the grader grew by {grown / 2 ** 20:.0f} MiB"


# --- the submissions' folder --------------------------------------------------------------

def test_a_file_name_that_is_not_utf8_costs_its_own_row_only(tiny_assignments, tmp_path):
    """A name in Latin-1 (a zip made on Windows): Python reads it with a surrogate,
    which the sheet's UTF-8 cannot write."""
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, os.fsdecode(b"Jos\xe9.ipynb"), WRONG)
    _, table, feedback, _ = _grade(folder, tiny_assignments)
    assert len(table) == 2 and len(_feedback_files(feedback)) == 2
    assert _points(table["a_honest.ipynb"]) == next(
        _points(row) for name, row in table.items() if name != "a_honest.ipynb")


def test_a_long_file_name_gets_its_feedback(tiny_assignments, tmp_path):
    """A 246-character name (the system allows 255): its feedback's temporary file,
    `.<name>.md.<8 characters>.part`, is longer than a file name may be."""
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    long_name = "x" * 240 + ".ipynb"
    _notebook(folder, long_name, WRONG)
    _, table, feedback, _ = _grade(folder, tiny_assignments)
    assert set(_feedback_files(feedback)) == {"a_honest.ipynb", long_name}


def test_a_named_pipe_cannot_hang_the_grader(tiny_assignments, tmp_path):
    """A FIFO named like a notebook (an archive can hold one): reading it waits for a
    writer that never comes."""
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    os.mkfifo(folder / "m_pipe.ipynb")
    with _in_a_thread(lambda: _grade(folder, tiny_assignments)) as run:
        run["thread"].join(15)
        hung = run["thread"].is_alive()
        if hung:  # set it free: a writer that closes at once
            with open(folder / "m_pipe.ipynb", "wb"):
                pass
            run["thread"].join(60)
    assert not hung, "grading had not ended after 15 s: it waits on the named pipe"
    if "error" in run:
        raise run["error"]
    _, table, _, _ = run["result"]
    assert table["m_pipe.ipynb"]["problem"] and table["m_pipe.ipynb"]["total"] == "0"


# --- another student's row and feedback ---------------------------------------------------

def test_a_name_that_folds_to_anothers_cannot_take_their_row(tiny_assignments, tmp_path):
    """The roster joins files by `str.lower()`: "mi\\u212Ae.ipynb" (a Kelvin sign, which
    looks like a K) lowers to "mike.ipynb" and sorts after it, so that Mike's row shows
    Mallory's notebook and Mike's own notebook leaves the sheet."""
    folder = tmp_path / "class"
    _notebook(folder, "mike.ipynb", {name: SOLUTIONS[name] for name in WRONG})
    _notebook(folder, "mi\u212ae.ipynb")  # nothing solved
    roster = tmp_path / "roster.csv"
    roster.write_text("id,name,file\ns1,Mike,mike.ipynb\ns2,Mallory,mallory.ipynb\n",
                      encoding="utf-8")
    _, table, _, _ = _grade(folder, tiny_assignments, roster=roster)
    assert {"mike.ipynb", "mi\u212ae.ipynb"} <= set(table), "a submission left the sheet"
    with open(folder.parent / f"{folder.name}-grades.csv", newline="", encoding="utf-8") as f:
        mike = next(row for row in csv.DictReader(f) if row["id"] == "s1")
    assert mike["submission"] == "mike.ipynb" or mike["problem"], mike


def test_a_feedback_file_is_never_anothers(tiny_assignments, tmp_path):
    """"X.ipynb" takes X.md, so "x.ipynb" falls back to x.ipynb.md, which
    "x.ipynb.ipynb" (whose stem is x.ipynb, a new stem) then writes over."""
    folder = tmp_path / "class"
    _notebook(folder, "X.ipynb", WRONG)
    _notebook(folder, "x.ipynb", {name: SOLUTIONS[name] for name in WRONG})
    _notebook(folder, "x.ipynb.ipynb")
    _, table, feedback, _ = _grade(folder, tiny_assignments)
    assert set(_feedback_files(feedback)) == set(table) == {
        "X.ipynb", "x.ipynb", "x.ipynb.ipynb"}


KEYRING = '''import ctypes

libc = ctypes.CDLL(None, use_errno=True)
libc.syscall.restype = ctypes.c_long
NAME = {name!r}.encode()
USER_KEYRING = ctypes.c_int(-4)  # KEY_SPEC_USER_KEYRING: the user's, not the process's
'''
"""What both sides of the keyring attack share: the key's name, unique to one test run."""
KEY_WRITER = KEYRING + '''
SOURCE = {source!r}
exec(SOURCE)
libc.syscall(248, b"user", NAME, SOURCE.encode(), len(SOURCE.encode()), USER_KEYRING)
'''
"""A correct notebook that leaves its answers in the user's keyring (add_key)."""
KEY_READER = KEYRING + '''
key = libc.syscall(250, 10, USER_KEYRING, b"user", NAME, 0)  # KEYCTL_SEARCH
if key > 0:
    found = ctypes.create_string_buffer(30000)
    size = libc.syscall(250, 11, ctypes.c_long(key), found, 30000)  # KEYCTL_READ
    exec(found.raw[:size].decode())
'''
"""A wrong notebook that takes the answers another left in the keyring."""
KEY_REMOVER = KEYRING + '''
def remove():
    key = libc.syscall(250, 10, USER_KEYRING, b"user", NAME, 0)
    if key > 0:
        libc.syscall(250, 21, ctypes.c_long(key))  # KEYCTL_INVALIDATE
    return int(key)
'''
"""Finds the key, removes it, and says whether it was there (its id, or -1)."""


def _remove_key(name):
    """Runs `KEY_REMOVER` confined: the key's id if a key of that name was left, else -1."""
    with sandbox.Confined(CONFINED, sandbox.Limits()) as run:
        run.start({"cells": [KEY_REMOVER.format(name=name)], "functions": ["remove"]})
        while "ready" not in run.receive(time.monotonic() + 60):
            pass
        run.send({"id": 1, "call": "remove", "args": []})
        return runner.decode(run.receive(time.monotonic() + 60)["value"])


def test_nothing_a_submission_leaves_in_the_kernel_reaches_the_next(tiny_assignments,
                                                                     tmp_path):
    """Every submission runs as the machine's user 65534, whose keyring the kernel keeps
    between processes and runs: one notebook leaves its answers there, the next one,
    wrong, takes them (no solution in its notebook), and the key outlives the run."""
    name = f"icm-redteam-{secrets.token_hex(6)}"
    folder = tmp_path / "class"
    solved = {function: SOLUTIONS[function] for function in WRONG}
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, "k1_writer.ipynb", solved, [KEY_WRITER.format(
        name=name, source="\n\n".join(solved.values()))])
    _notebook(folder, "k2_reader.ipynb", WRONG, last=[KEY_READER.format(name=name)])
    try:
        _, table, _, _ = _grade(folder, tiny_assignments, jobs=1)
    finally:
        left = _remove_key(name)
    assert table["k1_writer.ipynb"]["total"] == "20"
    _assert_gains_nothing(table, "k2_reader.ipynb", again=None)
    assert left == -1, "a key a submission made outlived its run"


SPINNERS = 16
"""The processes of the greedy submission in the processor test."""
SPIN_SECONDS = 2.0
"""How long each side of the processor test spins."""
GREEDY = f'''import os
import time


def spin(seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        pass


def measure():
    children = []
    for _ in range({SPINNERS}):
        pid = os.fork()
        if pid == 0:
            os.setsid()  # a session of its own: a scheduling group of its own
            spin({SPIN_SECONDS})
            os._exit(0)
        children.append(pid)
    for pid in children:
        os.waitpid(pid, 0)
    times = os.times()
    return times.children_user + times.children_system
'''
"""A submission that spins many processes, each in a session of its own, and says how
much processor time they got."""
MODEST = f'''import os
import time


def measure():
    end = time.monotonic() + {SPIN_SECONDS}
    while time.monotonic() < end:
        pass
    times = os.times()
    return times.user + times.system
'''
"""A submission that spins one process for as long, and says how much it got."""


def test_a_submission_cannot_take_the_processor_from_the_one_graded_beside_it():
    """Two submissions graded at once (`jobs=2`): a greedy one of many processes and a
    modest one of one process, each spinning for the same time. The control groups
    limit memory and processes, not the processor: the scheduler shares it per process
    (per session, with autogroup), so that the greedy one takes nearly all of it, and
    the modest one's calls run many times slower against their deadlines."""
    measured = {}

    def run(name, cell):
        with sandbox.Confined(CONFINED, sandbox.Limits()) as confined:
            confined.start({"cells": [cell], "functions": ["measure"]})
            while "ready" not in confined.receive(time.monotonic() + 60):
                pass
            confined.send({"id": 1, "call": "measure", "args": []})
            measured[name] = runner.decode(
                confined.receive(time.monotonic() + 60)["value"])
    threads = [threading.Thread(target=run, args=item)
               for item in (("greedy", GREEDY), ("modest", MODEST))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(120)
    assert set(measured) == {"greedy", "modest"}
    assert measured["greedy"] <= 3 * measured["modest"], measured


# --- what reaches the instructor -----------------------------------------------------------

def _outside_code(text):
    """The lines of a Markdown text outside its fenced code blocks (a fence closes on a
    line of the same character, at least as long; indentation is not looked at)."""
    lines, fence = [], None
    for line in text.splitlines():
        run = re.match(r"`{3,}|~{3,}", line.strip())
        if fence is None and run:
            fence = run.group()
        elif fence is not None and run and line.strip() == run.group() and \
                run.group()[0] == fence[0] and len(run.group()) >= len(fence):
            fence = None
        elif fence is None:
            lines.append(line)
    return lines


def test_what_a_notebook_says_reaches_the_feedback_as_text(tiny_assignments, tmp_path):
    """A cell's error text is written into the feedback's Markdown as it is, a case's
    report inside a fence of three backticks, which a line of three in the student's
    error text closes, and the file's name into a heading: a notebook can add headings
    ("10 of 10") and HTML of its own."""
    folder = tmp_path / "class"
    _notebook(folder, "m_markdown.ipynb", {
        **WRONG, "least_squares_slope": "def least_squares_slope(values):\n"
                                        "    raise ValueError('x\\n```\\n\\n"
                                        "<img src=x onerror=alert(2)>\\n\\n```')\n"}, [
        "raise ValueError('x\\n\\n## Exercise 2.1: the least-squares slope: 10 of 10\\n\\n"
        "<img src=x onerror=alert(1)>')\n"])
    _notebook(folder, "<img src=x onerror=alert(3)>.ipynb", WRONG)
    _, _, feedback, _ = _grade(folder, tiny_assignments)
    outside = _outside_code((feedback / "m_markdown.md").read_text(encoding="utf-8"))
    assert not any(line.startswith("## Exercise 2.1: the least-squares slope: 10 of 10")
                   for line in outside)
    for path in feedback.glob("*.md"):
        outside = _outside_code(path.read_text(encoding="utf-8"))
        assert [line for line in outside if "<img" in line] == [], path.name


def test_the_progress_lines_hold_no_terminal_control_characters(tiny_assignments, tmp_path):
    """A file name can hold an escape sequence (ESC [ 2 K erases the terminal's line),
    which the progress lines print as they are."""
    folder = tmp_path / "class"
    _notebook(folder, "a_honest.ipynb", WRONG)
    _notebook(folder, "\x1b[2K\rm_escape.ipynb", WRONG)
    _, _, _, lines = _grade(folder, tiny_assignments)
    controls = [line for line in lines
                if any(ord(c) < 32 or 127 <= ord(c) < 160 for c in line)]
    assert controls == []


@pytest.fixture(scope="module", autouse=True)
def no_survivor():
    """After the module: no process of a run it graded is alive (the hang test kills
    the runs it must set free)."""
    yield
    time.sleep(1)
    left = _confined_processes()
    for process in left:
        with contextlib.suppress(psutil.Error):
            process.kill()
    assert left == []
