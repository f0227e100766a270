"""`make lab`: the chapters as JupyterLab and Notebook 7 show them (book/_ext/lab_edition.py).

The unit tests write small made-up notebooks (the glue, the book's roles, the folder's
rules). The browser tests start JupyterLab as `make lab` starts it (the same script,
on the built book's execution cache; as root where the tests run as root, which CI
does), open the smallest chapter in headless Chromium, in JupyterLab and in Notebook 7,
and compare what a student reads with the built page: every number the page glues
into the prose is in the rendered cell, in order; the admonitions and dropdowns are
boxes, no MyST is left as text; no solution is in the notebooks it opens. Their cost
beyond the book's build (shared with the other book tests): one JupyterLab server and
two page loads, seconds on a quiet machine.
"""

import base64
import json
import os
import pathlib
import re
import socket
import subprocess
import sys
import time
import urllib.request

import nbformat
import pytest

from conftest import ROOT, chromium, toc_files

sys.path.insert(0, str(ROOT / "book" / "_ext"))
import lab_edition  # noqa: E402 (beside the build scripts)

CHAPTER = "button_experiment"
"""The chapter opened in the browser: the smallest (its page loads in seconds), with
glued numbers, admonitions, dropdowns, every kind of exercise and solutions."""
CHAPTERS = [name.removeprefix("book/") for name in toc_files()
            if (ROOT / f"{name}.ipynb").exists()]
PATIENCE_SECONDS = 600
"""How long the server and a page may take before the test gives up: far above their
time on a busy 2-core machine (seconds), so that only a hang fails it."""
GLUE_PREFIX = "application/papermill.record/"


# --- unit tests: made-up notebooks ---------------------------------------------------------

def _glued(name, value):
    """The hidden output myst_nb.glue(name, value, display=False) writes."""
    return nbformat.v4.new_output("display_data", data={GLUE_PREFIX + "text/plain": repr(value)},
                                  metadata={"scrapbook": {"name": name,
                                                          "mime_prefix": GLUE_PREFIX}})


def _executed(markdown, *, solution=False):
    cells = [nbformat.v4.new_code_cell("glue(...)", outputs=[
        _glued("share", 0.123456), _glued("seeds", 200),
        nbformat.v4.new_output("display_data", data={
            GLUE_PREFIX + "text/markdown": "**every** seed"},
            metadata={"scrapbook": {"name": "words", "mime_prefix": GLUE_PREFIX}}),
        nbformat.v4.new_output("display_data", data={
            GLUE_PREFIX + "image/png": base64.b64encode(b"png").decode(),
            GLUE_PREFIX + "text/plain": "<Figure>"},
            metadata={"scrapbook": {"name": "fig_a", "mime_prefix": GLUE_PREFIX}}),
        nbformat.v4.new_output("stream", text="shown\n")])]
    cells += [nbformat.v4.new_markdown_cell(text) for text in markdown]
    if solution:
        cells += [nbformat.v4.new_markdown_cell("```{solution-start} ex-a\n:class: dropdown\n```",
                                                metadata={"tags": ["solution"]}),
                  nbformat.v4.new_code_cell("answer = 42", metadata={"tags": ["solution"]}),
                  nbformat.v4.new_markdown_cell("```{solution-end}\n```",
                                                metadata={"tags": ["solution"]})]
    return nbformat.v4.new_notebook(cells=cells)


TITLES = {"goal_oriented_interest": ("Goal-oriented interest", ".ipynb"),
          "preface": ("Preface", ".md")}
LABELS = {"a2007": "Oudeyer et al., 2007", "b2009": "Baranes and Oudeyer, 2009"}


def _lab(markdown, **keywords):
    notebook = _executed(markdown, solution=keywords.pop("solution", False))
    return lab_edition.lab_notebook(notebook, keywords.pop("edition", "students"), TITLES,
                                    LABELS, **keywords)


def test_glued_numbers_read_as_the_page_formats_them():
    lab = _lab(["Red in {glue:text}`share:.1%` of {glue:text}`seeds` seeds, "
                "{glue:text}`share:.3f`; {glue:md}`words`, {sub}`2`."])
    assert lab.cells[1].source == ("Red in 12.3% of 200 seeds, 0.123; **every** seed, "
                                   "{sub}`2`.")
    # The hidden glue outputs go (Jupyter would show "no renderer"); the others stay.
    assert [output.output_type for output in lab.cells[0].outputs] == ["stream"]


