"""Grades a folder of students' notebooks with the autograders of `assign`, on this
machine, with no server.

    python -m icm.course grade SUBMISSIONS_DIR --out grades.csv [--assignments DIR]
        [--feedback DIR] [--time-limit S] [--memory-limit GB] [--cell-timeout S] [--jobs N]

Each notebook says which chapter it is (otter's `assignment_name` in its metadata,
written by `assign`); it is graded by that chapter's autograder zip (the one
Gradescope would run), with `otter.api.grade_submission` (otter run: the notebook
executed in a Jupyter kernel, then the tests, public and hidden).

A submission is someone else's code running here, so each is graded in a process of
its own (`icm.course._worker`), in a new session, from a folder of its own holding a
copy of the notebook and of the autograder (read into memory before any submission
runs), with a limit on its memory (address space) and on its time: at the limit the
process and every process it started are killed. A cell that runs too long is
interrupted and the next cells run. An infinite loop, a crash, `sys.exit`, a kernel
that dies, an error at import, a notebook that deletes the files around it: each
costs that submission its points, never another's. This is not a sandbox: the
notebook runs as the user who grades, and can read and write what that user can.
Grade submissions you do not trust in otter's containers (see the instructors' page).

Writes one CSV row per submission (its points per exercise, its total, what went
wrong) and, per submission, a feedback file in Markdown: the points of each test, the
public tests' reports, the hidden tests' verdicts with their hints (never their
cases).
"""

import concurrent.futures
import csv
import dataclasses
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import zipfile

from icm import _validate

MANIFEST = "assignment.json"
"""The file, beside the autograder, that `icm.course.assign.manifest` writes (here, not
in `assign`, so that grading does not import `assign`: nbformat and every exercise's
check, 3 s of a `python -m icm.course grade` that needs none of them)."""
TIME_LIMIT = 600.0
"""Seconds one submission may take, kernel start and every test included."""
CELL_TIMEOUT = 120.0
"""Seconds one cell may run before it is interrupted."""
MEMORY_LIMIT = 6.0
"""GiB of address space for one submission's processes, each (the kernel's imports
alone reserve about 2)."""


class GradeError(ValueError):
    """Grading that cannot start: no submissions, no autograder."""


@dataclasses.dataclass
class Assignment:
    """One chapter's grading material, read into memory.

    Attributes:
      chapter: the chapter's name.
      title: its title.
      exercises: [(label, title, points)] of its autograded exercises, in order.
      autograder: the bytes of otter's autograder zip.
      zip_name: that zip's file name.
    """

    chapter: str
    title: str
    exercises: list
    autograder: bytes
    zip_name: str


@dataclasses.dataclass
class Graded:
    """One submission's grade.

    Attributes:
      submission: its file name.
      chapter: its chapter (None if unknown).
      points: {label: points earned}.
      possible: {label: points possible}.
      tests: {label: [test cases as `_worker.summary` gives them]}.
      problem: what went wrong with the submission as a whole ("" if nothing).
      seconds: how long its grading took.
    """

    submission: str
    chapter: str = None
    points: dict = dataclasses.field(default_factory=dict)
    possible: dict = dataclasses.field(default_factory=dict)
    tests: dict = dataclasses.field(default_factory=dict)
    problem: str = ""
    seconds: float = 0.0

    @property
    def total(self):
        """The points earned."""
        return sum(self.points.values())


def load_assignments(folder):
    """Every chapter's grading material under `folder` (what `assign` wrote).

    Args:
      folder: the assignments' folder.

    Returns:
      {chapter: `Assignment`}, in the book's order.

    Raises:
      GradeError: if it holds none.
    """
    folder = pathlib.Path(folder)
    found, numbers = {}, {}
    for manifest_path in sorted(folder.glob(f"*/autograder/{MANIFEST}")):
        manifest = json.loads(manifest_path.read_text())
        numbers[manifest["chapter"]] = manifest.get("number", 0)
        zips = sorted(manifest_path.parent.glob("*-autograder_*.zip"))
        if not zips:
            continue
        found[manifest["chapter"]] = Assignment(
            manifest["chapter"], manifest["title"],
            [(e["label"], e["title"], float(e["points"])) for e in manifest["exercises"]],
            zips[-1].read_bytes(), zips[-1].name)
    if not found:
        raise GradeError(f"no assignment in {folder}: run `python -m icm.course assign "
                         f"{folder}` (or `make assignments`) first")
    return dict(sorted(found.items(), key=lambda item: (numbers[item[0]], item[0])))


