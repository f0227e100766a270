"""What grading gives an instructor: each submission's points case by case, the grade
sheet (one CSV row per student, joined to a roster when there is one, with a column
for each exercise marked by hand) and each student's feedback in Markdown.

Every cell of the sheet is safe to open in a spreadsheet: a text that a spreadsheet
would read as a formula (starting with =, +, -, @, a tab or a carriage return) is
written with a leading apostrophe.
"""

import csv
import dataclasses
import html
import io
import pathlib
import re
import unicodedata

from icm import files, records

FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
"""How a spreadsheet recognises a formula (OWASP's list for CSV injection)."""


@dataclasses.dataclass
class CaseGrade:
    """One case of a test.

    Attributes:
      name: the case's name, as the student reads it.
      passed: whether the student's function got it right.
      message: why it failed ("" if it passed).
    """

    name: str
    passed: bool
    message: str = ""


@dataclasses.dataclass
class TestGrade:
    """One test of an exercise: the public test or a hidden one, worth `points`,
    shared equally among its cases.

    Attributes:
      name: "public test" or "hidden test N".
      hidden: whether its cases are hidden.
      points: its points.
      cases: its cases (`CaseGrade`).
    """

    name: str
    hidden: bool
    points: float
    cases: list = dataclasses.field(default_factory=list)

    @property
    def earned(self):
        """Its points times the share of its cases passed."""
        if not self.cases:
            return 0.0
        return self.points * sum(case.passed for case in self.cases) / len(self.cases)


@dataclasses.dataclass
class ExerciseGrade:
    """One autograded exercise of a submission.

    Attributes:
      label: the exercise's label.
      title: its number and title, e.g. "Exercise 2.1: the least-squares slope".
      possible: its points.
      tests: its tests (`TestGrade`).
      problem: why it could not be tested at all ("" if it was).
    """

    label: str
    title: str
    possible: float
    tests: list = dataclasses.field(default_factory=list)
    problem: str = ""

    @property
    def earned(self):
        """The points of its tests."""
        return sum(test.earned for test in self.tests)


@dataclasses.dataclass
class Graded:
    """One submission's grade.

    Attributes:
      submission: its file's name.
      chapter: its chapter (None if unknown).
      exercises: {label: `ExerciseGrade`} of its chapter's autograded exercises.
      hand_marked: [(label, title, points)] of its chapter's exercises marked by hand.
      problem: what went wrong with the submission as a whole ("" if nothing).
      notes: lines about the notebook (a cell that raised, a cell left out).
      seconds: how long its grading took.
      peak_memory: the most memory its processes used at once, in bytes (0 if not
        measured: unconfined).
    """

    submission: str
    chapter: str = None
    exercises: dict = dataclasses.field(default_factory=dict)
    hand_marked: list = dataclasses.field(default_factory=list)
    problem: str = ""
    notes: list = dataclasses.field(default_factory=list)
    seconds: float = 0.0
    peak_memory: int = 0

    @property
    def points(self):
        """{label: points earned}."""
        return {label: grade.earned for label, grade in self.exercises.items()}

    @property
    def possible(self):
        """{label: points possible}."""
        return {label: grade.possible for label, grade in self.exercises.items()}

    @property
    def total(self):
        """The points earned."""
        return sum(self.points.values())


def number(value):
    """Points as the sheet writes them: at most two decimals, no trailing zeros."""
    return f"{round(value, 2):g}"


def printable(text):
    """`text` with its control characters and characters that cannot be written
    escaped (a file's name printed in a terminal, or written into a sheet)."""
    text = text.encode("utf-8", "backslashreplace").decode("utf-8")
    return "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii")
                   for c in text)


def folded(name):
    """How file names are compared: compatibility-normalised and case-folded, so that
    "MIKE.ipynb" and "mi\u212ae.ipynb" (a Kelvin sign for its K) are one name."""
    return unicodedata.normalize("NFKC", name).casefold()


def _fence(text):
    """A code fence longer than any run of backticks in `text` (which then cannot close
    it and turn what follows into Markdown or HTML)."""
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    return "`" * max(3, longest + 1)


def safe_cell(value):
    """A value as a CSV cell that no spreadsheet reads as a formula.

    Args:
      value: the cell's value.

    Returns:
      Its text, with a leading apostrophe if it starts as a formula does.
    """
    text = printable(str(value))
    return "'" + text if text.lstrip().startswith(FORMULA_STARTS) else text


def read_roster(path):
    """A class roster: a CSV file with the columns `id`, `name` and `file` (other
    columns ignored), one row per student.

    Args:
      path: the file.

    Returns:
      A list of `records.RosterRow`, in the file's order.

    Raises:
      records.RecordError: for a file that cannot be read, lacks a column, or has a
        bad row (named by its line), or a repeated id or file.
    """
    path = pathlib.Path(path)
    text = records.read_text(path).removeprefix("\ufeff")  # (a spreadsheet's BOM)
    reader = csv.DictReader(io.StringIO(text))
    fields = [name.strip().lower() for name in reader.fieldnames or ()]
    missing = [name for name in ("id", "name", "file") if name not in fields]
    if missing:
        raise records.RecordError(f"{path}: the roster needs the columns id, name and "
                                  f"file; missing {', '.join(missing)}")
    rows, ids, names = [], {}, {}
    for line, raw in enumerate(reader, start=2):
        entry = {str(key).strip().lower(): value for key, value in raw.items()
                 if key is not None}
        try:
            row = records.RosterRow.model_validate(entry)
        except records.pydantic.ValidationError as error:
            raise records.RecordError(f"{path}, line {line}: {records.problem(error)}") \
                from None
        for seen, key, what in ((ids, row.id, "id"), (names, row.file.lower(), "file")):
            if key in seen:
                raise records.RecordError(f"{path}, line {line}: the {what} {key!r} is "
                                          f"also on line {seen[key]}")
            seen[key] = line
        rows.append(row)
    return rows


