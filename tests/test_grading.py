"""Grading as an instructor uses it: a folder of notebooks graded in their confinement,
case by case, into a grade sheet joined to the class's roster and a feedback file per
student; one malformed file costs one row; the command line; the plain values that
cross between the grader and a confined notebook. (The attacks on the grader are in
tests/test_grading_attacks.py.)"""

import csv
import json
import pathlib
import subprocess
import sys
import time

import numpy as np
import pytest

from grading_support import (CHAPTER, INTEREST_OWN, ROOT, WRONG, rows, solution_functions, submission,
                             write_assignments)

from icm import files, records
from icm.course import cgroups, grade, gradebook, runner, sandbox, session
from icm.exercises.registry import EXERCISES

CONFINED = sandbox.probe()


@pytest.fixture(scope="module")
def assignments(tmp_path_factory):
    return write_assignments(tmp_path_factory.mktemp("assignments"))


@pytest.fixture(scope="module")
def graded(assignments, tmp_path_factory):
    """Honest submissions of a class, graded as an instructor would: a correct one,
    one with typical mistakes, one left unsolved, one that imports the library's
    answer, one that hard-codes the public cases, and a goal-choice rule (another
    chapter) that ignores the generator it is given."""
    folder = tmp_path_factory.mktemp("submissions")
    submission(assignments, folder, "correct")
    submission(assignments, folder, "mistakes", {"task_interest": WRONG["task_interest"]})
    submission(assignments, folder, "unsolved", solved=False)
    submission(assignments, folder, "imports", {
        "least_squares_slope": "from icm.learners.interest import least_squares_slope\n",
        "task_interest": INTEREST_OWN})
    submission(assignments, folder, "hard_coded", {
        "least_squares_slope": _hard_coded("ex-least-squares-slope",
                                           "def least_squares_slope(values):")})
    submission(assignments, folder, "global_random", {"choose_region": (
        "import numpy as np\n\n\ndef choose_region(interests, epsilon, rng):\n"
        "    values = np.asarray(interests, dtype=float)\n"
        "    if np.random.random() < epsilon or not values.sum() > 0:\n"
        "        return int(np.random.randint(len(values)))\n"
        "    return int(np.random.choice(len(values), p=values / values.sum()))\n")},
        chapter="forming_actions")
    sheet = folder.parent / f"{folder.name}-grades.csv"
    results = grade.grade(folder, sheet, assignments=assignments, jobs=2,
                          trusted=not CONFINED.available, progress=lambda _: None)
    return sheet, {r.submission: r for r in results}, folder


def _hard_coded(label, definition):
    """An answer that looks its result up in a table of the public cases' answers."""
    exercise = EXERCISES[label]
    solved = solution_functions()[exercise.function]
    table = {repr(case.args): solved(*case.args) for case in exercise.public_cases()}
    arguments = definition.split("(", 1)[1].split(")")[0]
    names = ", ".join(a.split("=")[0].strip() for a in arguments.split(","))
    return (f"ANSWERS = {table!r}\n\n\n{definition}\n"
            f"    return ANSWERS.get(repr(({names},)), 0.0)\n")


def test_a_class_is_graded_case_by_case(graded):
    sheet, results, _ = graded
    table = rows(sheet)
    with open(sheet, newline="") as file:
        header = next(csv.reader(file))
    assert header == ["submission", "chapter", "ex-least-squares-slope", "ex-task-interest",
                      "ex-action-weight-90 (by hand, of 5)", "ex-goal-choice",
                      "ex-hardest-button (by hand, of 5)", "total", "possible", "problem"]
    assert all(not row["problem"] for row in table.values()), table
    total = {name: float(row["total"]) for name, row in table.items()}
    assert total["correct.ipynb"] == 20 and table["correct.ipynb"]["possible"] == "20"
    assert total["unsolved.ipynb"] == 0
    # Typical mistakes: the slope right; the interest wrong on some cases only, and
    # paid for the others (each case is its test's points shared among its cases).
    mistakes = results["mistakes.ipynb"].exercises
    assert mistakes["ex-least-squares-slope"].earned == 10
    assert 0 < mistakes["ex-task-interest"].earned < 10
    for test in mistakes["ex-task-interest"].tests:
        passed = sum(case.passed for case in test.cases)
        assert test.earned == pytest.approx(test.points * passed / len(test.cases))
    # The library is not there to import: 0 for that exercise, the rest graded.
    assert table["imports.ipynb"]["ex-least-squares-slope"] == "0"
    assert table["imports.ipynb"]["ex-task-interest"] == "10"
    # A table of the public cases (and 0 elsewhere): the public test, and of the
    # hidden cases only those whose slope is 0, the ties.
    hard = results["hard_coded.ipynb"].exercises["ex-least-squares-slope"]
    assert [t.earned for t in hard.tests][0] == 2
    assert {c.name for t in hard.tests[1:] for c in t.cases if c.passed} == \
        {"ties: every value the same (hidden)"}
    assert hard.earned < 4
    # A goal-choice rule that ignores its generator fails only the generator's case.
    rule = results["global_random.ipynb"].exercises["ex-goal-choice"]
    failed = {c.name for t in rule.tests for c in t.cases if not c.passed}
    assert failed == {"the generator it is given: the same rng, the same choices"}
    assert 0 < rule.earned < 10


