"""The course: each chapter's assignment written by otter from the chapter's own
exercises (placeholders and public tests for the students, solutions and hidden tests
for the autograder only, numbered as the book numbers them), the in-kernel tests of the
students' notebooks (their time limits and the own-answer rule), the questions
exported to Moodle XML and read back, and the instructors' page's directives (the slide
decks are in tests/test_slides.py). Grading a class is in tests/test_grading.py, and
the attacks on it in tests/test_grading_attacks.py."""

import dataclasses
import json
import re
import subprocess
import sys
import zipfile

import nbformat
import numpy as np
import pytest

from conftest import ROOT

from icm.course import assign, grade, grading, lms
from icm.exercises.registry import EXERCISES

SEED = 20261202
"""The grading seed of the tests' assignments."""


def _solutions():
    namespace = {"np": np}
    for _, path in assign.chapters():
        for exercise in assign.chapter_exercises(path):
            if exercise.kind == "implement":
                exec(exercise.solution, namespace)
    return namespace


SOLUTIONS = _solutions()


# --- the registry and the hidden cases ---------------------------------------------------

def test_the_registry_holds_every_implement_exercise_of_the_book_and_no_other():
    book = {}
    for name, path in assign.chapters():
        for exercise in assign.chapter_exercises(path):
            if exercise.kind == "implement":
                book[exercise.label] = exercise
    assert sorted(book) == sorted(EXERCISES)
    for label, exercise in EXERCISES.items():
        assert f"def {exercise.function}(" in book[label].placeholder, label
        assert exercise.total == exercise.points + sum(exercise.hidden_points) > 0
        assert exercise.timeout > 0 and len(exercise.hidden_points) >= 2


@pytest.mark.parametrize("label", sorted(EXERCISES))
def test_the_books_solution_passes_the_public_and_every_hidden_test(label):
    exercise = EXERCISES[label]
    function = SOLUTIONS[exercise.function]
    grading.public_test(label, function)
    for seed in (SEED, 7):
        for test in range(len(exercise.hidden_points)):
            grading.hidden_test(label, function, seed, test)


@pytest.mark.parametrize("label", sorted(EXERCISES))
def test_hidden_cases_are_drawn_from_the_seed_in_the_public_cases_shapes(label):
    exercise = EXERCISES[label]
    public = exercise.public_cases()
    first = exercise.hidden_cases(exercise.generator(SEED, 0))
    again = exercise.hidden_cases(exercise.generator(SEED, 0))
    assert [c.args for c in first] == [c.args for c in again]  # one seed, one draw
    # Other seeds and other tests draw other cases (the console's few layouts may
    # repeat now and then: among five draws, several differ).
    draws = {repr([c.args for c in exercise.hidden_cases(exercise.generator(seed, test))])
             for seed in (SEED, SEED + 1, SEED + 2) for test in (0, 1)}
    assert len(draws) >= 3, label
    assert all(c.name.endswith(")") and "hidden" in c.name for c in first)
    # Of the same shapes: the same argument count and types as the public cases'.
    shapes = {tuple(type(a).__name__ for a in c.args) for c in public}
    assert {tuple(type(a).__name__ for a in c.args) for c in first} <= shapes, label
    # A table of the public cases' answers fails every hidden test. (A goal-choice
    # rule is random: its table, choices replayed, cannot pass the public generator
    # case either.)
    table = _lookup_table(exercise)
    assert exercise.takes_generator or exercise.public(table).passed, label
    for test in range(len(exercise.hidden_points)):
        result = exercise.hidden(table, SEED, test)
        assert not result.passed and result.borrowed is None, (label, test)


def _lookup_table(exercise):
    """An answer that returns the book's solution's results on the public cases only,
    from a table, and a constant elsewhere: the cheat of the hard-coded submission."""
    solution = SOLUTIONS[exercise.function]
    if exercise.takes_generator:  # the choices made on the check's own generators
        return _replaying(exercise, solution)
    answers = {}
    for case in exercise.public_cases():
        arguments = _copy(case.args)
        result = solution(*arguments)
        answers[repr(case.args)] = (result, arguments)

    def table(*args):
        found = answers.get(repr(args))
        if found is None:
            return 0.0
        result, changed = found
        for given, wanted in zip(args, changed):  # in-place changes, replayed
            if isinstance(given, list):
                given[:] = _copy(wanted)
            elif isinstance(given, dict):
                given.clear()
                given.update(_copy(wanted))
        return result
    return table


