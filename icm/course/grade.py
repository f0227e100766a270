"""Grades a folder of students' notebooks on this machine, with no server, without ever
running a student's code in the grader's own process.

    python -m icm.course grade SUBMISSIONS_DIR --out grades.csv [--assignments DIR]
        [--roster ROSTER.csv] [--feedback DIR] [--time-limit S] [--memory-limit GIB]
        [--cell-timeout S] [--jobs N] [--trusted] [--force]

How a submission is graded:

1. The grader reads the notebook as data (`icm.records.SubmittedNotebook`): which
   chapter it is (otter's assignment name in its metadata) and its code cells. A file
   that is not such a notebook costs its own row, never the run.
2. The notebook's cells run in its own confinement (`icm.course.sandbox`: no network,
   no icm, no grading material, no other submission, limits on its memory, processes,
   disk and time), in the program `icm.course.runner`. The handed-out cells that only
   a student's kernel needs (the install and `grader.check` cells, left unchanged) are
   not run; an unchanged setup cell is replaced by `GRADING_SETUP`.
3. For each implement exercise, the grader calls the student's function through that
   program (`icm.course.session.RemoteFunction`): the exercise's check runs here, in
   the grader, on plain values that come back. Its public test is the check's public
   cases; its hidden tests are cases of the same kinds drawn from a secret made for
   this run (`secrets`), per chapter, which exists only in this process. Each test's
   points are shared among its cases: one case wrong costs that case's share.

Nothing the notebook does can reach the grader: it cannot patch the checks (they are
not in its process), read the hidden cases or the expected results (never sent),
forge the results (its answers are compared here), survive its run (its processes are
killed with its PID namespace and control group), or touch another submission or the
grader's files (not in its view). Where the confinement is not available
(`sandbox.probe` says why), `grade` refuses, unless told `trusted=True` (notebooks
you trust: the solutions, your own tests), which runs the same program unconfined.

Writes one CSV row per student (`icm.course.gradebook.write_csv`, joined to a roster
when given) and one feedback file per submission, in Markdown.
"""

import concurrent.futures
import dataclasses
import hashlib
import os
import pathlib
import secrets
import time

from icm import _validate, files, records
from icm.course import gradebook, grading, limits, sandbox, session
from icm.exercises._core import NOT_IMPLEMENTED
from icm.exercises.registry import EXERCISES

MANIFEST = "assignment.json"
"""The file, beside the autograder, that `icm.course.assign.manifest` writes."""
TIME_LIMIT = 600.0
"""Seconds one submission may take, its cells and every test included."""
CELL_TIMEOUT = 120.0
"""Seconds one cell may run before it is left out."""
MEMORY_LIMIT = 4.0
"""GiB of memory for one submission, all its processes and its RAM disk together."""
MAX_JOBS = limits.JOBS[1]
"""The most submissions graded at once: the machine's cores."""
GRADING_SETUP = "import numpy as np"
"""What the grader runs in place of an assignment's setup cell left unchanged (the
setup installs icm and otter and starts `grader.check`, which only the student's own
kernel runs): the import it gives the student's answers."""
MAX_SUBMISSION_BYTES = 32 * 2 ** 20
"""The largest notebook read (a notebook with its outputs is a few MB)."""
FEEDBACK_STEM_BYTES = 200
"""The longest stem of a feedback file's name, in bytes (a name has at most 255, and
its temporary name while it is written takes more)."""
COMMAND = "grade"
"""This command's name in the marker of the feedback folders it writes."""
SETUP_MARK = "grader = otter.Notebook("
"""How the setup cell of an assignment's notebook is recognised."""


class GradeError(ValueError):
    """Grading that cannot start: no submissions, no assignment, no confinement."""


@dataclasses.dataclass
class Assignment:
    """One chapter's assignment, as the grader needs it.

    Attributes:
      chapter: the chapter's name.
      number: its number in the book.
      title: its title.
      exercises: its exercises (`records.ManifestExercise`), in order (implement and
        extend).
      handed_out: the sources of the student's notebook's code cells that are not
        answer cells (setup, checks, export, the extend exercises' empty cells).
      setup: the source of its setup cell ("" if none).
    """

    chapter: str
    number: int
    title: str
    exercises: list
    handed_out: frozenset = frozenset()
    setup: str = ""

    @property
    def autograded(self):
        """Its implement exercises."""
        return [e for e in self.exercises if e.kind == "implement"]


