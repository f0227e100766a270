"""The book: notebooks committed clean, the table of contents complete, and a full
build with every notebook executed and every warning fatal."""

import nbformat
import pytest
import yaml

from conftest import ROOT, toc_files

NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebooks_are_committed_without_outputs(path):
    notebook = nbformat.read(path, as_version=4)
    for cell in notebook.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [], f"{path.name} has outputs: clear them before committing"
            assert cell.execution_count is None, f"{path.name} has execution counts"
    assert "widgets" not in notebook.metadata, f"{path.name} carries saved widget state"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebooks_set_mujoco_gl_only_if_unset_and_import_icm(path):
    # The first code cell after the one that installs icm on Binder or Colab (checked
    # by tests/test_launch.py).
    notebook = nbformat.read(path, as_version=4)
    first_code = [c for c in notebook.cells if c.cell_type == "code"][1].source
    assert 'os.environ.setdefault("MUJOCO_GL", "egl")' in first_code
    assert "import icm" in first_code
    assert "matplotlib.use(" not in "".join(c.source for c in notebook.cells)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_every_chapter_opens_with_its_title(path):
    # The first cell a reader sees (after the install cell, which the book removes) is
    # the chapter's title, as in every chapter: no code above it.
    notebook = nbformat.read(path, as_version=4)
    shown = [c for c in notebook.cells if "remove-cell" not in c.metadata.get("tags", [])]
    assert shown[0].cell_type == "markdown" and shown[0].source.startswith("# "), \
        f"{path.name} starts with a {shown[0].cell_type} cell: {shown[0].source[:60]!r}"


def test_every_chapter_is_in_the_table_of_contents_and_exists():
    listed = set(toc_files())
    on_disk = {str(p.relative_to(ROOT).with_suffix(""))
               for p in (ROOT / "book").iterdir() if p.suffix in (".ipynb", ".md")}
    assert listed == on_disk


def test_build_configuration_makes_failures_fatal():
    config = yaml.safe_load((ROOT / "_config.yml").read_text())
    # Executed beforehand by execute_book.py (forced in the tests and CI), read from
    # the cache by the build; a notebook the build had to execute itself still fails
    # the build on an error, and within minutes if it hangs.
    assert config["execute"]["execute_notebooks"] == "cache"
    assert config["execute"]["raise_on_error"] is True
    assert config["execute"]["allow_errors"] is False
    assert config["execute"]["timeout"] <= 300


@pytest.mark.book
def test_the_install_cell_is_neither_executed_nor_shown_by_the_build(built_book):
    from jupyter_cache import get_cache
    from test_launch import INSTALL_CELL

    # The outputs the build used: those of the execution cache (the build executed no
    # notebook itself, built_book checks).
    cache = get_cache(str(built_book.parent / ".jupyter_cache"))
    for path in NOTEBOOKS:
        record = cache.match_cache_notebook(nbformat.read(path, as_version=4))
        executed = cache.get_cache_bundle(record.pk).nb
        install = executed.cells[0]
        assert install.source == INSTALL_CELL
        assert install.execution_count is None and install.outputs == [], path.name
        code = [c for c in executed.cells if c.cell_type == "code"]
        assert code[1].execution_count == 1, f"{path.name}: the kernel ran something before"
        html = (built_book / "book" / f"{path.stem}.html").read_text()
        for line in ("install icm when it is missing", "ICM_SOURCE", "find_spec"):
            assert line not in html, f"{path.name}: the install cell is shown"


@pytest.mark.book
def test_book_builds_with_every_chapter_and_figure(built_book):
    for name in toc_files():
        page = built_book / f"{name}.html"
        assert page.exists(), f"missing page {page}"
        html = page.read_text()
        assert "Traceback" not in html and "output traceback" not in html, f"error in {page}"
    for path in NOTEBOOKS:
        notebook = nbformat.read(path, as_version=4)
        expected = sum(1 for c in notebook.cells
                       if c.cell_type == "code" and "figure" in c.metadata.get("mystnb", {}))
        html = (built_book / "book" / f"{path.stem}.html").read_text()
        assert html.count("<img") >= expected, f"{path.name}: a figure did not render"
        assert "&lt;Figure size" not in html, f"{path.name}: a figure rendered as text"


