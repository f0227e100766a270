"""The exercises in the book and the students' edition: at least 3 exercises in every
chapter (24 in all, 10 of them checked), each implement exercise with a placeholder
and a check, solutions that strip cleanly, the instructors' page listing every
exercise, and a built students' edition with no solution in it."""

import ast
import re
import sys

import nbformat
import pytest

from conftest import ROOT, first_objective, toc_files

sys.path.insert(0, str(ROOT / "book" / "_ext"))
import student_edition  # noqa: E402 (beside the build scripts)

CHAPTERS = [name.removeprefix("book/") for name in toc_files()
            if (ROOT / f"{name}.ipynb").exists()]
EXERCISE = re.compile(r"\{exercise(?:-start)?\} (Implement|Predict, then check|Extend): "
                      r"(.+)\n:label: (ex-[a-z0-9-]+)")
KINDS = {"Implement": "implement", "Predict, then check": "predict, then check",
         "Extend": "extend"}


def exercises(name):
    """[(label, kind, title)] of a chapter's exercises, in order."""
    notebook = nbformat.read(ROOT / "book" / f"{name}.ipynb", as_version=4)
    found = []
    for cell in notebook.cells:
        if cell.cell_type == "markdown":
            for kind, title, label in EXERCISE.findall(cell.source):
                found.append((label, KINDS[kind], title))
    return found


def test_every_chapter_has_at_least_three_exercises_and_the_book_24():
    counts = {name: len(exercises(name)) for name in CHAPTERS}
    assert len(counts) == 8, counts
    assert all(n >= 3 for n in counts.values()), counts
    assert sum(counts.values()) >= 24
    kinds = [kind for name in CHAPTERS for _, kind, _ in exercises(name)]
    assert kinds.count("implement") >= 10
    assert {"implement", "predict, then check", "extend"} <= set(kinds)


def test_labels_are_unique():
    labels = [label for name in CHAPTERS for label, _, _ in exercises(name)]
    assert len(labels) == len(set(labels))


@pytest.mark.parametrize("name", CHAPTERS)
def test_each_implement_exercise_has_a_placeholder_a_check_and_a_solution(name):
    notebook = nbformat.read(ROOT / "book" / f"{name}.ipynb", as_version=4)
    cells = notebook.cells
    for i, cell in enumerate(cells):
        match = EXERCISE.search(cell.source) if cell.cell_type == "markdown" else None
        if not match or match.group(1) != "Implement":
            continue
        label = match.group(3)
        placeholder, check, end = cells[i + 1], cells[i + 2], cells[i + 3]
        assert placeholder.cell_type == "code" and "raise NotImplementedError" in \
            placeholder.source, label
        assert "exercises.check_" in check.source, label
        assert "{exercise-end}" in end.source, label
        start = cells[i + 4]
        assert f"{{solution-start}} {label}" in start.source and ":class: dropdown" in \
            start.source, label
        solution = [c for c in cells[i + 5:i + 8] if "solution" in c.metadata.get("tags", [])]
        assert any(c.cell_type == "code" and "raise NotImplementedError" not in c.source
                   for c in solution), label
        assert any(c.source == check.source for c in solution), \
            f"{label}: the solution runs the check, so that the build exercises it"
        function = re.search(r"def (\w+)\(", placeholder.source).group(1)
        assert f"({function}" in check.source, label


@pytest.mark.parametrize("name", CHAPTERS)
def test_each_prediction_is_answered_in_the_page_with_glued_numbers(name):
    notebook = nbformat.read(ROOT / "book" / f"{name}.ipynb", as_version=4)
    cells = notebook.cells
    for i, cell in enumerate(cells):
        match = EXERCISE.search(cell.source) if cell.cell_type == "markdown" else None
        if not match or match.group(1) != "Predict, then check":
            continue
        assert ":class: icm-quiz" in cell.source
        computation, explanation = cells[i + 1], cells[i + 2]
        assert "exercises.Choices(" in computation.source
        (call,) = [node for node in ast.walk(ast.parse(computation.source))
                   if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "Choices"]
        assert not isinstance(call.args[2], ast.Constant), \
            "the right option comes from the computed number, not typed"
        assert "remove-input" in computation.metadata.get("tags", [])
        assert "icm-quiz-explanation" in explanation.source
        assert "{glue:text}`" in explanation.source, "the explanation quotes a glued number"


