"""Assignments from the book: for each chapter, the student's notebook and the
autograder, written by otter-grader (`otter assign`) from the chapter's own Exercises
section.

    python -m icm.course assign OUT [--seed N] [--chapters NAME ...] [--no-run-tests] ...

One source: the chapter's notebook holds each exercise's text (its sphinx-exercise
block), its placeholder cell and its solution cells (tagged `solution`);
`icm.exercises.registry` holds each implement exercise's tests, points and time
limits. This module writes them in otter's master-notebook format (an assignment
config, then per implement exercise a question: its text, its solution with the
placeholder as the prompt, a public test and hidden tests) and runs otter assign on
it, which writes

- `OUT/<chapter>/student/<chapter>.ipynb`: what the students get: the exercises with
  their placeholders and `grader.check` cells (the public tests);
- `OUT/<chapter>/autograder/`: the solutions' notebook, the tests with the hidden ones,
  and `<chapter>-autograder_<time>.zip`, what `python -m icm.course grade` and
  Gradescope grade with.

The hidden tests draw their cases at grading time from one seed (`--seed`, or a fresh
random one), written only into the autograder's tests: keep `OUT/*/autograder` away
from students. Then each chapter's solutions' notebook is graded by its autograder as
a student's would be (`icm.course.grade`; unless `--no-run-tests`), and every test
must pass. The "predict, then check" questions stay in the book's pages (and
`python -m icm.course lms`); the "extend" exercises go into the notebook as prompts
with a cell for the answer, marked by hand.

OUT must be new, empty, or this command's (`icm.files`), unless `--force`, and not in
the book's sources; the chapters replace theirs in it only once all are written and
their solutions pass (`icm.files.staged`): a failed run leaves OUT as it was.
"""

import concurrent.futures
import dataclasses
import hashlib
import json
import pathlib
import re
import secrets
import tempfile

import nbformat
import yaml

from icm import _validate, files, records, store
from icm._book import toc_pages
from icm.course.grade import MANIFEST  # the file, beside the autograder, `manifest` writes
from icm.course.grade import MAX_JOBS  # the machine's cores
from icm.exercises.registry import EXERCISES

ROOT = store.PROJECT
"""The book's sources (ROOT/book, _toc.yml, ...), found through the package's data."""
EXERCISE = re.compile(r"\{exercise(?:-start)?\} (Implement|Predict, then check|Extend): "
                      r"(.+)\n:label: (ex-[a-z0-9-]+)")
"""An exercise's directive in a chapter: its kind, its title and its label."""
KINDS = {"Implement": "implement", "Predict, then check": "predict", "Extend": "extend"}
SOLUTION_TAG = "solution"
EXTEND_POINTS = 5.0
"""The points of an extend exercise, marked by hand (its marking guide, on the
instructors' page, is out of this many)."""
SOURCES = ("book", "_toc.yml", "_config.yml", "requirements.txt")
"""What `assign` reads in the project's folder, which OUT may be neither in nor hold."""
ROLE = re.compile(r"\{([a-z]+)(?::[a-z]+)?\}`([^`]*)`")
"""A MyST role (`{ref}`text <target>``, `{doc}`name``, ...)."""


COMMAND = "python -m icm.course assign"
"""The command, as the marker of its output folder names it (`icm.files.MARKER`)."""


class AssignError(ValueError):
    """A chapter's exercises that cannot be made into an assignment."""


@dataclasses.dataclass
class ChapterExercise:
    """One exercise of a chapter, as its notebook holds it.

    Attributes:
      label: e.g. "ex-press-outcome".
      kind: "implement", "predict" or "extend".
      title: e.g. "the rule of the console".
      prompt: the exercise's text, as Jupyter's Markdown (the directive taken off).
      placeholder: an implement exercise's placeholder cell (else "").
      solution: an implement exercise's solution code (else "").
    """

    label: str
    kind: str
    title: str
    prompt: str
    placeholder: str = ""
    solution: str = ""