def _replaying(exercise, solution):
    """A goal-choice "table": the solution's choices recorded on the public check's
    generators (seeds 1000, 1001, ...) and played back, whatever generator it is
    given."""
    from icm.exercises import goal_choice

    recorded = {}
    for i, case in enumerate(exercise.public_cases()):
        rng = np.random.default_rng(1000 + i)
        recorded[repr(case.args)] = [solution(list(case.args[0]), case.args[1], rng)
                                     for _ in range(goal_choice.DRAWS)]
    played = {}

    def table(interests, epsilon, rng):
        key = repr((list(interests), epsilon))
        choices = recorded.get(key)
        if choices is None:
            return 0
        position = played.get(key, 0)
        played[key] = position + 1
        return choices[position % len(choices)]
    return table


def _copy(value):
    import copy

    return copy.deepcopy(value)


def test_a_hidden_tests_failure_shows_neither_the_input_nor_the_expected_result():
    exercise = EXERCISES["ex-least-squares-slope"]
    wrong = lambda values: (values[-1] - values[0]) / (len(values) - 1)  # the endpoints
    result = exercise.hidden(wrong, SEED, 0)
    assert not result.passed
    with pytest.raises(AssertionError) as raised:
        grading.hidden_test("ex-least-squares-slope", wrong, SEED, 0)
    message = str(raised.value)
    assert result.case.name in message and "Hint:" in message
    assert str(list(result.case.args[0])[0]) not in message
    assert "expected" not in message and f"{result.expected}" not in message
    with pytest.raises(AssertionError) as raised:  # the public test: the full report
        grading.public_test("ex-least-squares-slope", wrong)
    assert "expected:" in str(raised.value) and "input:" in str(raised.value)


def test_an_answer_that_calls_the_library_gets_zero_on_every_test_of_the_exercise():
    from icm.learners.interest import least_squares_slope

    cheats = [
        lambda values: least_squares_slope(values),
        # Right on the cases it was shown (a table), the library's elsewhere.
        _table_or_library(EXERCISES["ex-least-squares-slope"], least_squares_slope),
        # Wrong on an early case, the library's later.
        lambda values: 0.0 if len(values) == 2 else least_squares_slope(values),
    ]
    exercise = EXERCISES["ex-least-squares-slope"]
    for cheat in cheats:
        for test in [None] + list(range(len(exercise.hidden_points))):
            with pytest.raises(AssertionError, match="0 points for this exercise") as raised:
                if test is None:
                    grading.public_test(exercise.label, cheat)
                else:
                    grading.hidden_test(exercise.label, cheat, SEED, test)
            assert "icm.learners.interest.least_squares_slope" in str(raised.value)


def _table_or_library(exercise, library):
    table = {repr(c.args): SOLUTIONS[exercise.function](*c.args)
             for c in exercise.public_cases()}
    return lambda values: table.get(repr((values,))) if repr((values,)) in table \
        else library(values)


def test_each_test_has_a_time_limit_a_loop_cannot_catch(monkeypatch):
    import time

    quick = dataclasses.replace(EXERCISES["ex-red-first"], timeout=1.0)
    monkeypatch.setitem(EXERCISES, "ex-red-first", quick)

    def loops(red_trial, green_trial):
        while True:
            try:
                time.sleep(0.01)
            except Exception:  # a student's catch-all does not swallow the limit
                pass

    start = time.monotonic()
    with pytest.raises(AssertionError, match="more than 1 s"):
        grading.public_test("ex-red-first", loops)
    for test in range(len(quick.hidden_points)):  # not run again: each would wait
        with pytest.raises(AssertionError, match="earlier test"):
            grading.hidden_test("ex-red-first", loops, SEED, test)
    assert time.monotonic() - start < 10

    def exits(red_trial, green_trial):
        raise SystemExit(3)
    with pytest.raises(AssertionError, match="SystemExit"):
        grading.public_test("ex-red-first", exits)


def test_a_missing_or_unknown_function_fails_with_a_sentence():
    with pytest.raises(AssertionError, match="`red_first` is not defined"):
        grading.public_test("ex-red-first", None)
    with pytest.raises(AssertionError, match="no implement exercise"):
        grading.public_test("ex-nothing", SOLUTIONS["red_first"])