@pytest.mark.parametrize("name", CHAPTERS)
def test_the_solutions_strip_cleanly(name):
    notebook = nbformat.read(ROOT / "book" / f"{name}.ipynb", as_version=4)
    stripped = student_edition.strip_solutions(notebook, name)
    assert student_edition.solutions_of(notebook)
    assert student_edition.solutions_of(stripped) == []
    text = "".join(cell.source for cell in stripped.cells)
    assert "{solution" not in text
    assert text.count("raise NotImplementedError") == sum(
        1 for _, kind, _ in exercises(name) if kind == "implement")
    for label, _, _ in exercises(name):
        assert f":label: {label}" in text  # every exercise stays
    assert len(notebook.cells) > len(stripped.cells)


def _notebook(*cells):
    made = []
    for kind, source, tags in cells:
        cell = (nbformat.v4.new_code_cell if kind == "code" else nbformat.v4.new_markdown_cell)(source)
        if tags:
            cell.metadata["tags"] = tags
        made.append(cell)
    return nbformat.v4.new_notebook(cells=made)


START = ("md", "```{solution-start} ex-a\n:class: dropdown\n```", ["solution"])
END = ("md", "```{solution-end}\n```", ["solution"])


def test_stripping_refuses_a_cell_that_needs_a_solution():
    leaky = _notebook(("code", "def f(x):\n    raise NotImplementedError", None), START,
                      ("code", "def f(x):\n    return x\nresult = f(2)", ["solution"]), END,
                      ("code", "print(result)", None))
    with pytest.raises(student_edition.StripError, match="uses result"):
        student_edition.strip_solutions(leaky)
    redefined = _notebook(("code", "def f(x):\n    raise NotImplementedError", None), START,
                          ("code", "def f(x):\n    return x", ["solution"]), END,
                          ("code", "f(3)", None))
    with pytest.raises(student_edition.StripError, match="uses f"):
        student_edition.strip_solutions(redefined)
    fine = _notebook(("code", "x = 1", None), START, ("code", "x = 2", ["solution"]), END,
                     ("code", "x = 3\nprint(x)", None))
    assert len(student_edition.strip_solutions(fine).cells) == 2


def test_stripping_refuses_a_number_glued_only_in_a_solution():
    leaky = _notebook(START, ("code", 'glue("ex_n", 3, display=False)', ["solution"]), END,
                      ("md", "It took {glue:text}`ex_n` tries.", None))
    with pytest.raises(student_edition.StripError, match="ex_n"):
        student_edition.strip_solutions(leaky)
    prefixed = _notebook(START, ("code", 'glue(f"ex_n_{k}", 3, display=False)', ["solution"]),
                         END, ("md", "{glue:text}`ex_n_red:.0%`", None))
    with pytest.raises(student_edition.StripError, match="ex_n_red"):
        student_edition.strip_solutions(prefixed)


def test_stripping_refuses_a_solution_left_untagged_or_half_tagged():
    untagged = _notebook(START, ("code", "x = 2", None), END)
    with pytest.raises(student_edition.StripError, match="untagged cell inside"):
        student_edition.strip_solutions(untagged)
    directive = _notebook(("md", "```{solution} ex-a\nThe answer.\n```", None))
    with pytest.raises(student_edition.StripError, match="solution directive"):
        student_edition.strip_solutions(directive)
    unended = _notebook(START, ("code", "x = 2", ["solution"]))
    with pytest.raises(student_edition.StripError, match="without its solution-end"):
        student_edition.strip_solutions(unended)
    outside = _notebook(("code", "x = 2", ["solution"]))
    with pytest.raises(student_edition.StripError, match="outside"):
        student_edition.strip_solutions(outside)


def _instructors_sections():
    """{chapter: its section of the instructors' page}, in order."""
    page = (ROOT / "book" / "instructors.md").read_text()
    part = page.split("\n## Chapter by chapter", 1)[1]
    return {name: part.split(f"\n### {number}. ", 1)[1].split("\n### ", 1)[0]
            for number, name in enumerate(CHAPTERS, 1)}