def test_each_student_gets_feedback_that_says_why_and_never_shows_a_hidden_case(graded):
    sheet, results, _ = graded
    folder = sheet.parent / f"{sheet.stem}-feedback"
    assert files.is_ours(folder, grade.COMMAND)
    assert sorted(p.name for p in folder.glob("*.md")) == sorted(
        f"{pathlib.Path(name).stem}.md" for name in results)
    correct = (folder / "correct.md").read_text()
    assert "**20 of 20 points**" in correct and "failed" not in correct
    assert "Exercise 2.1: the least-squares slope" in correct  # the book's numbers
    assert "Exercise 2.4" in correct and "marked by hand" in correct
    imports = (folder / "imports.md").read_text()
    assert "No module named 'icm'" in imports and "write the function" in imports
    mistakes = (folder / "mistakes.md").read_text()
    assert "input:" in mistakes and "expected:" in mistakes  # a public case, in full
    exercise = results["mistakes.ipynb"].exercises["ex-task-interest"]
    hidden = [c for t in exercise.tests if t.hidden for c in t.cases if not c.passed]
    assert hidden and all("values are not shown" in c.message and "expected" not in
                          c.message for c in hidden)
    assert "Hint:" in mistakes


def test_a_case_wrong_costs_that_case_only():
    exercise = EXERCISES["ex-least-squares-slope"]
    solved = solution_functions()["least_squares_slope"]
    cases = exercise.public_cases()

    def wrong_on_ties(values):  # the edge case of ties: every value the same
        return 1.0 if len(set(values)) == 1 else solved(values)

    verdicts, stopped = grade._judged(exercise, wrong_on_ties, cases, hidden=False)
    assert not stopped and [v.name for v in verdicts] == [c.name for c in cases]
    assert [v.name for v in verdicts if not v.passed] == ["ties: every value the same"]
    test = gradebook.TestGrade("public test", False, 2, verdicts)
    assert test.earned == pytest.approx(2 * (len(cases) - 1) / len(cases))


def test_the_roster_gives_a_row_per_student(assignments, graded, tmp_path):
    _, _, folder = graded
    roster = tmp_path / "roster.csv"
    roster.write_text("id,name,file,email\n"
                      "s1,Ada Lovelace,correct.ipynb,ada@example.org\n"
                      "s2,Alan Turing,MISTAKES.IPYNB,\n"
                      "s3,Grace Hopper,never_handed_in.ipynb,\n")
    subset = tmp_path / "handed_in"
    subset.mkdir()
    for name in ("correct.ipynb", "mistakes.ipynb", "hard_coded.ipynb"):
        (subset / name).write_bytes((folder / name).read_bytes())
    sheet = tmp_path / "sheet.csv"
    grade.grade(subset, sheet, assignments=assignments, roster=roster,
                trusted=not CONFINED.available, progress=lambda _: None)
    with open(sheet, newline="") as file:
        table = list(csv.DictReader(file))
    assert [(r["id"], r["name"], r["submission"]) for r in table] == [
        ("s1", "Ada Lovelace", "correct.ipynb"), ("s2", "Alan Turing", "mistakes.ipynb"),
        ("s3", "Grace Hopper", "never_handed_in.ipynb"), ("", "", "hard_coded.ipynb")]
    assert table[0]["total"] == "20" and table[2]["problem"] == "no submission"
    assert table[3]["problem"] == "not on the roster"