def chapters(root=ROOT):
    """The book's chapters, in order: [(name, notebook path)].

    Args:
      root: the project's folder.

    Returns:
      The list.
    """
    try:
        pages = toc_pages(root, "Chapters")
    except ValueError:  # no part "Chapters"
        pages = []
    found = [(path.stem, path) for path in (root / f"{page}.ipynb" for page in pages)
             if path.exists()]
    if not found:
        raise AssignError(f"no chapter notebooks found from {root / '_toc.yml'}: run this "
                          f"from a clone of the project")
    return found


def _tags(cell):
    return cell.get("metadata", {}).get("tags", [])


def markdown_of(source):
    """An exercise's MyST text as plain Markdown for Jupyter: the directive's fences
    and options taken off, roles replaced by their text.

    Args:
      source: the cell's source.

    Returns:
      The text.

    Raises:
      AssignError: for a glued number ({glue}), which only the book can show.
    """
    lines = [line for line in source.splitlines()
             if not re.match(r"\s*(```|:::)(\{exercise(-start)?\}.*)?\s*$", line)
             and not re.match(r":(label|class): ", line)]
    text = "\n".join(lines).strip()
    if "{glue" in text:
        raise AssignError(f"an exercise's text quotes a glued number: {text[:80]}...")

    def role(match):
        name, content = match.groups()
        target = re.match(r"(.*?)\s*<([^>]*)>$", content)
        return target.group(1) if target else f"*{content}*" if name == "doc" else content
    return ROLE.sub(role, text)


def chapter_exercises(path):
    """The exercises of a chapter's notebook, in order.

    Args:
      path: the notebook.

    Returns:
      A list of `ChapterExercise`.

    Raises:
      AssignError: for an implement exercise without its placeholder or solution.
    """
    cells = nbformat.read(path, as_version=4).cells
    found = []
    for i, cell in enumerate(cells):
        match = EXERCISE.search(cell.source) if cell.cell_type == "markdown" else None
        if not match or SOLUTION_TAG in _tags(cell):
            continue
        kind, title, label = KINDS[match.group(1)], match.group(2).strip(), match.group(3)
        exercise = ChapterExercise(label, kind, title, markdown_of(cell.source))
        if kind == "implement":
            placeholder = cells[i + 1]
            if placeholder.cell_type != "code" or "raise NotImplementedError" not in \
                    placeholder.source:
                raise AssignError(f"{path.name}: {label} has no placeholder cell after it")
            exercise.placeholder = placeholder.source
            solution, inside = [], False
            for other in cells[i + 1:]:
                if SOLUTION_TAG in _tags(other) and f"{{solution-start}} {label}" in \
                        other.source:
                    inside = True
                elif inside and "{solution-end}" in other.source:
                    break
                elif inside and other.cell_type == "code" and \
                        "exercises.check_" not in other.source:
                    solution.append(other.source)
            if not solution:
                raise AssignError(f"{path.name}: {label} has no solution code")
            exercise.solution = "\n\n\n".join(solution)
        found.append(exercise)
    return found


def _title(path):
    for cell in nbformat.read(path, as_version=4).cells:
        heading = re.match(r"#\s+(.+)", cell.source) if cell.cell_type == "markdown" else None
        if heading:
            return heading.group(1).strip()
    return path.stem.replace("_", " ")


def _install_cell(path):
    """The chapter's first cell (it installs icm on Binder and Colab when missing)."""
    first = nbformat.read(path, as_version=4).cells[0]
    return first.source if first.cell_type == "code" else ""


def pinned(name, root=ROOT):
    """The version requirements.txt pins for a package.

    Args:
      name: the package's name.
      root: the project's folder.

    Returns:
      "name==version".

    Raises:
      AssignError: if it is not pinned there.
    """
    for line in (root / "requirements.txt").read_text().splitlines():
        if re.match(rf"{re.escape(name)}==", line.strip()):
            return line.strip()
    raise AssignError(f"requirements.txt pins no {name}")


