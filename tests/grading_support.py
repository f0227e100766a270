"""What the grading tests share: the assignments of two chapters, written once per test
process, the book's solutions, and a builder of submissions (a student's notebook with
its answer cells replaced and cells of one's own added)."""

import csv
import pathlib
import re

import nbformat
import numpy as np

from conftest import ROOT

from icm.course import assign
from icm.exercises.registry import EXERCISES

SEED = 20261202
"""The assignments' seed (their autograder zips'; the local grader draws its own)."""
CHAPTER = "goal_oriented_interest"
"""The chapter graded end to end: two implement exercises (the slope, the interest of a
task) and an extend exercise."""
CHAPTERS = (CHAPTER, "forming_actions")
"""The chapters written: the second has the goal-choice rule, drawn thousands of times
from the generator it is given."""
WRONG = {
    # The slope divided by n instead of the spread: right only where the slope is 0.
    "least_squares_slope": """def least_squares_slope(values):
    n = len(values)
    x_mean, y_mean = (n - 1) / 2, sum(values) / n
    return sum((x - x_mean) * (y - y_mean) for x, y in enumerate(values)) / n
""",
    # The interest without its new-task rule.
    "task_interest": """def task_interest(history, others, window=5, new_task_factor=0.5):
    if len(history) < 2:
        return 0.0
    recent = history[-window:]
    n = len(recent)
    x_mean, y_mean = (n - 1) / 2, sum(recent) / n
    slope = sum((x - x_mean) * (y - y_mean) for x, y in enumerate(recent)) / sum(
        (x - x_mean) ** 2 for x in range(n))
    return max(0.0, -slope)
""",
}
"""Typical wrong answers, each right on some cases and wrong on others."""
INTEREST_OWN = """def task_interest(history, others, window=5, new_task_factor=0.5):
    if len(history) == 0:
        return 0.0
    if len(history) == 1:
        return new_task_factor * sum(others) / len(others) if others else 0.0
    recent = history[-window:]
    n = len(recent)
    x_mean, y_mean = (n - 1) / 2, sum(recent) / n
    slope = sum((x - x_mean) * (y - y_mean) for x, y in enumerate(recent)) / sum(
        (x - x_mean) ** 2 for x in range(n))
    return max(0.0, -slope)
"""
"""A right interest of a task that needs no other answer of the notebook."""


def solutions():
    """{function name: the book's solution's source}, from the chapters' notebooks."""
    found = {}
    for _, path in assign.chapters():
        for exercise in assign.chapter_exercises(path):
            if exercise.kind == "implement":
                found[EXERCISES[exercise.label].function] = exercise.solution
    return found


SOLUTIONS = solutions()


def solution_functions():
    """{function name: the book's solution, defined}."""
    namespace = {"np": np}
    for source in SOLUTIONS.values():
        exec(source, namespace)
    return namespace


def write_assignments(out):
    """The assignments of `CHAPTERS` in `out` (otter assign, without grading the
    solutions: the tests do)."""
    assign.assign(out, seed=SEED, names=list(CHAPTERS), run_tests=False,
                  progress=lambda _: None)
    return out


def student_notebook(out, chapter=CHAPTER):
    """The path of a chapter's student's notebook."""
    return pathlib.Path(out) / chapter / "student" / f"{chapter}.ipynb"


def submission(out, folder, name, answers=None, extra=(), chapter=CHAPTER, setup=None,
               solved=True, last=()):
    """Writes a submission: the student's notebook of `chapter` with each answer cell
    replaced (by the function it defines: `answers`, else the book's solution if
    `solved`, else left as the placeholder), the cells `extra` added after the setup
    cell and the cells `last` at the end, and the setup cell replaced by `setup` if
    given.

    Returns:
      Its path.
    """
    answers = dict(answers or {})
    notebook = nbformat.read(student_notebook(out, chapter), as_version=4)
    cells = []
    for cell in notebook.cells:
        defined = re.search(r"def (\w+)\(", cell.source) if cell.cell_type == "code" else None
        if defined and "otter_answer_cell" in cell.metadata.get("tags", []):
            function = defined.group(1)
            if function in answers:
                cell.source = answers[function]
            elif solved:
                cell.source = SOLUTIONS[function]
        if cell.cell_type == "code" and "grader = otter.Notebook" in cell.source:
            if setup is not None:
                cell.source = setup
            cells.append(cell)
            cells += [nbformat.v4.new_code_cell(source) for source in extra]
            continue
        cells.append(cell)
    notebook.cells = cells + [nbformat.v4.new_code_cell(source) for source in last]
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.ipynb"
    nbformat.write(notebook, path)
    return path


def rows(sheet):
    """{submission: row} of a grade sheet."""
    with open(sheet, newline="") as file:
        return {row["submission"]: row for row in csv.DictReader(file)}


__all__ = ["ROOT", "SEED", "CHAPTER", "CHAPTERS", "WRONG", "INTEREST_OWN", "SOLUTIONS", "rows",
           "solution_functions", "student_notebook", "submission", "write_assignments"]