def load_assignments(folder):
    """Every chapter's assignment under `folder` (what `assign` wrote): its manifest
    and its student's notebook.

    Args:
      folder: the assignments' folder.

    Returns:
      {chapter: `Assignment`}, in the book's order.

    Raises:
      GradeError: if it holds none, or a manifest or notebook is malformed (named).
    """
    folder = pathlib.Path(folder)
    found = {}
    for path in sorted(folder.glob(f"*/autograder/{MANIFEST}")):
        try:
            manifest = records.read_json(path, records.Manifest)
            student = path.parent.parent / "student" / f"{manifest.chapter}.ipynb"
            template = records.read_json(student, records.SubmittedNotebook)
        except records.RecordError as error:
            raise GradeError(f"a malformed assignment: {error}") from None
        for exercise in manifest.exercises:
            if exercise.kind == "implement" and exercise.label not in EXERCISES:
                raise GradeError(f"{path}: {exercise.label} is not an implement exercise "
                                 f"of icm.exercises.registry")
        code = [cell for cell in template.cells if cell.cell_type == "code"]
        found[manifest.chapter] = Assignment(
            manifest.chapter, manifest.number, manifest.title, manifest.exercises,
            frozenset(cell.text for cell in code
                      if "otter_answer_cell" not in cell.metadata.get("tags", [])),
            next((cell.text for cell in code if SETUP_MARK in cell.text), ""))
    if not found:
        raise GradeError(f"no assignment in {folder}: run `python -m icm.course assign "
                         f"{folder}` (or `make assignments`) first")
    return dict(sorted(found.items(), key=lambda item: (item[1].number, item[0])))


def chapter_seed(secret, chapter):
    """The seed of a chapter's hidden cases in one run: the run's secret and the
    chapter's name, hashed (so that one chapter's cases say nothing of another's).

    Args:
      secret: the run's secret, bytes.
      chapter: the chapter's name.

    Returns:
      An integer >= 0.
    """
    digest = hashlib.blake2b(chapter.encode(), key=secret, digest_size=16).digest()
    return int.from_bytes(digest, "big")


def read_submission(name, data, assignments):
    """The chapter and the cells to run of a submitted notebook.

    Args:
      name: the file's name.
      data: its bytes.
      assignments: {chapter: `Assignment`}.

    Returns:
      (the `Assignment`, [a code cell's source, or None for a cell not run]).

    Raises:
      ValueError: for a file that is not a notebook of one of the assignments, naming
        what is wrong.
    """
    try:
        notebook = records.parse_json(data, records.SubmittedNotebook, name)
    except records.RecordError as error:
        text = str(error).split(": ", 1)[-1]
        if text.startswith("metadata"):
            raise ValueError(f"not an assignment's notebook ({text}: it has no otter "
                             f"assignment_name in its metadata)") from None
        raise ValueError(f"not a notebook ({text})") from None
    chapter = notebook.metadata.otter.assignment_name
    assignment = assignments.get(chapter)
    if assignment is None:
        raise ValueError(f"no assignment for the chapter {chapter[:80]!r} (there are: "
                         f"{', '.join(assignments)})")
    cells = []
    for cell in notebook.cells:
        if cell.cell_type != "code":
            continue
        source = cell.text
        if source == assignment.setup:
            cells.append(GRADING_SETUP)
        elif source in assignment.handed_out:
            cells.append(None)
        else:
            cells.append(source)
    return assignment, cells