def _repository(root=ROOT):
    config = yaml.safe_load((root / "_config.yml").read_text())["repository"]
    return config["url"], config.get("branch", "main")


def _raw(source):
    return nbformat.v4.new_raw_cell(source)


def _test_cell(function, body, points, hidden):
    config = f"points: {points}\n" + ("hidden: true\n" if hidden else "")
    return nbformat.v4.new_code_cell(
        f'""" # BEGIN TEST CONFIG\n{config}""" # END TEST CONFIG\n{body}')


def master_notebook(name, path, seed, root=ROOT):
    """The otter master notebook of one chapter's assignment.

    Args:
      name: the chapter's name (its notebook's stem).
      path: its notebook.
      seed: the grading seed written into the hidden tests.
      root: the project's folder.

    Returns:
      An nbformat notebook.

    Raises:
      AssignError: for an implement exercise that `icm.exercises.registry` does not
        know, or whose placeholder defines another function.
    """
    exercises = [e for e in chapter_exercises(path) if e.kind != "predict"]
    url, branch = _repository(root)
    config = {
        "name": name,
        "requirements": "requirements.txt",
        "python_version": "3.11",
        "init_cell": False,
        "check_all_cell": False,
        "export_cell": {"pdf": False, "run_tests": False,
                        "instructions": "Or hand in this notebook itself (the .ipynb file)."},
        "run_tests": True,
        "solutions_pdf": False,
        "template_pdf": False,
        "tests": {"files": False, "ok_format": False},
        "generate": {"pdf": False, "show_hidden": False, "show_stdout": False},
    }
    title = _title(path)
    cells = [_raw("# ASSIGNMENT CONFIG\n" + yaml.safe_dump(config, sort_keys=False)),
             nbformat.v4.new_markdown_cell(
                 f"# {title}: exercises\n\n"
                 f"The exercises of the chapter *{title}* "
                 f"([the chapter's notebook]({url}/blob/{branch}/book/{name}.ipynb)); read the "
                 f"chapter first.\n\n"
                 f"Write each function in the cell under its exercise, in place of `raise "
                 f"NotImplementedError`, run that cell, then run the `grader.check` cell "
                 f"below it: it tries your function on the cases the book's check shows, and "
                 f"says which case fails, with its input, the expected and the given result, "
                 f"and a hint. Your grade also rests on **hidden tests**: cases of the same "
                 f"kinds, drawn when your notebook is graded, whose values you never see. "
                 f"Keep each function's name, and write it with Python and NumPy alone: "
                 f"when your notebook is graded, its code runs on its own, where icm is not "
                 f"installed (an answer must be your own code, so the library's "
                 f"implementation of what it asks for is not there to call). Each case of a "
                 f"test earns its share of the test's points. The extend exercises are "
                 f"marked by hand."),
             nbformat.v4.new_code_cell(
                 "import numpy as np\n\n" + _install_cell(path).rstrip() + "\n\n"
                 f"# The grader of this notebook's checks, when missing.\n"
                 f"if importlib.util.find_spec(\"otter\") is None:\n"
                 f"    subprocess.check_call([sys.executable, \"-m\", \"pip\", \"install\", "
                 f"\"--quiet\", \"{pinned('otter-grader', root)}\"])\n\n"
                 f"import otter\n\ngrader = otter.Notebook(\"{name}.ipynb\")")]
    numbers = exercise_numbers(name, path, root)
    for exercise in exercises:
        heading = (f"## Exercise {numbers[exercise.label]}. {exercise.kind.capitalize()}: "
                   f"{exercise.title}\n\n")
        if exercise.kind == "extend":
            cells += [nbformat.v4.new_markdown_cell(
                heading + exercise.prompt + "\n\n*Marked by hand. Where the exercise "
                "uses the chapter's runs, work in the chapter's notebook and write your "
                "answer here.*"),
                      nbformat.v4.new_code_cell("# Your work here."),
                      nbformat.v4.new_markdown_cell("*Your answer here.*")]
            continue
        registered = EXERCISES.get(exercise.label)
        if registered is None:
            raise AssignError(f"{path.name}: {exercise.label} is not in "
                              f"icm.exercises.registry.EXERCISES")
        if not re.search(rf"def {re.escape(registered.function)}\(", exercise.placeholder):
            raise AssignError(f"{path.name}: the placeholder of {exercise.label} does not "
                              f"define {registered.function}")
        if "'''" in exercise.placeholder:
            raise AssignError(f"{path.name}: the placeholder of {exercise.label} holds '''")
        question = {"name": exercise.label, "points": None}
        function = registered.function
        cells += [
            _raw("# BEGIN QUESTION\n" + yaml.safe_dump(question, sort_keys=False)),
            nbformat.v4.new_markdown_cell(heading + exercise.prompt +
                                          f"\n\n*{registered.total:g} points: the public "
                                          f"test {registered.points:g}, the hidden tests "
                                          f"{sum(registered.hidden_points):g}.*"),
            _raw("# BEGIN SOLUTION"),
            # The student's notebook gets the placeholder (otter's prompt lines), the
            # solutions' notebook the solution.
            nbformat.v4.new_code_cell(
                "# BEGIN SOLUTION NO PROMPT\n" + exercise.solution.rstrip() +
                "\n# END SOLUTION\n''' # BEGIN PROMPT\n" + exercise.placeholder.rstrip() +
                "\n''' # END PROMPT"),
            _raw("# END SOLUTION"),
            _raw("# BEGIN TESTS"),
            _test_cell(function,
                       f"def test_public({function}):\n"
                       f"    from icm.course.grading import public_test\n"
                       f"    public_test(\"{exercise.label}\", {function})",
                       registered.points, hidden=False)]
        for test, points in enumerate(registered.hidden_points):
            cells.append(_test_cell(
                function,
                f"def test_hidden_{test + 1}({function}):\n"
                f"    from icm.course.grading import hidden_test\n"
                f"    seed = {chapter_seed(seed, name)}\n"
                f"    hidden_test(\"{exercise.label}\", {function}, seed, {test})",
                points, hidden=True))
        cells += [_raw("# END TESTS"), _raw("# END QUESTION")]
    notebook = nbformat.v4.new_notebook(cells=cells)
    notebook.metadata["kernelspec"] = {"display_name": "Python 3", "language": "python",
                                       "name": "python3"}
    notebook.metadata["language_info"] = {"name": "python"}
    return notebook