@pytest.mark.parametrize("text, why", [
    ("id,name\ns1,Ada\n", "missing file"),
    ("id,name,file\n,Ada,a.ipynb\n", "line 2: id"),
    ("id,name,file\ns1,Ada,../a.ipynb\n", "not a path"),
    ("id,name,file\ns1,Ada,a.ipynb\ns1,Bob,b.ipynb\n", "line 3: the id 's1'"),
    ("id,name,file\ns1,Ada,a.ipynb\ns2,Bob,A.ipynb\n", "line 3: the file"),
])
def test_a_malformed_roster_is_refused_naming_its_line(tmp_path, text, why):
    roster = tmp_path / "roster.csv"
    roster.write_text(text)
    with pytest.raises(records.RecordError, match=why) as raised:
        gradebook.read_roster(roster)
    assert str(roster) in str(raised.value)


MALFORMED = {
    "otter_not_a_dict.ipynb": '{"cells": [], "metadata": {"otter": 5}}',
    "deeply_nested.ipynb": "[" * 100000 + "]" * 100000,
    "not_json.ipynb": "{ this is not JSON",
    "empty.ipynb": "",
    "cells_not_a_list.ipynb": '{"cells": 3, "metadata": {"otter": {"assignment_name": "x"}}}',
    "formula.ipynb": '{"cells": [], "metadata": {"otter": {"assignment_name": '
                     '"=HYPERLINK(\\"http://x\\")"}}}',
    "binary.ipynb": b"\xff\xfe\x00garbage",
    "=SUM(1+1).ipynb": "{}",
}


def test_one_bad_file_costs_one_row_and_the_sheet_is_safe_in_a_spreadsheet(
        assignments, graded, tmp_path):
    _, _, folder = graded
    (tmp_path / "correct.ipynb").write_bytes((folder / "correct.ipynb").read_bytes())
    (tmp_path / "upper.IPYNB").write_bytes((folder / "correct.ipynb").read_bytes())
    for name, content in MALFORMED.items():
        path = tmp_path / name
        path.write_bytes(content if isinstance(content, bytes) else content.encode())
    (tmp_path / "link.ipynb").symlink_to(folder / "correct.ipynb")
    sheet = tmp_path.parent / f"{tmp_path.name}.csv"
    grade.grade(tmp_path, sheet, assignments=assignments,
                trusted=not CONFINED.available, progress=lambda _: None)
    table = {name.removeprefix("'"): row for name, row in rows(sheet).items()}
    assert set(table) == set(MALFORMED) | {"correct.ipynb", "upper.IPYNB", "link.ipynb"}
    assert table["correct.ipynb"]["total"] == table["upper.IPYNB"]["total"] == "20"
    for name in MALFORMED:
        assert table[name]["total"] == "0" and table[name]["problem"], name
    assert "metadata.otter" in table["otter_not_a_dict.ipynb"]["problem"]
    assert "nested too deeply" in table["deeply_nested.ipynb"]["problem"]
    assert "symbolic link" in table["link.ipynb"]["problem"]
    with open(sheet, newline="") as file:
        cells = [cell for row in csv.reader(file) for cell in row]
    assert not any(cell.startswith(gradebook.FORMULA_STARTS) for cell in cells)
    assert "'=SUM(1+1).ipynb" in cells  # quoted, not dropped