def test_the_books_roles_become_links_citations_and_figures():
    lab = _lab(["See {doc}`goal_oriented_interest`, {doc}`this one <goal_oriented_interest>` "
                "and {doc}`preface`; {cite:p}`a2007,b2009`, {cite:t}`a2007`.",
                "::::{dropdown} A question?\n```{glue:figure} fig_a\n:name: fig-a\n\n"
                "The caption, {glue:text}`seeds` seeds.\n```\n::::",
                "```{glue:md} words\n:format: myst\n```"], chapter=3)
    assert lab.cells[1].source.split("---\n")[-1] == (
        "See [Goal-oriented interest](goal_oriented_interest.ipynb), "
        "[this one](goal_oriented_interest.ipynb) and *Preface* (in the book); "
        "[Baranes and Oudeyer, 2009, Oudeyer et al., 2007], Oudeyer et al. [2007].")
    # The first Markdown cell numbers the exercises as the page does.
    assert lab.cells[1].source.startswith('---\nnumbering:\n  enumerator: "3.%s"\n---\n')
    assert lab.cells[2].source == (
        "::::{dropdown} A question?\n![The caption, 200 seeds.](attachment:fig_a.png)\n\n"
        "**Fig. 3.1** The caption, 200 seeds.\n::::")
    assert lab.cells[2].attachments == {"fig_a.png": {"image/png": base64.b64encode(
        b"png").decode()}}
    assert lab.cells[3].source == "**every** seed"


def test_a_code_cells_figure_gets_its_caption_numbered_with_the_glued_ones():
    notebook = _executed(["# Title", "```{glue:figure} fig_a\nSecond.\n```"])
    notebook.cells.insert(1, nbformat.v4.new_code_cell("figure()", metadata={
        "mystnb": {"figure": {"caption": "First, {glue:text}`seeds` seeds.", "name": "fig-1"}},
        "tags": ["remove-input"]}))
    lab = lab_edition.lab_notebook(notebook, "instructor", TITLES, LABELS, chapter=2)
    assert [cell.cell_type for cell in lab.cells] == ["code", "code", "markdown", "markdown",
                                                      "markdown"]
    assert lab.cells[2].source == "**Fig. 2.1** First, 200 seeds."
    assert lab.cells[1].metadata.jupyter == {"source_hidden": True}
    assert "**Fig. 2.2** Second." in lab.cells[4].source


def test_cross_references_read_as_the_page_numbers_and_names_them():
    notebook = _executed(["(sec-rods)=\n## The rod table\n\n:::{dropdown} Why a fold?\n"
                          ":name: fold-why\nBecause.\n:::",
                          "```{glue:figure} fig_a\n:name: fig-a\n\nA caption.\n```",
                          "```{exercise} Implement: the minimum jerk\n:label: ex-jerk\n```",
                          "See {numref}`fig-a`, {numref}`fig-code`, {numref}`Figure %s "
                          "<fig-a>`, {numref}`ex-jerk`, {ref}`sec-rods`, {ref}`fold-why` "
                          "and {ref}`the fold <fold-why>`."])
    notebook.cells.insert(1, nbformat.v4.new_code_cell("figure()", metadata={
        "mystnb": {"figure": {"caption": "First.", "name": "fig-code"}}}))
    lab = lab_edition.lab_notebook(notebook, "students", TITLES, LABELS, chapter=3)
    assert lab.cells[-1].source == ("See Fig. 3.2, Fig. 3.1, Figure 3.2, Exercise 3.1, The "
                                    "rod table, Why a fold? and the fold.")


def test_a_figure_of_another_chapter_reads_with_that_chapters_number():
    other = _executed(["# Five", "```{glue:figure} fig_a\n:name: fig-5\n\nA caption.\n```"])
    this = _executed(["See {numref}`fig-5` and {ref}`the other <fig-5>`."])
    targets = lab_edition.book_targets({pathlib.Path("five.ipynb"): other}, {"five": 5})
    lab = lab_edition.lab_notebook(this, "students", TITLES, LABELS, chapter=3,
                                   book_targets=targets)
    assert lab.cells[-1].source.split("---\n")[-1] == "See Fig. 5.1 and the other."
    with pytest.raises(lab_edition.LabEditionError, match="'fig-5' is also five.ipynb's"):
        lab_edition.book_targets({pathlib.Path("five.ipynb"): other,
                                  pathlib.Path("six.ipynb"): other}, {"five": 5, "six": 6})