def grading_requirements(root=ROOT):
    """What a grading machine (Gradescope's) installs: the project's pins and icm.

    Args:
      root: the project's folder.

    Returns:
      The text of a requirements file.
    """
    url, branch = _repository(root)
    lines = [line.strip() for line in (root / "requirements.txt").read_text().splitlines()
             if line.strip() and not line.lstrip().startswith("#")]
    return "\n".join(lines + [f"icm @ git+{url}@{branch}"]) + "\n"


def assign_chapter(name, path, out, seed, root=ROOT):
    """Writes one chapter's assignment into `out/<name>`, a folder that must not exist
    yet, with otter assign.

    Args:
      name: the chapter's name.
      path: its notebook.
      out: the output folder.
      seed: the grading seed.
      root: the project's folder.

    Returns:
      The folder written.

    Raises:
      AssignError: when the student's notebook holds what it must not.
      icm.files.DestinationError: if `out/<name>` exists (this never replaces one).
    """
    import contextlib
    import io
    import logging

    from otter.assign import main as otter_assign

    result = pathlib.Path(out).resolve() / name
    if result.exists() or result.is_symlink():
        raise files.DestinationError(f"{result} exists: assign_chapter writes a new folder")
    with tempfile.TemporaryDirectory(prefix=f"icm-assign-{name}-") as folder:
        master = pathlib.Path(folder) / f"{name}.ipynb"
        nbformat.write(master_notebook(name, path, seed, root), master)
        (master.parent / "requirements.txt").write_text(grading_requirements(root))
        logging.getLogger("otter").setLevel(logging.WARNING)  # (its summary, per chapter)
        with contextlib.redirect_stdout(io.StringIO()):
            otter_assign(str(master), str(result), no_pdfs=True, no_run_tests=True)
    check_student_notebook(name, path, result, seed)
    files.write_text(result / "autograder" / MANIFEST, _manifest_text(name, path))
    return result