# --- otter's assignments --------------------------------------------------------------

@pytest.fixture(scope="module")
def assignments(tmp_path_factory):
    """Every chapter's assignment, as `make assignments` writes it (otter assign), but
    without otter's run of the tests on the solutions (the tests above run them)."""
    out = tmp_path_factory.mktemp("assignments")
    written = assign.assign(out, seed=SEED, run_tests=False, progress=lambda _: None)
    return out, written


def _implement(path):
    return [e for e in assign.chapter_exercises(path) if e.kind == "implement"]


def test_each_chapter_gets_a_students_notebook_and_an_autograder(assignments):
    out, written = assignments
    with_implement = [name for name, path in assign.chapters() if _implement(path)]
    assert sorted(written) == sorted(with_implement) and len(written) == 8
    for name, path in assign.chapters():
        folder = out / name
        notebook = nbformat.read(folder / "student" / f"{name}.ipynb", as_version=4)
        assert notebook.metadata["otter"]["assignment_name"] == name
        text = "\n".join(cell.source for cell in notebook.cells)
        code = "\n".join(cell.source for cell in notebook.cells if cell.cell_type == "code")
        implement = _implement(path)
        assert code.count("raise NotImplementedError") == len(implement)
        for exercise in assign.chapter_exercises(path):
            if exercise.kind == "predict":
                continue
            assert exercise.title in text, (name, exercise.label)
            if exercise.kind == "implement":
                assert f'grader.check("{exercise.label}")' in text
                assert exercise.placeholder.strip() in text
        manifest = json.loads((folder / "autograder" / assign.MANIFEST).read_text())
        number = [n for n, _ in assign.chapters()].index(name) + 1
        graded = [e for e in assign.chapter_exercises(path) if e.kind != "predict"]
        assert [e["label"] for e in manifest["exercises"]] == [e.label for e in graded]
        assert manifest["number"] == number
        # Numbered as the book numbers them (the marking guides' "Exercise N.k").
        everything = [e.label for e in assign.chapter_exercises(path)]
        for entry in manifest["exercises"]:
            assert entry["number"] == f"{number}.{everything.index(entry['label']) + 1}"
            assert f"## Exercise {entry['number']}. " in text
        assert len(list((folder / "autograder").glob("*-autograder_*.zip"))) == 1
    # The grade sheet's columns follow the book.
    loaded = grade.load_assignments(out)
    assert list(loaded) == [name for name, _ in assign.chapters()]


def test_no_solution_and_no_hidden_test_reaches_a_student(assignments):
    out, _ = assignments
    for name, path in assign.chapters():
        notebook = nbformat.read(out / name / "student" / f"{name}.ipynb", as_version=4)
        text = "\n".join(cell.source for cell in notebook.cells)
        everything = text + json.dumps(notebook.metadata)
        assert str(assign.chapter_seed(SEED, name)) not in everything
        assert "hidden_test" not in everything
        assert "hidden=True" not in everything
        for exercise in _implement(path):
            for line in exercise.solution.splitlines():
                if len(line.strip()) > 25 and line.strip() not in exercise.placeholder:
                    assert line.strip() not in everything, (name, line)
        public = notebook.metadata["otter"]["tests"]
        assert sorted(public) == sorted(e.label for e in _implement(path))
        for label, source in public.items():
            assert "public_test" in source and source.count("@test_case") == 1


def test_the_autograder_zip_holds_the_hidden_tests_and_what_gradescope_runs(assignments):
    from otter.test_files.exception_test import ExceptionTestFile

    out, _ = assignments
    for name, path in assign.chapters():
        (zip_path,) = (out / name / "autograder").glob("*-autograder_*.zip")
        with zipfile.ZipFile(zip_path) as archive:
            names = set(archive.namelist())
            assert {"run_autograder", "setup.sh", "otter_config.json",
                    "environment.yml"} <= names
            config = json.loads(archive.read("otter_config.json"))
            assert config["assignment_name"] == name and config["show_hidden"] is False
            environment = archive.read("environment.yml").decode()
            assert assign.pinned("otter-grader") in environment
            assert "icm @ git+https://github.com/" in environment
            for exercise in _implement(path):
                source = archive.read(f"tests/{exercise.label}.py").decode()
                test_file = ExceptionTestFile.from_string(source, exercise.label)
                registered = EXERCISES[exercise.label]
                cases = test_file.test_cases
                assert [c.hidden for c in cases] == \
                    [False] + [True] * len(registered.hidden_points)
                assert [c.points for c in cases] == \
                    [registered.points] + list(registered.hidden_points)
                # Each chapter's own seed, drawn from the assignment's: no chapter's
                # autograder tells another's hidden cases.
                seed = assign.chapter_seed(SEED, name)
                assert source.count(f"seed = {seed}") == len(registered.hidden_points)
                assert f"seed = {SEED}\n" not in source