def test_a_quiz_explanation_is_folded_until_the_student_looks():
    lab = _lab([":::{div} icm-quiz-explanation\nThe answer: {glue:text}`share:.0%`.\n:::",
                ":::{div} other\nStays.\n:::"])
    assert lab.cells[1].source == ":::{dropdown} Check your answer\nThe answer: 12%.\n:::"
    assert lab.cells[2].source == ":::{div} other\nStays.\n:::"


def test_the_students_notebooks_have_no_solution_the_instructors_have_theirs():
    students = _lab(["Text."], solution=True)
    instructor = _lab(["Text."], solution=True, edition="instructor")
    assert not [c for c in students.cells if "solution" in c.metadata.get("tags", [])]
    assert len([c for c in instructor.cells if "solution" in c.metadata.get("tags", [])]) == 3


@pytest.mark.parametrize("markdown, words", [
    ("{glue:text}`missing`", "no glued value 'missing'"),
    ("{glue:text}`other.ipynb::share`", "another notebook"),
    ("{glue:math}`share`", "{glue:math}"),
    ("{doc}`nowhere`", "not a page of the book"),
    ("{cite:p}`nobody2020`", "not in references.bib"),
    ("{numref}`fig-5`", "names no figure, exercise, section or fold"),
    ("{ref}`nowhere`", "names no figure, exercise, section or fold"),
    ("```{glue:math} share\n```", "{glue:math}")])
def test_what_cannot_be_written_for_jupyter_is_refused_by_name(markdown, words):
    with pytest.raises(lab_edition.LabEditionError, match=re.escape(words)) as error:
        _lab([markdown], name="chapter.ipynb")
    assert "chapter.ipynb, cell 1" in str(error.value)


def test_the_folder_is_written_once_marked_and_a_students_work_is_kept(tmp_path):
    folder = tmp_path / "lab"
    first = {"a.ipynb": _lab(["A."]), "b.ipynb": _lab(["B."])}
    assert lab_edition.write_edition(folder, first, "students") == (["a.ipynb", "b.ipynb"], [])
    assert json.loads((folder / lab_edition.MARKER).read_text())["edition"] == "students"
    # A student edits b and runs a (outputs and metadata change, not the cells).
    edited = nbformat.read(folder / "b.ipynb", as_version=4)
    edited.cells[1].source = "My answer."
    nbformat.write(edited, folder / "b.ipynb")
    ran = nbformat.read(folder / "a.ipynb", as_version=4)
    ran.cells[0].outputs, ran.metadata["trusted"] = [], True
    nbformat.write(ran, folder / "a.ipynb")
    (folder / "c.ipynb").write_text("a file of the student's")
    again = {"a.ipynb": _lab(["A, new."]), "b.ipynb": _lab(["B, new."]),
             "c.ipynb": _lab(["C."])}
    assert lab_edition.write_edition(folder, again, "students") == (["a.ipynb"],
                                                                   ["b.ipynb", "c.ipynb"])
    assert nbformat.read(folder / "a.ipynb", as_version=4).cells[1].source == "A, new."
    assert nbformat.read(folder / "b.ipynb", as_version=4).cells[1].source == "My answer."
    assert (folder / "c.ipynb").read_text() == "a file of the student's"
    assert not [p.name for p in folder.iterdir() if p.name.endswith(".tmp")]


def test_a_folder_this_command_did_not_write_is_refused(tmp_path):
    (tmp_path / "mine.ipynb").write_text("{}")
    with pytest.raises(lab_edition.LabEditionError, match="not written by make lab"):
        lab_edition.write_edition(tmp_path, {"a.ipynb": _lab(["A."])}, "students")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.ipynb"]