def _judged(exercise, function, cases, hidden):
    """Every case of one test, judged: ([`gradebook.CaseGrade`], what stopped the
    student's function, or "").

    A check stops at the first case that fails (its report is about that case), and
    may judge cases of its own after the given ones (the goal-choice rule's generator).
    So the check is run again on the cases after each one that fails; the cases of its
    own are judged on the cases that passed.
    """
    verdicts, remaining, passed_cases = {}, list(cases), []
    order, stopped, own_cases_judged = None, "", False
    while True:
        try:
            result = exercise.check(function, cases=remaining)
        except session.CallStopped as error:  # a time limit, an exit: the rest fails
            stopped = error.reason
            for case in remaining:
                verdicts.setdefault(case.name, gradebook.CaseGrade(case.name, False, stopped))
            break
        except Exception as error:  # a function the check cannot call, or judge
            text = str(error) if isinstance(error, (TypeError, ValueError)) else (
                f"the check could not judge your function's answer ({type(error).__name__}"
                f": {error})")
            for case in remaining:
                verdicts.setdefault(case.name, gradebook.CaseGrade(case.name, False,
                                                                   text[:2000]))
            break
        if order is None:
            order = list(result.cases)
        if result.status == NOT_IMPLEMENTED:
            message = grading.case_message(result, hidden)
            for name in result.cases:
                verdicts.setdefault(name, gradebook.CaseGrade(name, False, message))
            break
        failed = None if result.passed else result.case.name
        for name in result.cases:
            if name == failed:
                break
            verdicts.setdefault(name, gradebook.CaseGrade(name, True))
            passed_cases += [case for case in remaining if case.name == name]
        if failed is None:
            break
        message = grading.case_message(result, hidden)
        if not hidden:  # its place among all the test's cases, not among those rerun
            message = message.replace(result.headline(), f"{exercise.function}: case "
                                      f"{order.index(failed) + 1} of {len(order)}, "
                                      f"\"{failed}\", failed.", 1)
        verdicts[failed] = gradebook.CaseGrade(failed, False, message)
        given = [case.name for case in remaining]
        if failed not in given:  # a case of the check's own: the last it judges
            break
        remaining = remaining[given.index(failed) + 1:]
        if not remaining:
            unjudged = [name for name in order if name not in verdicts]
            if unjudged and passed_cases and not own_cases_judged:
                remaining, own_cases_judged = passed_cases, True  # on those that passed
                continue
            break
    names = order or [case.name for case in cases]
    return [verdicts.get(name) or gradebook.CaseGrade(
        name, False, stopped or "not judged: every case before it failed")
        for name in names], stopped


def _tests(exercise, seed):
    """The tests of an exercise: (name, hidden, points, cases)."""
    tests = [("public test", False, exercise.points, list(exercise.public_cases()))]
    for test, points in enumerate(exercise.hidden_points):
        tests.append((f"hidden test {test + 1}", True, points,
                      list(exercise.hidden_cases(exercise.generator(seed, test)))))
    return tests


def _grade_exercise(run, entry, seed):
    """Grades one implement exercise through the session `run`."""
    exercise = EXERCISES[entry.label]
    grade = gradebook.ExerciseGrade(entry.label, f"Exercise {entry.number}: {entry.title}",
                                    entry.points)
    function, why = run.function(exercise.function)
    if function is None:
        imports = any("No module named 'icm'" in error for error in run.cell_errors.values())
        grade.problem = why + (" (your notebook imports icm, which the grader does not "
                               "give your code: write the function with Python and NumPy "
                               "alone; an answer must be your own)" if imports else "")
    stopped = ""
    for name, hidden, points, cases in _tests(exercise, seed):
        test = gradebook.TestGrade(name, hidden, points)
        grade.tests.append(test)
        if function is None or stopped:
            test.cases = [gradebook.CaseGrade(case.name, False, grade.problem or
                                              f"not run: {stopped}") for case in cases]
            continue
        run.call_deadline = time.monotonic() + exercise.timeout
        test.cases, stopped = _judged(exercise, function, cases, hidden)
    return grade