def _manifest_text(name, path):
    """The file `MANIFEST` (`manifest`), read back with the grader's model first."""
    text = json.dumps(manifest(name, path), indent=1)
    records.parse_json(text, records.Manifest, f"{name}'s manifest")  # (names the field)
    return text


def check_solutions(written, jobs=2, progress=print):
    """Grades each chapter's solutions' notebook with its own autograder, as a
    student's notebook would be graded: every test must pass.

    Args:
      written: {chapter name: its assignment's folder}.
      jobs: notebooks graded at once.
      progress: a function of one line.

    Raises:
      AssignError: naming each test the solutions fail.
    """
    from icm.course import grade, sandbox

    folder = pathlib.Path(next(iter(written.values()))).parent
    assignments = grade.load_assignments(folder)
    confinement = sandbox.probe()  # our own notebooks: confined where it can be
    secret = secrets.token_bytes(32)

    def one(name):
        notebook = (written[name] / "autograder" / f"{name}.ipynb").read_bytes()
        return grade.grade_submission(f"{name} (solutions)", notebook, assignments, secret,
                                      confinement if confinement.available else None)

    failed = []
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        for graded in pool.map(one, written):
            possible = sum(graded.possible.values())
            progress(f"{graded.submission}: {graded.total:g} of {possible:g} points")
            if graded.problem or graded.total < possible:
                failed.append(f"{graded.submission}: {graded.total:g} of {possible:g} "
                              f"{graded.problem}".strip() + "; " + "; ".join(
                                  f"{label}, {test.name}, {case.name}: {case.message}"
                                  for label, exercise in graded.exercises.items()
                                  for test in exercise.tests for case in test.cases
                                  if not case.passed))
    if failed:
        raise AssignError("the solutions fail their own tests: " + " | ".join(failed))


def manifest(name, path):
    """What the grader needs to know of a chapter's assignment besides otter's
    autograder: its title and its autograded exercises, in order, with their points.

    Args:
      name: the chapter's name.
      path: its notebook.

    Returns:
      A dict.
    """
    numbers = exercise_numbers(name, path)
    return {"chapter": name, "number": int(numbers["chapter"]), "title": _title(path),
            "exercises": [{"label": e.label, "title": e.title, "number": numbers[e.label],
                           "kind": e.kind,
                           "function": EXERCISES[e.label].function if e.kind == "implement"
                           else None,
                           "points": EXERCISES[e.label].total if e.kind == "implement"
                           else EXTEND_POINTS}
                          for e in chapter_exercises(path) if e.kind != "predict"]}


def exercise_numbers(name, path, root=ROOT):
    """The numbers the book gives a chapter's exercises ("2.4": the chapter's number,
    then the exercise's place among all the chapter's exercises), which the
    assignment's notebook, its grade sheet and the instructors' marking guides share.

    Args:
      name: the chapter's name.
      path: its notebook.
      root: the project's folder.

    Returns:
      {label: "N.k"}, and "chapter": "N" (0 for a notebook outside the book's
      chapters).
    """
    order = [found for found, _ in chapters(root)]
    chapter = order.index(name) + 1 if name in order else 0
    numbers = {e.label: f"{chapter}.{k}" for k, e in enumerate(chapter_exercises(path), 1)}
    numbers["chapter"] = str(chapter)
    return numbers


def chapter_seed(seed, name):
    """The seed of one chapter's hidden tests in its autograder zip (what Gradescope
    runs): the assignment's seed and the chapter's name, hashed, so that one chapter's
    autograder says nothing of another's hidden cases.

    Args:
      seed: the assignment's seed, an integer >= 0.
      name: the chapter's name.

    Returns:
      An integer >= 0 (of 63 bits).
    """
    digest = hashlib.blake2b(f"{seed}:{name}".encode(), digest_size=8).digest()
    return int.from_bytes(digest, "big") >> 1