def test_jupyter_is_started_with_allow_root_as_root_only(tmp_path):
    as_root = lab_edition.jupyter_command(tmp_path, ["--port", "8890"], euid=0)
    assert as_root[:4] == [sys.executable, "-m", "jupyter", "lab"]
    assert "--allow-root" in as_root and as_root[-2:] == ["--port", "8890"]
    assert "--allow-root" not in lab_edition.jupyter_command(tmp_path, [], euid=1000)
    assert as_root.count("--allow-root") == 1 == lab_edition.jupyter_command(
        tmp_path, ["--allow-root"], euid=0).count("--allow-root")


def test_make_lab_runs_this_script_for_students_and_instructors():
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^lab:.*\n\t\$\(BIN\)/python book/_ext/lab_edition.py \$\(LAB_ARGS\)$",
                     makefile, re.MULTILINE)
    assert re.search(r"^lab-instructor:.*\n\t\$\(BIN\)/python book/_ext/lab_edition.py "
                     r"--instructor \$\(LAB_ARGS\)$", makefile, re.MULTILINE)


# --- in a browser, on the built book -------------------------------------------------------

def _free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _settings(folder):
    """JupyterLab's settings for the test: every cell rendered at once (not as it
    scrolls into view), no question about Jupyter's news."""
    tracker = folder / "@jupyterlab" / "notebook-extension" / "tracker.jupyterlab-settings"
    tracker.parent.mkdir(parents=True)
    tracker.write_text(json.dumps({"windowingMode": "none"}))
    news = folder / "@jupyterlab" / "apputils-extension" / "notification.jupyterlab-settings"
    news.parent.mkdir(parents=True)
    news.write_text(json.dumps({"fetchNews": "false", "checkForUpdates": False}))


@pytest.fixture(scope="module")
def lab_server(built_book, tmp_path_factory):
    """JupyterLab started by book/_ext/lab_edition.py, as `make lab` starts it, on the
    built book's execution cache (nothing runs again); yields (url, folder of the
    notebooks it opened). Its own Jupyter folders, no token, a free port."""
    base = tmp_path_factory.mktemp("lab")
    folder, settings = base / "students", base / "settings"
    _settings(settings)
    environment = dict(os.environ, JUPYTER_CONFIG_DIR=str(base / "config"),
                       JUPYTER_RUNTIME_DIR=str(base / "runtime"),
                       JUPYTERLAB_SETTINGS_DIR=str(settings),
                       JUPYTERLAB_WORKSPACES_DIR=str(base / "workspaces"))
    port = _free_port()
    log = base / "lab.log"
    with open(log, "w") as output:
        server = subprocess.Popen(
            [sys.executable, str(ROOT / "book" / "_ext" / "lab_edition.py"),
             "--path-output", str(built_book.parents[1]), "--folder", str(folder),
             "--no-browser", f"--port={port}", "--ServerApp.port_retries=0",
             "--IdentityProvider.token=", "--ip=127.0.0.1"],
            cwd=ROOT, env=environment, stdout=output, stderr=subprocess.STDOUT)
    url = f"http://127.0.0.1:{port}"
    try:
        started = time.monotonic()
        while True:
            if server.poll() is not None:
                pytest.fail(f"make lab's JupyterLab ended ({server.returncode}):\n"
                            + log.read_text()[-4000:])
            try:
                with urllib.request.urlopen(f"{url}/api/status", timeout=10) as answer:
                    if answer.status == 200:
                        break
            except OSError:
                pass
            assert time.monotonic() - started < PATIENCE_SECONDS, log.read_text()[-4000:]
            time.sleep(0.5)
        yield url, folder, log
    finally:
        server.terminate()  # JupyterLab shuts its kernels down on SIGTERM
        try:
            server.wait(60)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()


@pytest.fixture(scope="module")
def browser():
    with chromium() as launched:
        yield launched


def _words(text):
    """Text as the test compares it: typographic quotes as plain ones (Sphinx and
    jupyterlab-myst both curl them), spaces collapsed."""
    for curly, plain in (("\u201c", '"'), ("\u201d", '"'), ("\u2018", "'"), ("\u2019", "'"),
                         ("\u00a0", " ")):
        text = text.replace(curly, plain)
    return " ".join(text.split())


def _page_numbers(built_book, chapter):
    """The texts the built page glues into the chapter's prose, in order."""
    from bs4 import BeautifulSoup

    page = BeautifulSoup((built_book / "book" / f"{chapter}.html").read_text(), "html.parser")
    return [_words(span.get_text()) for span in page.select("span.pasted-text")]