def grade_submission(name, data, assignments, secret, confinement,
                     limits=sandbox.Limits(), time_limit=TIME_LIMIT,
                     cell_timeout=CELL_TIMEOUT):
    """Grades one submission. Never raises for anything the submission does: what goes
    wrong is its `problem`.

    Args:
      name: the file's name.
      data: its bytes.
      assignments: {chapter: `Assignment`}.
      secret: the run's secret (bytes), from which the hidden cases are drawn.
      confinement: a `sandbox.Confinement`, or None to run unconfined (trusted work).
      limits: a `sandbox.Limits`.
      time_limit: seconds for the whole submission.
      cell_timeout: seconds for one cell.

    Returns:
      A `gradebook.Graded`.
    """
    graded = gradebook.Graded(name)
    start = time.monotonic()
    try:
        assignment, cells = read_submission(name, data, assignments)
    except ValueError as error:
        graded.problem = str(error)
        return graded
    graded.chapter = assignment.chapter
    graded.hand_marked = [(e.label, f"Exercise {e.number}: {e.title}", e.points)
                          for e in assignment.exercises if e.kind == "extend"]
    seed = chapter_seed(secret, assignment.chapter)
    functions = [EXERCISES[e.label].function for e in assignment.autograded]
    run = session.Session(cells, functions, confinement, limits, start + time_limit,
                          cell_timeout)
    try:
        with run:
            for entry in assignment.autograded:
                if graded.problem:
                    grade = gradebook.ExerciseGrade(
                        entry.label, f"Exercise {entry.number}: {entry.title}",
                        entry.points, problem="not run (see above)")
                else:
                    try:
                        grade = _grade_exercise(run, entry, seed)
                    except session.SessionOver as error:
                        graded.problem = str(error)
                        grade = gradebook.ExerciseGrade(
                            entry.label, f"Exercise {entry.number}: {entry.title}",
                            entry.points, problem="not run (see above)")
                graded.exercises[entry.label] = grade
    except (OSError, sandbox.ConfinementError) as error:  # the grader's own trouble
        graded.problem = f"the grader could not run it ({error})"
        for entry in assignment.autograded:
            graded.exercises.setdefault(entry.label, gradebook.ExerciseGrade(
                entry.label, f"Exercise {entry.number}: {entry.title}", entry.points,
                problem="not run (see above)"))
    graded.notes = [f"cell {cell + 1} raised {error}"
                    for cell, error in sorted(run.cell_errors.items())]
    graded.notes += [f"cell {cell + 1} was left out: {reason}"
                     for cell, reason in sorted(run.left_out.items())]
    graded.peak_memory = run.peak_memory
    if run.survivors:
        graded.notes.append("a process it started could not be stopped")
    graded.seconds = time.monotonic() - start
    return graded


def _submissions(folder):
    """The notebooks of a folder: every file whose name ends in .ipynb, in any case."""
    found = []
    for path in sorted(folder.iterdir()):
        if path.name.lower().endswith(".ipynb") and not path.is_dir():
            found.append(path)
    return found


def _read(path):
    """A submission's bytes, or (None, why not): a regular file only, not through a
    link, of a sane size (`records.read_bytes`)."""
    try:
        return records.read_bytes(path, MAX_SUBMISSION_BYTES, follow=False), ""
    except records.RecordError as error:
        return None, str(error).split(": ", 1)[-1] + ": not read"


def _is_grade_sheet(path):
    """Whether a file is a grade sheet this command wrote (its header's first cells)."""
    with open(path, encoding="utf-8", errors="replace") as file:
        first = file.readline()
    return first.startswith(("submission,chapter,", "id,name,submission,chapter,"))