def test_the_master_notebook_is_otters_format(tmp_path):
    name, path = assign.chapters()[0]
    master = assign.master_notebook(name, path, SEED)
    raw = [cell.source.splitlines()[0] for cell in master.cells if cell.cell_type == "raw"]
    assert raw[0] == "# ASSIGNMENT CONFIG"
    assert raw.count("# BEGIN QUESTION") == raw.count("# END QUESTION") == len(_implement(path))
    solution = [cell.source for cell in master.cells
                if cell.source.startswith("# BEGIN SOLUTION NO PROMPT")]
    assert len(solution) == len(_implement(path))
    assert all("''' # BEGIN PROMPT" in cell for cell in solution)


def test_bad_input_to_assign_is_refused(tmp_path):
    with pytest.raises(assign.AssignError, match="unknown chapters"):
        assign.assign(tmp_path, names=["no_such_chapter"], run_tests=False)
    with pytest.raises(ValueError, match="seed"):
        assign.assign(tmp_path, seed=-1, run_tests=False)
    with pytest.raises(assign.AssignError, match="glued number"):
        assign.markdown_of("```{exercise-start} Implement: x\n:label: ex-x\n```\n"
                           "It took {glue:text}`n` tries.")
    assert assign.markdown_of("See {ref}`the chapter <ch>` and {doc}`api`.") == \
        "See the chapter and *api*."


# --- the questions for a learning platform -------------------------------------------------

def _questions():
    return [{"chapter": "1. A chapter", "label": "ex-a", "name": "Exercise 1.3 Predict: a",
             "text": "<p>How many \\(x &lt; 2\\)?</p>",
             "options": [("one", False, "Count again."), ("two", True, "")],
             "explanation": "<p>Two: 40% of them.</p>"},
            {"chapter": "2. Another", "label": "ex-b", "name": "Exercise 2.1 Predict: b",
             "text": "<p>Which?</p>", "options": [("a", True, ""), ("b", False, "No.")],
             "explanation": "<p>A.</p>"}]


def test_the_moodle_export_reads_back_and_a_broken_one_does_not():
    questions = _questions()
    text = lms.moodle_xml(questions)
    assert lms.validate(text, questions) == []
    assert text.count('<question type="category">') == 2
    assert text.count('<answer fraction="100"') == 2
    broken = text.replace('<answer fraction="100"', '<answer fraction="0"')
    assert any("no right option" in p for p in lms.validate(broken, questions))
    assert any("not XML" in p for p in lms.validate(text.replace("</quiz>", ""), questions))
    assert lms.validate(text.replace("Count again.", "Count."), questions)
    assert lms.validate(text, questions[:1])  # a question missing


@pytest.mark.book
def test_every_question_of_the_book_is_exported_to_moodle_xml(built_book, tmp_path):
    from bs4 import BeautifulSoup

    out = tmp_path / "questions.xml"
    count = lms.export_moodle(built_book, out)
    quizzes = {}
    for name, path in assign.chapters():
        page = BeautifulSoup((built_book / "book" / f"{name}.html").read_text(), "html.parser")
        for block in page.select("div.exercise.icm-quiz"):
            right = block.select_one('input[data-correct="true"]').find_next("label")
            quizzes[block["id"]] = right.get_text(strip=True)
    predict = [e.label for _, p in assign.chapters() for e in assign.chapter_exercises(p)
               if e.kind == "predict"]
    assert count == len(predict) == len(quizzes) and sorted(quizzes) == sorted(predict)
    questions = lms.quiz_questions(built_book)
    assert lms.validate(out.read_text(), questions) == []
    for question in questions:
        (right,) = [text for text, is_right, _ in question["options"] if is_right]
        assert right == quizzes[question["label"]]
        assert question["explanation"] and "{glue" not in question["explanation"]