def _expected_per_cell(chapter, page_numbers, edition="students"):
    """For each Markdown cell of the chapter as `make lab` writes it (the source's own,
    and the caption that follows each figure's code cell), its source and the texts
    of the page it quotes, in order: the source's `{glue:text}` roles (in the page's
    order: each cell's, and after a figure's cell its caption's) matched one to one
    with the page's glued texts."""
    source = nbformat.read(ROOT / "book" / f"{chapter}.ipynb", as_version=4)
    expected, position = [], 0
    for cell in source.cells:
        caption = cell.metadata.get("mystnb", {}).get("figure", {}).get("caption")
        text = cell.source if cell.cell_type == "markdown" else caption
        if not text:
            continue
        count = sum(1 for role in lab_edition.ROLE.finditer(text)
                    if role.group("name") == "glue:text")
        quoted = page_numbers[position:position + count]
        position += count
        if edition == "instructor" or "solution" not in cell.metadata.get("tags", []):
            expected.append((text, quoted))
    assert position == len(page_numbers), "the page glues other numbers than the source"
    return expected


def _appear_in_order(texts, rendered):
    """The first text of `texts` not found in `rendered` after the one before it (a
    number must not be part of a longer one), or None."""
    at = 0
    for text in texts:
        pattern = (r"(?<![\d.])" if text[:1].isdigit() else "") + re.escape(text) + \
            (r"(?!\d)" if text[-1:].isdigit() else "")
        found = re.compile(pattern).search(rendered, at)
        if found is None:
            return text
        at = found.end()
    return None


READ_CELLS = """() => [...document.querySelectorAll('.jp-Notebook .jp-Cell')].map(cell => ({
  markdown: cell.classList.contains('jp-MarkdownCell'),
  text: cell.classList.contains('jp-MarkdownCell') ? cell.innerText : '',
  myst: cell.querySelector('.myst') !== null,
  admonitions: cell.querySelectorAll('aside.myst-admonition').length,
  dropdowns: cell.querySelectorAll('details.myst-dropdown').length,
  exercises: cell.querySelectorAll('aside.myst-exercise').length}))"""
RENDERED = """n => {
  const cells = [...document.querySelectorAll('.jp-Notebook .jp-MarkdownCell')];
  const shown = cell => [...cell.querySelectorAll('.myst, .jp-RenderedMarkdown')]
    .some(output => output.childElementCount > 0);
  return cells.length === n
    && cells.every(cell => cell.classList.contains('jp-mod-rendered') && shown(cell));
}"""
"""True once the notebook shows its `n` Markdown cells rendered: by jupyterlab-myst (in
an element of class `myst`) or, when it is missing, by JupyterLab's own renderer (then
the test fails at once, not after waiting for a rendering that will never come)."""
DIRECTIVES = re.compile(r"^[ \t]*(?:`{3,}|:{3,})\{([a-z:-]+)\}", re.MULTILINE)


NOTEBOOK7_OWN = "/static/notebook/"
"""Where Notebook 7's own code is served. Two errors of its own are thrown from there
on this server, with no part of ours in them: its shortcuts plugin reads the schema of
a plugin it has not loaded (also with every third-party extension disabled), and it
runs JupyterLab's file browser's `filebrowser:open-path`, which it does not have,
after JupyterLab has opened the notebook on the same server. Errors thrown from there
are not the chapter's; every error in JupyterLab, which shows the same notebook, is."""