def grade(submissions, out, assignments="_build/assignments", feedback_dir=None,
          roster=None, time_limit=TIME_LIMIT, memory_limit=MEMORY_LIMIT,
          cell_timeout=CELL_TIMEOUT, jobs=1, trusted=False, force=False, progress=print):
    """Grades every notebook in a folder and writes the grade sheet and the feedback.

    Args:
      submissions: the folder of submitted notebooks (their .ipynb files, any case).
      out: the CSV to write.
      assignments: the folder `assign` wrote.
      feedback_dir: the folder of the feedback files (default: beside `out`, in
        "<out's stem>-feedback").
      roster: a CSV of the class (columns id, name, file), or None.
      time_limit: seconds for one submission.
      memory_limit: GiB of memory for one submission, all its processes together.
      cell_timeout: seconds for one cell.
      jobs: submissions graded at once (at most the machine's cores).
      trusted: run the notebooks unconfined (only notebooks you trust).
      force: replace an existing sheet or feedback folder that this command did not
        write.
      progress: a function of one line, told as each submission is graded.

    Returns:
      The list of `gradebook.Graded`, one per submission, in the files' order.

    Raises:
      GradeError: for a folder with no notebook, no assignment, or no confinement
        (unless `trusted`).
      ValueError: for bad limits or destinations (before any work).
    """
    time_limit = _validate.real("time_limit", time_limit, *limits.TIME_LIMIT)
    memory_limit = _validate.real("memory_limit", memory_limit, *limits.MEMORY_LIMIT)
    cell_timeout = _validate.real("cell_timeout", cell_timeout, *limits.CELL_TIMEOUT)
    jobs = _validate.integer("jobs", jobs, *limits.JOBS)
    trusted = _validate.boolean("trusted", trusted)
    try:
        submissions = records.input_folder(submissions, "the submissions' folder")
    except records.RecordError as error:
        raise GradeError(str(error)) from None
    out = pathlib.Path(out)
    feedback_dir = pathlib.Path(feedback_dir) if feedback_dir else \
        out.parent / f"{out.stem}-feedback"
    inputs = [submissions, assignments] + ([roster] if roster else [])
    files.check_file(out, own=_is_grade_sheet, force=force, inputs=inputs, what="--out")
    files.check_folder(feedback_dir, force=force, inputs=inputs + [out],
                       what="--feedback", command=COMMAND)
    paths = _submissions(submissions)
    if not paths:
        raise GradeError(f"no notebook (*.ipynb) in {submissions}")
    loaded = load_assignments(assignments)
    students = gradebook.read_roster(roster) if roster else None
    confinement = None
    if not trusted:
        confinement = sandbox.probe()
        if not confinement.available:
            raise GradeError(f"submissions cannot be confined here: {confinement.problem}. "
                             f"Grade only notebooks you trust with --trusted")
    run_limits = sandbox.Limits(memory=int(memory_limit * 2 ** 30),
                            cpu_seconds=int(time_limit) + 30)
    secret = secrets.token_bytes(32)  # this run's hidden cases; never written anywhere
    # Everything is read before any submission runs.
    contents = [(path.name, *_read(path)) for path in paths]

    def one(item):
        name, data, unread = item
        if data is None:
            graded = gradebook.Graded(name, problem=unread)
        else:
            graded = grade_submission(name, data, loaded, secret, confinement, run_limits,
                                      time_limit, cell_timeout)
        progress(f"{gradebook.printable(graded.submission)}: "
                 f"{gradebook.number(graded.total)} of "
                 f"{gradebook.number(sum(graded.possible.values()))}"
                 + (f" ({graded.problem})" if graded.problem else "") +
                 f" [{graded.seconds:.0f} s]")
        return graded

    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        results = list(pool.map(one, contents))
    gradebook.write_csv(results, loaded, out, students)
    with files.staged(feedback_dir, replace=True, command=COMMAND) as staging:
        for graded, name in zip(results, feedback_names(results)):
            files.write_text(staging / name, gradebook.feedback(graded))
    return results


def feedback_names(results):
    """Each submission's feedback file's name: its stem (cut to `FEEDBACK_STEM_BYTES`)
    and ".md", made unique whatever the case ("-2", "-3", ...), so that no student's
    feedback is written over another's.

    Args:
      results: the list of `gradebook.Graded`.

    Returns:
      The names, in the same order.
    """
    names, taken = [], set()
    for graded in results:
        stem = os.fsdecode(os.fsencode(pathlib.Path(graded.submission).stem)
                           [:FEEDBACK_STEM_BYTES])
        name, copy = f"{stem}.md", 1
        while gradebook.folded(name) in taken:
            copy += 1
            name = f"{stem}-{copy}.md"
        taken.add(gradebook.folded(name))
        names.append(name)
    return names