def check_student_notebook(name, path, result, seed):
    """Refuses a student's notebook that holds a solution line, a hidden test or the
    seed.

    Args:
      name: the chapter's name.
      path: the chapter's notebook.
      result: the assignment's folder.
      seed: the grading seed.

    Raises:
      AssignError: naming what leaked.
    """
    student = nbformat.read(result / "student" / f"{name}.ipynb", as_version=4)
    text = "\n".join(cell.source for cell in student.cells) + "\n" + str(student.metadata)
    placeholders = "\n".join(e.placeholder for e in chapter_exercises(path))
    for exercise in chapter_exercises(path):
        for line in exercise.solution.splitlines():
            line = line.strip()
            if len(line) > 25 and line not in placeholders and line in text:
                raise AssignError(f"{name}: the student's notebook holds a solution line: "
                                  f"{line}")
    if "hidden_test" in text:
        raise AssignError(f"{name}: the student's notebook holds a hidden test")
    if re.search(rf"(?<!\d){chapter_seed(seed, name)}(?!\d)", text):
        raise AssignError(f"{name}: the student's notebook holds the hidden tests' seed")


def assign(out, seed=None, names=None, run_tests=True, jobs=min(2, MAX_JOBS), root=ROOT,
           progress=print, force=False):
    """Writes every chapter's assignment (or those named) into `out`.

    Everything is checked before any work, `out` too (`icm.files.check_folder`); the
    chapters replace theirs in `out` only once all are written and pass.

    Args:
      out: the output folder.
      seed: the grading seed, an integer in 0..2**63-1 (None: a fresh random one).
      names: the chapters to write (None: every chapter with an implement exercise).
      run_tests: whether to grade each chapter's solutions with its autograder (every
        test must pass; a minute or two).
      jobs: solutions graded at once, from 1 to the machine's cores.
      root: the project's folder.
      progress: a function of one line, told what is done.
      force: write into an existing folder that icm did not write (its other files
        stay; a chapter's folder of the same name is replaced).

    Returns:
      {chapter name: its folder}.

    Raises:
      AssignError: for an unknown chapter or a chapter that cannot be assigned.
      icm.files.DestinationError: for an `out` refused (see `icm.files.check_folder`).
      ValueError: for a bad seed or jobs.
    """
    seed = secrets.randbelow(2 ** 31) if seed is None else _validate.seed("seed", seed)
    jobs = _validate.integer("jobs", jobs, 1, MAX_JOBS)
    run_tests = _validate.boolean("run_tests", run_tests)
    force = _validate.boolean("force", force)
    known = dict(chapters(root))
    if names is not None:
        unknown = sorted(set(names) - set(known))
        if unknown:
            raise AssignError(f"unknown chapters {unknown}; the chapters are {sorted(known)}")
        known = {name: known[name] for name in names}
    out = files.check_folder(out, force=force, inputs=[root / name for name in SOURCES],
                             what="OUT", command=COMMAND)
    todo = {name: path for name, path in known.items()
            if any(e.kind == "implement" for e in chapter_exercises(path))}
    if not todo:
        raise AssignError(f"no implement exercise in the chapters {sorted(known)}: nothing "
                          f"to assign")
    for name, path in todo.items():
        _manifest_text(name, path)  # (before any work)
    with files.staged(out, command=COMMAND) as staging:
        written = {}
        for name, path in todo.items():
            written[name] = assign_chapter(name, path, staging, seed, root)
            progress(f"[{len(written)}/{len(todo)}] {name}: "
                     f"{out / name / 'student' / (name + '.ipynb')}")
        if run_tests:
            progress("grading each chapter's solutions with its autograder ...")
            check_solutions(written, jobs, progress)
    return {name: out / name for name in todo}