def _check_chapter_reads_as_its_page(browser, url, folder, built_book, ignored=None):
    """Opens the chapter at `url` and compares each Markdown cell as the student sees
    it with the notebook and the built page; returns how many glued numbers it found.
    A page error fails it unless its first frame is in the code served from `ignored`."""
    lab = nbformat.read(folder / f"{CHAPTER}.ipynb", as_version=4)
    written = [cell for cell in lab.cells if cell.cell_type == "markdown"]
    page = browser.new_page(viewport={"width": 1366, "height": 900})
    errors = []

    def keep(error):
        frames = [line for line in (error.stack or "").splitlines() if "    at " in line]
        if not (ignored and frames and ignored in frames[0]):
            errors.append(f"{error.message}\n{error.stack}")

    page.on("pageerror", keep)
    try:
        page.goto(url, timeout=PATIENCE_SECONDS * 1000)
        page.wait_for_function(RENDERED, arg=len(written), timeout=PATIENCE_SECONDS * 1000,
                               polling=500)
        # Every fold opened, as a student opens it to read it (a closed one's text is
        # not shown, so not in innerText).
        page.evaluate("() => document.querySelectorAll('.jp-Notebook details')"
                      ".forEach(fold => { fold.open = true; })")
        page.wait_for_function("() => [...document.querySelectorAll('.jp-Notebook details')]"
                               ".every(fold => fold.open)", timeout=PATIENCE_SECONDS * 1000)
        cells = page.evaluate(READ_CELLS)
    finally:
        page.close()
    assert not errors, errors
    assert all(cell["myst"] for cell in cells if cell["markdown"]), \
        "a Markdown cell not rendered by jupyterlab-myst (is it installed and enabled?)"
    assert [cell["markdown"] for cell in cells] == [c.cell_type == "markdown" for c in lab.cells]
    shown = [cell for cell in cells if cell["markdown"]]
    expected = _expected_per_cell(CHAPTER, _page_numbers(built_book, CHAPTER))
    assert len(expected) == len(written)
    numbers = 0
    for cell, written_cell, (source, quoted) in zip(shown, written, expected):
        rendered = _words(cell["text"])
        missing = _appear_in_order(quoted, rendered)
        assert missing is None, (f"the page's {missing!r} is not where it should be in "
                                 f"Jupyter's cell: {rendered[:800]}")
        numbers += len(quoted)
        # Nothing of MyST is left as text: no fence, no role, no glue key with its
        # format (what jupyterlab-myst shows of a role it does not know).
        assert not re.search(r":::|```|\{(glue|doc|cite)", rendered), rendered[:800]
        for role in lab_edition.ROLE.finditer(source):
            if role.group("name") == "glue:text" and ":" in role.group("content"):
                assert role.group("content") not in rendered, role.group("content")
        # Every admonition and dropdown is a box; so is every exercise.
        kinds = DIRECTIVES.findall(written_cell.source)
        assert cell["admonitions"] == kinds.count("admonition"), (kinds, cell)
        assert cell["dropdowns"] == kinds.count("dropdown"), (kinds, cell)
        assert cell["exercises"] >= kinds.count("exercise") + kinds.count("exercise-start")
    return numbers


def test_make_lab_opens_no_solution(lab_server):
    _, folder, _ = lab_server
    stripped = 0
    for chapter in CHAPTERS:
        source = nbformat.read(ROOT / "book" / f"{chapter}.ipynb", as_version=4)
        lab = nbformat.read(folder / f"{chapter}.ipynb", as_version=4)
        assert not [c for c in lab.cells if "solution" in c.metadata.get("tags", [])], chapter
        assert not [c for c in lab.cells if "{solution" in c.source], chapter
        code = [c for c in source.cells if c.cell_type == "code"]
        solutions = [c for c in code if "solution" in c.metadata.get("tags", [])]
        assert sum(c.cell_type == "code" for c in lab.cells) == len(code) - len(solutions)
        stripped += len(solutions)
    assert stripped > 0  # there were solutions to take out


def test_make_lab_started_as_root_when_run_as_root(lab_server):
    _, _, log = lab_server
    said = "running as root, so JupyterLab is started with --allow-root"
    assert (said in log.read_text()) == (os.geteuid() == 0)


@pytest.mark.parametrize("interface", ["lab/tree", "notebooks"])
def test_a_chapter_reads_in_jupyter_with_the_numbers_of_its_page(
        lab_server, browser, built_book, interface, note):
    url, folder, _ = lab_server
    started = time.monotonic()
    # (`?reset`: JupyterLab opens this notebook alone, not the tabs it had open before.)
    page = f"{url}/lab/tree/{CHAPTER}.ipynb?reset" if interface == "lab/tree" \
        else f"{url}/notebooks/{CHAPTER}.ipynb"
    numbers = _check_chapter_reads_as_its_page(
        browser, page, folder, built_book,
        ignored=NOTEBOOK7_OWN if interface == "notebooks" else None)
    assert numbers >= 10
    note(f"{interface}: {numbers} glued numbers of the page found in {CHAPTER}, page read "
         f"in {time.monotonic() - started:.1f} s")