def chapter_of(notebook_bytes):
    """The chapter a submitted notebook says it is (otter's assignment name).

    Args:
      notebook_bytes: the notebook's file.

    Returns:
      The chapter's name.

    Raises:
      ValueError: for a file that is not a notebook of an assignment.
    """
    try:
        notebook = json.loads(notebook_bytes)
    except (ValueError, UnicodeDecodeError) as error:
        raise ValueError(f"not a notebook (not JSON: {error})") from None
    name = notebook.get("metadata", {}).get("otter", {}).get("assignment_name") \
        if isinstance(notebook, dict) else None
    if not isinstance(name, str):
        raise ValueError("not an assignment's notebook (no otter assignment_name in its "
                         "metadata)")
    return name


def _kill_all(process):
    """Kills a worker, every process it started (its kernel has a session of its own),
    and whatever is left in its process group."""
    from icm.course._worker import kill_descendants

    kill_descendants(process.pid)
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


_PROBLEMS = (("DeadKernelError", "its kernel died: the notebook ended its own process "
                                 "(os._exit, a crash) or ran out of memory"),
             ("results.pkl", "it deleted or moved the grader's files around it"),
             ("No such file or directory", "it deleted or moved the grader's files around "
                                           "it"))
"""Known ways a notebook stops otter, and what the feedback says of them."""


def grade_one(name, notebook_bytes, assignments, time_limit=TIME_LIMIT,
              memory_limit=MEMORY_LIMIT, cell_timeout=CELL_TIMEOUT):
    """Grades one submission in a process of its own.

    Args:
      name: the submission's file name.
      notebook_bytes: its content.
      assignments: {chapter: `Assignment`}.
      time_limit: seconds for the whole submission.
      memory_limit: GiB of address space for each of its processes.
      cell_timeout: seconds for one cell.

    Returns:
      A `Graded`.
    """
    graded = Graded(name)
    try:
        graded.chapter = chapter_of(notebook_bytes)
    except ValueError as error:
        graded.problem = str(error)
        return graded
    assignment = assignments.get(graded.chapter)
    if assignment is None:
        graded.problem = (f"no autograder for the chapter {graded.chapter!r} (there are: "
                          f"{', '.join(sorted(assignments))})")
        return graded
    graded.possible = {label: points for label, _, points in assignment.exercises}
    graded.points = {label: 0.0 for label in graded.possible}
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="icm-grade-") as folder:
        here = pathlib.Path(folder)
        submission = here / "submission"
        submission.mkdir()
        notebook = submission / f"{graded.chapter}.ipynb"
        notebook.write_bytes(notebook_bytes)
        autograder = here / assignment.zip_name
        autograder.write_bytes(assignment.autograder)
        result = here / "result.json"
        log = here / "worker.log"
        command = [sys.executable, "-m", "icm.course._worker", str(autograder), str(notebook),
                   str(result), str(cell_timeout), str(int(memory_limit * 2 ** 30)),
                   str(int(time_limit) + 10)]
        with open(log, "wb") as output:
            process = subprocess.Popen(command, cwd=submission, stdin=subprocess.DEVNULL,
                                       stdout=output, stderr=subprocess.STDOUT,
                                       start_new_session=True)
            try:
                status = process.wait(timeout=time_limit)
            except subprocess.TimeoutExpired:
                status = None
            finally:
                _kill_all(process)  # and whatever the notebook left running
                process.wait()
        graded.seconds = time.monotonic() - start
        if status is None:
            graded.problem = (f"stopped after {time_limit:g} s, the time limit of a "
                              f"submission: the notebook ran too long (a loop that never "
                              f"ends?)")
            return graded
        try:
            data = json.loads(result.read_text())
        except (OSError, ValueError):
            tail = log.read_bytes()[-4000:].decode(errors="replace").strip().splitlines()
            reason = tail[-1] if tail else f"exit status {status}"
            said = next((text for key, text in _PROBLEMS if key in reason), None)
            graded.problem = f"the notebook stopped the grader: {said or reason}"
            return graded
    if data.get("error"):
        graded.problem = f"otter could not grade the notebook: {data['error']}"
    for label, test in data.get("tests", {}).items():
        if label in graded.points:
            graded.points[label] = float(test["score"])
            graded.tests[label] = test["cases"]
    return graded


def _message(case):
    """What a test case's feedback says: the test's own message, without otter's
    frame (the test's source line)."""
    if case["passed"]:
        return "passed"
    message = case["message"] or ""
    if "AssertionError: " in message:
        return message.split("AssertionError: ", 1)[1].strip()
    lines = [line for line in message.strip().splitlines() if line.strip()]
    return lines[-1].strip() if lines else "failed"