def public_objects():
    """Every public class and function of the package, as "module.name" where it is
    defined: those of public modules, and those of private modules (a name part
    starting with "_") that a public package re-exports."""
    import importlib
    import inspect
    import pkgutil

    import icm

    found = set()
    for info in pkgutil.walk_packages(icm.__path__, "icm."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if name.startswith("_") or not (inspect.isclass(obj) or inspect.isfunction(obj)):
                continue
            if obj.__module__ != info.name:
                continue
            private = any(part.startswith("_") for part in info.name.split("."))
            package = importlib.import_module(info.name.rsplit(".", 1)[0])
            if not private or getattr(package, name, None) is obj:
                found.add(f"{info.name}.{name}")
    return found


@pytest.mark.book
def test_api_reference_covers_every_public_class_and_function(built_book):
    html = (built_book / "book" / "api.html").read_text()
    objects = public_objects()
    assert len(objects) > 40
    missing = sorted(name for name in objects if f'id="{name}"' not in html)
    assert missing == [], f"not in the API reference: {missing}"


@pytest.mark.book
def test_every_section_of_a_chapter_reaches_the_pages_contents(built_book):
    # Each "## " heading of a chapter's markdown (outside code fences) is a section of
    # the built page, listed in the contents beside it, in order: a heading that a
    # fold or a directive swallowed by mistake becomes a line of bold text and leaves
    # the contents.
    import html as html_module
    import re

    for name in toc_files():
        path = ROOT / f"{name}.ipynb"
        if not path.exists():
            continue
        headings = []
        for cell in nbformat.read(path, as_version=4).cells:
            if cell.cell_type != "markdown":
                continue
            fenced = False
            for line in cell.source.splitlines():
                if line.startswith("```"):
                    fenced = not fenced
                elif not fenced and line.startswith("## "):
                    headings.append(line[3:].strip())
        page = (built_book / f"{name}.html").read_text()
        contents = page[page.index('id="pst-page-toc-nav"'):]
        contents = contents[:contents.index("</nav>")]
        listed = [re.sub(r"<[^>]+>", "", html_module.unescape(entry)).strip() for entry in
                  re.findall(r'class="[^"]*toc-h2[^"]*"[^>]*>\s*<a[^>]*>(.*?)</a>',
                             contents, re.S)]
        plain = [re.sub(r"[`*]", "", h) for h in headings]
        assert len(listed) == len(plain) > 2, (name, listed, plain)
        for shown, written in zip(listed, plain):
            assert shown.replace("\u2019", "'").endswith(written.replace("\u2019", "'")), \
                (name, shown, written)


def test_the_api_pages_contents_list_its_modules(built_book):
    # The contents beside the API page: one entry per module (each a heading of
    # book/api.md, under its section), none per function, class or constant; and no
    # section id with a dot, which the contents' highlighting of where the reader is
    # cannot follow.
    import re

    source = (ROOT / "book" / "api.md").read_text()
    modules = re.findall(r"^\.\. automodule:: (\S+)$", source, re.M)
    html = (built_book / "book" / "api.html").read_text()
    contents = html[html.index('id="pst-page-toc-nav"'):]
    contents = contents[:contents.index("</nav>")]
    assert contents.count('class="toc-h3') == len(modules) > 80
    assert 'class="toc-h4' not in contents and 'href="#icm.' not in contents
    assert contents.count('class="toc-h2') == source.count("\n## ")
    sections = re.findall(r'<section id="([^"]+)"', html)  # (the page's own: a class first)
    assert len(sections) == len(modules) + source.count("\n## ")
    assert not [s for s in sections if "." in s]
    for module in modules:  # each module's heading names it, whole or within its section
        heading = re.search(rf"^\(([\w-]+)\)=\n### `([\w.]+)`\n\n```{{eval-rst}}\n\.\.\n"
                            rf"\.\. automodule:: {re.escape(module)}$", source, re.M)
        assert heading and module.endswith(heading.group(2)), module
        assert heading.group(1) == re.sub("[._]+", "-", module)
        assert f'id="{heading.group(1)}"' in html, module  # its link that stays


@pytest.mark.book
def test_no_glued_share_reads_as_all_or_none_when_it_is_not(built_book):
    # A number glued into the prose as a percentage ({glue:text}`key:.0%`) reads as
    # "every seed" at 100%: 199 seeds of 200 must not show so (nor 1 of 200 as 0%).
    import ast
    import json
    import re

    executed = built_book.parent / "jupyter_execute" / "book"
    checked = 0
    for path in NOTEBOOKS:
        glued = json.loads((executed / f"{path.stem}.glue.json").read_text())
        text = "\n".join(c.source for c in nbformat.read(path, as_version=4).cells)
        for key, spec in re.findall(r"\{glue(?::text)?\}`(\w+):([^`]*%)`", text):
            value = float(ast.literal_eval(glued[key]["data"]["text/plain"]))
            shown = format(value, spec)
            assert value in (0, 1) or not re.fullmatch(r"(100|0)(\.0*)?%", shown), \
                f"{path.name}: {key} = {value} shows as {shown}"
            checked += 1
    assert checked > 200


@pytest.mark.book
def test_chapters_have_launch_and_download_buttons(built_book):
    config = yaml.safe_load((ROOT / "_config.yml").read_text())
    repository = config["repository"]["url"].removeprefix("https://github.com/")
    for path in NOTEBOOKS:
        html = (built_book / "book" / f"{path.stem}.html").read_text()
        assert f"mybinder.org/v2/gh/{repository}/main?urlpath=lab/tree/book/{path.name}" in html
        assert f"colab.research.google.com/github/{repository}/blob/main/book/{path.name}" in html
        assert f"_sources/book/{path.name}" in html  # the notebook download button


def test_the_preface_lists_every_chapter_in_order():
    import re

    from icm._book import toc_pages

    chapters = [page.removeprefix("book/") for page in toc_pages(ROOT, "Chapters")]
    preface = (ROOT / "book" / "preface.md").read_text()
    section = preface.split("## The chapters", 1)[1].split("\n## ", 1)[0]
    listed = re.findall(r"^\d+\. \{doc\}`(\w+)`", section, re.MULTILINE)
    assert listed == chapters


@pytest.mark.book
def test_the_references_are_labelled_as_the_text_cites_them(built_book):
    # The text cites author-year ("Deci and Ryan, 1985"); the References page must
    # label each entry the same way (book/_ext/bibliography.py), not "[DR85]".
    import re

    page = (built_book / "book" / "references.html").read_text()
    labels = dict(re.findall(r'<div class="citation" id="(id\d+)"[^>]*>\s*<span class="label">'
                             r'<span class="fn-bracket">\[</span>([^<]+)<', page))
    assert len(labels) >= 10
    cited = 0
    for name in toc_files():
        html = (built_book / f"{name}.html").read_text()
        # A citation links to the References page; "#id2" alone is a heading's own
        # anchor on the same page (Sphinx numbers those ids too).
        for match in re.finditer(
                r'href="(?:book/)?references\.html#(id\d+)"[^>]*>([^<]+)</a>', html):
            anchor, text = match.groups()
            if anchor not in labels:
                continue
            if re.fullmatch(r"\d{4}[a-z]?", text):
                # A textual citation, "Deci and Ryan (1985)": the year is the link, the
                # authors stand just before it.
                authors, year = labels[anchor].rsplit(", ", 1)
                before = re.sub(r"<[^>]+>", "", html[max(0, match.start() - 400):match.start()])
                assert year == text and authors in before[-120:], \
                    (name, anchor, labels[anchor], text, before[-80:])
            else:
                assert labels[anchor] == text, (name, anchor, labels[anchor], text)
            cited += 1
    assert cited >= 10
    assert all(re.fullmatch(r"[^,]+, \d{4}[a-z]?", label) for label in labels.values()), labels