def test_the_instructors_page_lists_every_exercise_with_its_time_and_the_objectives():
    page = (ROOT / "book" / "instructors.md").read_text()
    assert "book/instructors" in toc_files()
    assert "make book-students" in page and "make assignments" in page
    assert "**Objectives.**" not in page  # the chapters state them (chapter-objectives)
    for name, section in _instructors_sections().items():
        assert f":::{{chapter-objectives}} {name}\n:::" in section, name
        assert "**Prerequisites.**" in section, name
        block = section.split(f":::{{chapter-exercises}} {name}\n", 1)[1].split(":::")[0]
        listed = dict(re.findall(r"(ex-[a-z0-9-]+): (\d+ min)", block))
        assert sorted(listed) == sorted(label for label, _, _ in exercises(name)), name
    for name in CHAPTERS:  # the kit: plans and a marking guide per extend exercise
        for label, kind, _ in exercises(name):
            if kind == "extend":
                guide = page.split("## Marking guides", 1)[1].split("\n## ", 1)[0]
                assert f"{{exref}}`{label}`" in guide, label
    for heading in ("## What runs where", "## Course plans", "**Four weeks**",
                    "**Eight weeks**", "## Slides", "## The questions for a learning platform",
                    "### On Gradescope", "icm.course grade", "--roster"):
        assert heading in page, heading


def test_the_students_api_page_leaves_the_answers_out():
    api = (ROOT / "book" / "api.md").read_text()
    students = student_edition.students_api(api)
    excluded = re.findall(r":exclude-members: (.*)", students)
    names = {name.strip() for line in excluded for name in line.split(",")}
    assert {"reference_task_interest", "reference_q_learning_step", "reference_softmax",
            "hidden_slope_cases"} <= names
    assert all(name.startswith(("reference_", "hidden_", "set")) for name in names)
    assert students.count("automodule::") == api.count("automodule::")


def test_the_students_edition_has_no_source_pages(tmp_path):
    import yaml

    student_edition.prepare(tmp_path / "source")
    config = yaml.safe_load((tmp_path / "source" / "_config.yml").read_text())
    assert "sphinx.ext.viewcode" not in config["sphinx"]["extra_extensions"]
    assert "sphinx_exercise" in config["sphinx"]["extra_extensions"]
    full = yaml.safe_load((ROOT / "_config.yml").read_text())
    assert "sphinx.ext.viewcode" in full["sphinx"]["extra_extensions"]  # the full book's
    assert ":exclude-members: hidden_outcome_cases" in \
        (tmp_path / "source" / "book" / "api.md").read_text()
    instructors = (tmp_path / "source" / "book" / "instructors.md").read_text()
    assert "Marking guides" not in instructors and "full edition" in instructors


def test_it_empties_its_own_sources_only(tmp_path):
    from icm import files

    student_edition.prepare(tmp_path / "source")
    (tmp_path / "source" / "stale.txt").write_text("from an earlier run")
    student_edition.prepare(tmp_path / "source")  # its own folder: emptied, written again
    assert not (tmp_path / "source" / "stale.txt").exists()
    theirs = tmp_path / "theirs"
    theirs.mkdir()
    (theirs / "thesis.tex").write_text("a student's thesis")
    with pytest.raises(files.DestinationError, match="not written by icm"):
        student_edition.prepare(theirs)
    assert (theirs / "thesis.tex").read_text() == "a student's thesis"
    assert sorted(p.name for p in theirs.iterdir()) == ["thesis.tex"]


def test_make_has_the_students_edition_target():
    makefile = (ROOT / "Makefile").read_text()
    assert "book-students:" in makefile and "book/_ext/student_edition.py" in makefile


# --- the built students' edition -------------------------------------------------------

def _distinctive_solution_lines():
    """Lines of the solutions that appear nowhere else in the book's notebooks: what a
    students' edition must not contain."""
    lines = {}
    for name in CHAPTERS:
        notebook = nbformat.read(ROOT / "book" / f"{name}.ipynb", as_version=4)
        elsewhere = "\n".join(c.source for c in notebook.cells
                              if "solution" not in c.metadata.get("tags", []))
        for source in student_edition.solutions_of(notebook):
            for line in source.splitlines():
                line = line.strip()
                if len(line) > 30 and line not in elsewhere and "{solution" not in line:
                    lines.setdefault(name, []).append(line)
    return lines


@pytest.fixture(scope="module")
def students_edition(built_book):
    """Builds the students' edition beside the book the tests built, reusing its
    execution (as `make book-students` after `make book`); returns its HTML folder."""
    output = built_book.parents[1]
    status = student_edition.main(["--path-output", str(output), "--strict"])
    assert status == 0, "the students' edition did not build"
    return output / "_build" / "students" / "_build" / "html"