def test_the_command_line_grades_a_folder(assignments, graded, tmp_path):
    _, _, folder = graded
    here = tmp_path / "one"
    here.mkdir()
    (here / "a.ipynb").write_bytes((folder / "mistakes.ipynb").read_bytes())
    command = [sys.executable, "-m", "icm.course", "grade", str(here), "--out",
               str(tmp_path / "g.csv"), "--assignments", str(assignments)]
    if not CONFINED.available:
        command.append("--trusted")
    done = subprocess.run(command, capture_output=True, text=True, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    assert rows(tmp_path / "g.csv")["a.ipynb"]["ex-least-squares-slope"] == "10"
    assert (tmp_path / "g-feedback" / "a.md").exists()
    again = subprocess.run(command, capture_output=True, text=True, cwd=ROOT)
    assert again.returncode == 0, again.stderr  # its own sheet and feedback: replaced


@pytest.mark.parametrize("where", ["a notebook", "the submissions", "inside the submissions",
                                   "a folder of someone else's"])
def test_grade_refuses_to_write_over_what_it_did_not_write(assignments, tmp_path, where):
    submissions = tmp_path / "subs"
    submissions.mkdir()
    notebook = submissions / "alice.ipynb"
    notebook.write_text("{}")
    other = tmp_path / "mine"
    other.mkdir()
    (other / "notes.txt").write_text("keep me")
    out, feedback = tmp_path / "g.csv", None
    if where == "a notebook":
        out = notebook
    elif where == "the submissions":
        feedback = submissions
    elif where == "inside the submissions":
        feedback = submissions / "feedback"
    else:
        feedback = other
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    with pytest.raises(files.DestinationError) as raised:
        grade.grade(submissions, out, assignments=assignments, feedback_dir=feedback,
                    trusted=True, progress=lambda _: None)
    assert str(out if where == "a notebook" else feedback) in str(raised.value)
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before


def test_grade_refuses_bad_input(tmp_path, assignments):
    with pytest.raises(grade.GradeError, match="does not exist"):
        grade.grade(tmp_path / "none", tmp_path / "grades.csv", assignments=assignments)
    with pytest.raises(grade.GradeError, match="no notebook"):
        grade.grade(tmp_path, tmp_path.parent / "g0.csv", assignments=assignments)
    (tmp_path / "a.ipynb").write_text("{}")
    with pytest.raises(grade.GradeError, match="no assignment"):
        grade.grade(tmp_path, tmp_path.parent / "g1.csv", assignments=tmp_path / "none",
                    trusted=True)
    for name, value in (("time_limit", 0), ("memory_limit", 1e300), ("cell_timeout", -1),
                        ("jobs", 0), ("jobs", grade.MAX_JOBS + 1)):
        with pytest.raises(ValueError, match=name):
            grade.grade(tmp_path, tmp_path.parent / "g2.csv", assignments=assignments,
                        **{name: value})


def test_without_confinement_grade_refuses_unless_trusted(monkeypatch, assignments, graded,
                                                          tmp_path):
    _, _, folder = graded
    (tmp_path / "correct.ipynb").write_bytes((folder / "correct.ipynb").read_bytes())
    monkeypatch.setattr(sandbox, "probe", lambda: sandbox.Confinement(
        problem="bubblewrap is not installed"))
    with pytest.raises(grade.GradeError, match="bubblewrap is not installed.*--trusted"):
        grade.grade(tmp_path, tmp_path.parent / "t.csv", assignments=assignments)
    results = grade.grade(tmp_path, tmp_path.parent / "t.csv", assignments=assignments,
                          trusted=True, progress=lambda _: None)
    assert results[0].total == 20


def test_a_malformed_assignment_is_refused_naming_its_file(assignments, tmp_path):
    import shutil

    copy = tmp_path / "assignments"
    shutil.copytree(assignments, copy)
    manifest = copy / CHAPTER / "autograder" / grade.MANIFEST
    data = json.loads(manifest.read_text())
    data["exercises"][0]["points"] = "many"
    manifest.write_text(json.dumps(data))
    with pytest.raises(grade.GradeError, match=rf"{manifest}.*exercises\.0\.points"):
        grade.load_assignments(copy)


# --- the confinement and the values that cross ------------------------------------------

def test_plain_values_cross_unchanged_and_nothing_else_crosses():
    rng = np.random.default_rng(3)
    rng.random(5)
    value = {"a": [1, 2.5, float("nan"), float("-inf"), None, True, "text"],
             "$not a tag": (1, (2, 3)), (1, 2): {3, 4}, 5: np.arange(6).reshape(2, 3),
             "floats": np.array([0.5, np.nan]), "rng": rng, "big": 2 ** 80}
    back = runner.decode(runner.loads(runner.dumps({"v": runner.encode(value)})[:-1])["v"])
    assert back["a"][:2] == [1, 2.5] and np.isnan(back["a"][2]) and back["a"][3] == -np.inf
    assert back["$not a tag"] == (1, (2, 3)) and back[(1, 2)] == {3, 4}
    assert back[5].tolist() == [[0, 1, 2], [3, 4, 5]] and back[5].dtype == np.int64
    assert back["big"] == 2 ** 80
    assert back["rng"].random() == rng.random()  # the same state
    for bad in (object(), lambda: 1, np.array(["text"]), {"k": object()}):
        with pytest.raises(runner.WireError):
            runner.encode(bad)
    deep = []
    for _ in range(runner.MAX_DEPTH + 5):
        deep = [deep]
    with pytest.raises(runner.WireError, match="nested"):
        runner.encode(deep)
    for data in ({"$pickle": "x"}, {"$array": [1], "dtype": "O", "shape": [1]},
                 {"$generator": {"bit_generator": "os.system"}},
                 {"$dict": [[[1], 2]]}, {"$tuple": 3}):
        with pytest.raises(runner.WireError):
            runner.decode(data)
    with pytest.raises(runner.WireError, match="not JSON"):
        runner.loads(b"[" * 100000)


def test_arguments_changed_in_place_are_changed_back_here():
    critic, actor = {"s": 0.5}, {"s": [0.0, 1.0]}
    row = actor["s"]
    assert session.write_back(critic, {"s": 0.75, "t": 0.1})
    assert session.write_back(actor, {"s": [0.0, 2.0]})
    assert critic == {"s": 0.75, "t": 0.1} and row == [0.0, 2.0] and actor["s"] is row
    array = np.zeros(3)
    assert session.write_back(array, np.ones(3)) and array.tolist() == [1, 1, 1]
    rng, moved = np.random.default_rng(1), np.random.default_rng(1)
    moved.random(3)
    assert session.write_back(rng, moved) and rng.random() == moved.random()


def test_control_groups_of_version_2_are_made_and_limited(tmp_path, monkeypatch):
    root = tmp_path / "cgroup"
    root.mkdir()
    (root / "cgroup.controllers").write_text("cpu memory pids io\n")
    (root / "cgroup.subtree_control").write_text("")
    (root / cgroups.GROUP).mkdir()  # (the kernel fills a new group with its files)
    (root / cgroups.GROUP / "cgroup.subtree_control").write_text("")
    kind = sandbox.CgroupV2(root)
    assert kind.usable() == ""
    assert (root / "cgroup.subtree_control").read_text() == "+memory +pids +cpu"
    assert (root / cgroups.GROUP / "cgroup.subtree_control").read_text() == \
        "+memory +pids +cpu"
    real_mkdir = pathlib.Path.mkdir

    def mkdir_with_files(self, *args, **kwargs):  # as the kernel fills a new group
        real_mkdir(self, *args, **kwargs)
        if self.parent == root / cgroups.GROUP:
            (self / "cpu.max").write_text("max 100000")
    monkeypatch.setattr(pathlib.Path, "mkdir", mkdir_with_files)
    group = kind.create("one", sandbox.Limits(memory=2 ** 30, processes=10, cpus=1.5))
    monkeypatch.undo()
    folder = root / cgroups.GROUP / "one"
    assert (folder / "cpu.max").read_text() == "150000 100000"
    assert (folder / "memory.max").read_text() == str(2 ** 30)
    assert (folder / "pids.max").read_text() == "10"
    (folder / "memory.events").write_text("low 0\nhigh 0\nmax 3\noom 1\noom_kill 1\n")
    (folder / "memory.peak").write_text("12345\n")
    assert group.out_of_memory() and group.peak_memory() == 12345
    (root / "no").mkdir()
    assert "no cgroup v2" in sandbox.CgroupV2(root / "no").usable()
    assert "lacks ['pids']" in sandbox.CgroupV2(_controllers(tmp_path, "memory")).usable()


def _controllers(tmp_path, text):
    folder = tmp_path / "other"
    folder.mkdir()
    (folder / "cgroup.controllers").write_text(text)
    return folder


@pytest.mark.skipif(not CONFINED.available, reason=f"no confinement: {CONFINED.problem}")
def test_the_confinement_sees_only_python_numpy_and_the_runner_and_refuses_calls():
    cells = ["import os, sys, socket\n"
             "seen = sorted(os.listdir('/'))\n"
             "grader = sorted(os.listdir('/grader'))\n"
             "packages = sorted(os.listdir('/grader/packages'))\n"
             "who = (os.getuid(), os.getgid(), os.getpid())\n"
             "import importlib.util\n"
             "missing = [m for m in ('icm', 'otter', 'pytest', 'pip') "
             "if importlib.util.find_spec(m) is not None]\n"
             "import ctypes\n"
             "libc = ctypes.CDLL(None, use_errno=True)\n"
             "refused = []\n"
             "for number in (248, 250, 272, 101, 323):  # add_key keyctl unshare ptrace "
             "userfaultfd (x86-64)\n"
             "    refused.append((libc.syscall(number, 0, 0, 0, 0, 0), ctypes.get_errno()))\n"
             "status = open('/proc/self/status').read()\n"
             "bounds = status.split('CapBnd:')[1].split()[0]\n"
             "def probe():\n"
             "    return [seen, grader, packages, list(who), missing, refused, bounds]\n"]

    with sandbox.Confined(CONFINED, sandbox.Limits()) as run:
        run.start({"cells": cells, "functions": ["probe"]})
        while "ready" not in run.receive(time.monotonic() + 60):
            pass
        run.send({"id": 1, "call": "probe", "args": []})
        seen, grader, packages, who, importable, refused, bounds = runner.decode(
            run.receive(time.monotonic() + 60)["value"])
    assert "work" not in seen and "home" not in seen and "etc" not in seen
    assert grader == ["packages", "runner.py"]
    assert set(packages) <= {"numpy", "numpy.libs"}
    assert who == [65534, 65534, 1] and importable == []
    import platform

    if platform.machine() == "x86_64":  # the seccomp filter: each refused, EPERM
        assert refused == [(-1, 1)] * 5, refused
    if sandbox.drops_root():  # no capability left to gain, even through a setuid file
        assert bounds == "0000000000000000"


# --- the time limits: each fires once, at its limit, never a multiple of it -------------

LOOP = "while True:\n    pass\n"


def test_each_cell_past_its_limit_is_left_out_once_and_the_rest_is_graded(assignments,
                                                                         tmp_path):
    # Three cells that never end: each is left out once, at its own limit, and the
    # notebook is run again without it (never rerun: three limits in all, not six); its
    # answers are then graded in full.
    folder = tmp_path / "class"
    submission(assignments, folder, "loops", extra=[LOOP, LOOP, LOOP])
    cell = 4.0
    graded = grade.grade(folder, tmp_path / "g.csv", assignments=assignments,
                         time_limit=120, cell_timeout=cell, trusted=not CONFINED.available,
                         progress=lambda _: None)[0]
    left_out = [note for note in graded.notes if "left out" in note]
    assert len(left_out) == 3 and all("time limit of a cell" in n for n in left_out)
    assert graded.total == 20 and not graded.problem
    assert 3 * cell <= graded.seconds < 3 * cell + 30, graded.seconds


def test_a_submission_is_stopped_at_its_own_limit_once_not_at_a_multiple(assignments,
                                                                        tmp_path):
    # Functions that never return, in a submission allowed less than one test's limit:
    # the first call is stopped at the submission's limit, and nothing else runs (a
    # limit counted per test or per exercise would let it run three times as long).
    folder = tmp_path / "class"
    looping = {name: f"def {signature}:\n" + "".join(f"    {line}\n" for line in
                                                    LOOP.splitlines())
               for name, signature in (("least_squares_slope", "least_squares_slope(values)"),
                                       ("task_interest", "task_interest(history, others, "
                                                         "window=5, new_task_factor=0.5)"))}
    submission(assignments, folder, "loops", looping)
    limit = 8.0
    assert limit < EXERCISES["ex-least-squares-slope"].timeout
    graded = grade.grade(folder, tmp_path / "g.csv", assignments=assignments,
                         time_limit=limit, trusted=not CONFINED.available,
                         progress=lambda _: None)[0]
    assert graded.total == 0
    assert "time limit" in graded.problem, graded.problem
    assert limit <= graded.seconds < limit + 10, graded.seconds