def feedback(graded, assignment):
    """A submission's feedback, in Markdown.

    Args:
      graded: its `Graded`.
      assignment: its chapter's `Assignment` (None if unknown).

    Returns:
      The text.
    """
    lines = [f"# Feedback: {graded.submission}", ""]
    if assignment is None:
        return "\n".join(lines + [f"Not graded: {graded.problem}.", ""])
    possible = sum(graded.possible.values())
    lines += [f"Chapter: {assignment.title}. Total: **{graded.total:g} of {possible:g} "
              f"points**.", ""]
    if graded.problem:
        lines += [f"**The notebook as a whole:** {graded.problem}.", ""]
    for label, title, points in assignment.exercises:
        lines += [f"## {title} (`{label}`): {graded.points.get(label, 0):g} of {points:g}", ""]
        cases = graded.tests.get(label)
        if not cases:
            lines += ["Not graded (see above).", ""]
            continue
        said = None
        for case in cases:
            kind = "hidden test" if case["hidden"] else "public test"
            earned = case["points"] if case["passed"] else 0
            text = _message(case)
            verdict = "passed" if case["passed"] else \
                "failed, for the same reason" if text == said else "failed"
            lines.append(f"- {kind} ({earned:g} of {case['points']:g}): {verdict}")
            if verdict == "failed":
                lines += ["", "  ```text"] + [f"  {line}" for line in text.splitlines()] + \
                    ["  ```", ""]
                said = text
        lines.append("")
    return "\n".join(lines)


def grade(submissions, out, assignments="_build/assignments", feedback_dir=None,
          time_limit=TIME_LIMIT, memory_limit=MEMORY_LIMIT, cell_timeout=CELL_TIMEOUT,
          jobs=1, progress=print):
    """Grades every notebook in a folder and writes the grade sheet and the feedback.

    Args:
      submissions: the folder of submitted notebooks (their .ipynb files).
      out: the CSV to write.
      assignments: the folder `assign` wrote.
      feedback_dir: the folder of the feedback files (default: beside `out`, in
        "<out's stem>-feedback").
      time_limit: seconds for one submission.
      memory_limit: GiB of address space for each process of one submission.
      cell_timeout: seconds for one cell.
      jobs: submissions graded at once.
      progress: a function of one line, told as each submission is graded.

    Returns:
      The list of `Graded`, in the order of the rows.

    Raises:
      GradeError: for a folder with no notebook, or no assignment.
      ValueError: for bad limits.
    """
    time_limit = _validate.positive("time_limit", time_limit)
    memory_limit = _validate.positive("memory_limit", memory_limit)
    cell_timeout = _validate.positive("cell_timeout", cell_timeout)
    jobs = _validate.integer_at_least("jobs", jobs, 1)
    submissions = pathlib.Path(submissions)
    paths = sorted(p for p in submissions.glob("*.ipynb") if p.is_file())
    if not paths:
        raise GradeError(f"no notebook (*.ipynb) in {submissions}")
    loaded = load_assignments(assignments)
    # Everything is read before any submission runs: none can change another's input.
    contents = [(path.name, path.read_bytes()) for path in paths]
    out = pathlib.Path(out)
    feedback_dir = pathlib.Path(feedback_dir) if feedback_dir else \
        out.parent / f"{out.stem}-feedback"

    def one(item):
        graded = grade_one(*item, loaded, time_limit, memory_limit, cell_timeout)
        progress(f"{graded.submission}: {graded.total:g} of {sum(graded.possible.values()):g}"
                 + (f" ({graded.problem})" if graded.problem else "") +
                 f" [{graded.seconds:.0f} s]")
        return graded

    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(one, contents))
    write_csv(results, loaded, out)
    if feedback_dir.exists():
        shutil.rmtree(feedback_dir)
    feedback_dir.mkdir(parents=True)
    for graded in results:
        (feedback_dir / f"{pathlib.Path(graded.submission).stem}.md").write_text(
            feedback(graded, loaded.get(graded.chapter)))
    return results


def write_csv(results, assignments, out):
    """The grade sheet: one row per submission; its name, its chapter, its points in
    each exercise (of every chapter present, in the book's order; empty for another
    chapter's), its total, the points possible, and what went wrong.

    Args:
      results: the list of `Graded`.
      assignments: {chapter: `Assignment`}.
      out: the CSV's path.
    """
    chapters = {graded.chapter for graded in results}
    labels = [label for chapter, assignment in assignments.items() if chapter in chapters
              for label, _, _ in assignment.exercises]
    out.parent.mkdir(parents=True, exist_ok=True)
    with open(out, "w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["submission", "chapter"] + labels + ["total", "possible", "problem"])
        for graded in results:
            writer.writerow(
                [graded.submission, graded.chapter or ""] +
                [f"{graded.points[label]:g}" if label in graded.points else ""
                 for label in labels] +
                [f"{graded.total:g}", f"{sum(graded.possible.values()):g}", graded.problem])


def read_zip_tests(autograder_bytes):
    """The names of the tests in an autograder zip (for checks).

    Args:
      autograder_bytes: the zip.

    Returns:
      {file name: source} of its tests/ folder.
    """
    import io

    with zipfile.ZipFile(io.BytesIO(autograder_bytes)) as archive:
        return {name: archive.read(name).decode() for name in archive.namelist()
                if name.startswith("tests/")}