def write_csv(results, assignments, out, roster=None):
    """The grade sheet: one row per student (per roster row, then per submission not
    on the roster; without a roster, per submission): the student's id and name, the
    submission, its chapter, its points in each autograded exercise, an empty column
    for each exercise marked by hand, the total of the autograded points, the points
    possible and what went wrong.

    Args:
      results: the list of `Graded`.
      assignments: {chapter: assignment} (its `.exercises` of `records.
        ManifestExercise`), in the book's order.
      out: the CSV's path (written whole, through a temporary file and a rename).
      roster: a list of `records.RosterRow`, or None.
    """
    chapters = {graded.chapter for graded in results}
    columns = [(e.label, e) for chapter, assignment in assignments.items()
               if chapter in chapters for e in assignment.exercises]
    header = (["id", "name"] if roster is not None else []) + ["submission", "chapter"]
    header += [label if e.kind == "implement" else f"{label} (by hand, of {number(e.points)})"
               for label, e in columns]
    header += ["total", "possible", "problem"]
    by_file = {}
    for graded in results:
        by_file.setdefault(folded(graded.submission), []).append(graded)
    rows = []
    listed = set()
    for student in roster or ():
        matching = by_file.get(folded(student.file), [])
        exact = [graded for graded in matching if graded.submission == student.file]
        graded = exact[0] if exact else matching[0] if len(matching) == 1 else None
        if graded is None:
            why = ("no submission" if not matching else "several submissions match this "
                   "file: " + ", ".join(g.submission for g in matching))
            rows.append([student.id, student.name, student.file, ""] + [""] * len(columns)
                        + ["0", "", why])
        else:
            listed.add(id(graded))
            rows.append([student.id, student.name] + _row(graded, columns))
    for graded in results:
        if id(graded) in listed:
            continue
        row = _row(graded, columns)
        if roster is not None:
            row = ["", ""] + row
            row[-1] = "; ".join(filter(None, ["not on the roster", row[-1]]))
        rows.append(row)
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow([safe_cell(cell) for cell in header])
    for row in rows:
        writer.writerow([safe_cell(cell) for cell in row])
    files.write_text(out, buffer.getvalue())


def _row(graded, columns):
    points = graded.points
    cells = [graded.submission, graded.chapter or ""]
    for label, exercise in columns:
        cells.append(number(points[label]) if label in points else "")
    return cells + [number(graded.total), number(sum(graded.possible.values())),
                    graded.problem]


def feedback(graded):
    """A submission's feedback, in Markdown: its total, then each exercise's points
    test by test, the public cases that failed with their input, the expected and the
    given result and a hint, the hidden ones by their kind and hint only.

    Args:
      graded: its `Graded`.

    Returns:
      The text.
    """
    lines = [f"# Feedback: {html.escape(printable(graded.submission))}", ""]
    if graded.chapter is None or not graded.exercises and graded.problem:
        return "\n".join(lines + [f"Not graded: {graded.problem}.", ""])
    possible = sum(graded.possible.values())
    lines += [f"Chapter: {graded.chapter}. Autograded total: **{number(graded.total)} of "
              f"{number(possible)} points**.", ""]
    if graded.problem:
        lines += [f"**The notebook as a whole:** {graded.problem}.", ""]
    if graded.notes:
        notes = "\n".join(graded.notes)
        lines += ["**Your notebook's cells, run by the grader:**", "",
                  f"{_fence(notes)}text", notes, _fence(notes), ""]
    for grade in graded.exercises.values():
        lines += [f"## {grade.title} (`{grade.label}`): {number(grade.earned)} of "
                  f"{number(grade.possible)}", ""]
        if grade.problem:
            lines += [f"Not tested: {grade.problem}.", ""]
        said = None
        for test in grade.tests:
            passed = sum(case.passed for case in test.cases)
            lines.append(f"- {test.name} ({number(test.earned)} of {number(test.points)}): "
                         f"{passed} of {len(test.cases)} cases passed")
            if grade.problem:
                continue
            for case in test.cases:
                if case.passed:
                    continue
                if case.message == said:
                    lines.append(f"  - \"{case.name}\": failed, for the same reason")
                    continue
                fence = _fence(case.message)
                lines += [f"  - \"{case.name}\": failed", "", f"    {fence}text"]
                lines += [f"    {line}" for line in case.message.splitlines()]
                lines += [f"    {fence}", ""]
                said = case.message
        lines.append("")
    for label, title, points in graded.hand_marked:
        lines += [f"## {title} (`{label}`): marked by hand, of {number(points)}", ""]
    return "\n".join(lines)