# --- the instructors' page's directives, on a small book ------------------------------------

FIXTURE_CHAPTER = {
    "cells": [
        nbformat.v4.new_markdown_cell(
            "# A chapter\n\n:::{admonition} Learning objectives\n:class: icm-objectives\n"
            "- Compute a thing.\n- Explain it.\n:::\n\nThe chapter's text."),
        nbformat.v4.new_markdown_cell("## Exercises"),
        nbformat.v4.new_markdown_cell("```{exercise-start} Implement: the first thing\n"
                                      ":label: ex-first\n```\n\nWrite it."),
        nbformat.v4.new_markdown_cell("```{exercise-end}\n```"),
        nbformat.v4.new_markdown_cell(":::{exercise} Extend: the second thing, 90%\n"
                                      ":label: ex-second\n\nExtend it.\n:::"),
    ]}


def test_the_instructors_page_reads_objectives_and_exercises_from_the_chapters(tmp_path):
    source = tmp_path / "src"
    source.mkdir()
    nbformat.write(nbformat.v4.new_notebook(cells=FIXTURE_CHAPTER["cells"]),
                   source / "chapter.ipynb")
    (source / "index.md").write_text(
        "# Instructors\n\n```{toctree}\nchapter\nwrong\n```\n\n"
        ":::{chapter-objectives} chapter\n:::\n\n"
        ":::{chapter-exercises} chapter\nex-first: 10 min\nex-second: 20 min\n:::\n\n"
        "See {exref}`ex-second`.\n")
    # A page whose times leave an exercise out: an error, and the only message.
    (source / "wrong.md").write_text("# Wrong\n\n:::{chapter-exercises} chapter\n"
                                     "ex-first: 10 min\n:::\n")
    (source / "conf.py").write_text(
        "import sys\n"
        f"sys.path.insert(0, {str(ROOT / 'book' / '_ext')!r})\n"
        "extensions = ['myst_nb', 'sphinx_exercise', 'course_pages']\n"
        "nb_execution_mode = 'off'\nmyst_enable_extensions = ['colon_fence']\n"
        "numfig = True\nexclude_patterns = ['_build']\n")
    done = subprocess.run([sys.executable, "-m", "sphinx", "-b", "html", "-q",
                           str(source), str(tmp_path / "html")], capture_output=True,
                          text=True)
    messages = [line for line in (done.stdout + done.stderr).splitlines()
                if "WARNING" in line or "ERROR" in line]
    assert len(messages) == 1 and "wrong.md" in messages[0], messages
    assert "missing ['ex-second']" in messages[0]
    page = (tmp_path / "html" / "index.html").read_text()
    assert "icm-chapter-objectives" in page and "Compute a thing." in page
    assert "Explain it." in page and "Learning objectives" in page
    assert "icm-exercise-table" in page
    assert re.search(r"Exercise 1: the first thing", page)
    assert "Exercise 2: the second thing, 90%" in page  # (a "%" in a title)
    assert page.count('href="chapter.html#ex-second"') == 2  # the table and the exref
    assert "20 min" in page and "icm-course.css" in page
    assert (tmp_path / "html" / "_static" / "icm-course.css").exists()


def test_the_course_finds_the_book_through_the_packages_data():
    # Not through a checkout's parents: the book's sources are package data of
    # icm.project (icm/project links to them here; a wheel holds copies of them).
    import fnmatch
    import pathlib
    import tomllib

    import icm
    from icm import store

    package = pathlib.Path(icm.__file__).resolve().parent
    assert assign.ROOT == store.PROJECT == package / "project"
    chapters = assign.chapters()
    assert chapters and all(path.parent == package / "project" / "book"
                            for _, path in chapters)
    # Here, the links lead to the project's own files.
    for name in assign.SOURCES:
        assert (assign.ROOT / name).resolve() == (ROOT / name).resolve(), name
    # pyproject.toml declares them all as package data, so that an installed icm has them.
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    patterns = config["package-data"]["icm.project"]
    needed = ["_toc.yml", "_config.yml", "requirements.txt"] + [
        f"book/{path.name}" for _, path in chapters]
    for name in needed:
        assert any(fnmatch.fnmatch(name, pattern) for pattern in patterns), name
    # ... and the book's build scripts are not modules of icm.
    assert "icm.project.book*" in config["packages"]["find"]["exclude"]