@pytest.mark.book
def test_the_students_edition_has_no_solution(students_edition):
    import html as html_module

    solutions = _distinctive_solution_lines()
    assert sum(len(lines) for lines in solutions.values()) > 50
    pages = sorted(students_edition.rglob("*.html"))
    sources = sorted((students_edition / "_sources").rglob("*.ipynb"))
    assert len(sources) == len(CHAPTERS)
    texts = {p: html_module.unescape(p.read_text()) for p in pages}
    texts.update({p: "\n".join(c.source for c in nbformat.read(p, as_version=4).cells)
                  for p in sources})
    for name, lines in solutions.items():
        for path, text in texts.items():
            for line in lines:
                assert line not in text, f"{path.name} holds a solution line of {name}: {line}"
    for path, text in texts.items():
        assert 'class="solution' not in text and "solution-start" not in text, path.name
        # No hidden test, and no reference solution in the API pages or their sources.
        assert not re.search(r"""hidden_test\(\s*['"]ex-""", text), path.name  # a test
        assert "BEGIN TEST CONFIG" not in text, path.name
        assert "viewcode" not in text and "_modules/" not in text, path.name
    assert not (students_edition / "_modules").exists()
    assert "Marking guides" not in (students_edition / "book" / "instructors.html").read_text()
    api = (students_edition / "book" / "api.html").read_text()
    assert 'id="icm.exercises.rods.reference_q_learning_step"' not in api
    assert 'id="icm.exercises.interest.hidden_slope_cases"' not in api
    assert 'id="icm.exercises.rods.check_q_learning_step"' in api


@pytest.mark.book
def test_the_students_notebooks_hold_the_placeholders_and_checks(students_edition):
    for name in CHAPTERS:
        page = (students_edition / "book" / f"{name}.html").read_text()
        notebook = nbformat.read(students_edition / "_sources" / "book" / f"{name}.ipynb",
                                 as_version=4)
        text = "\n".join(c.source for c in notebook.cells)
        for label, kind, _ in exercises(name):
            assert f'id="{label}"' in page, (name, label)
        implement = sum(1 for _, kind, _ in exercises(name) if kind == "implement")
        assert text.count("raise NotImplementedError") == implement, name
        assert text.count("exercises.check_") == implement, name
        assert page.count("not implemented yet") >= implement, name
        assert "students' edition" in page


@pytest.mark.book
def test_the_book_runs_every_check_on_its_solution_and_on_its_placeholder(built_book):
    # In the full book every check runs twice: on the placeholder (not implemented
    # yet) and on the solution (every case passed).
    for name in CHAPTERS:
        page = (built_book / "book" / f"{name}.html").read_text()
        implement = sum(1 for _, kind, _ in exercises(name) if kind == "implement")
        assert page.count("icm-check-todo") == implement, name
        assert page.count("icm-check-passed") == implement, name
        assert "icm-check-failed" not in page, name
        assert 'class="solution' in page and "dropdown" in page, name


@pytest.mark.book
def test_the_instructors_page_links_every_exercise(built_book):
    page = (built_book / "book" / "instructors.html").read_text()
    page = page.replace("\u201c", '"').replace("\u201d", '"')  # (Sphinx's smart quotes)
    for number, name in enumerate(CHAPTERS, 1):
        for index, (label, _, title) in enumerate(exercises(name), 1):
            assert f'href="{name}.html#{label}"' in page, label
            # Each exercise with its number and its title (issue 26).
            assert f"Exercise {number}.{index}: {title}" in page, (label, title)
    assert page.count('icm-exercise-table') >= len(CHAPTERS)
    # The objectives, as the chapter that states them has them.
    start = page.index("icm-chapter-objectives")
    assert first_objective("button_experiment") in " ".join(page[start:start + 3000].split())
    assert page.count("icm-chapter-objectives") == sum(  # the chapters that state them
        1 for name in CHAPTERS if ":class: icm-objectives" in "".join(
            c.source for c in nbformat.read(ROOT / "book" / f"{name}.ipynb",
                                            as_version=4).cells[:3]))


@pytest.mark.book
def test_the_instructors_tables_fill_the_text_column(built_book):
    shutil_which = __import__("shutil").which
    chromium = shutil_which("chromium") or shutil_which("chromium-browser")
    playwright_api = pytest.importorskip("playwright.sync_api")
    if chromium is None:
        pytest.skip("Chromium is not installed")
    with playwright_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium,
                                             args=["--no-sandbox", "--disable-gpu"])
        page = browser.new_page(viewport={"width": 1366, "height": 800})
        page.goto((built_book / "book" / "instructors.html").as_uri())
        widths = page.eval_on_selector_all(
            "table.icm-exercise-table", "els => els.map(e => [e.getBoundingClientRect().width,"
            " e.closest('article, main').getBoundingClientRect().width])")
        browser.close()
    assert len(widths) == len(CHAPTERS)
    for table, column in widths:
        assert table > 0.9 * column, (table, column)
