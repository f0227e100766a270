"""The book: notebooks committed clean, the table of contents complete, and a full
build with every notebook executed and every warning fatal."""

import pathlib
import subprocess
import sys

import nbformat
import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


def toc_files():
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    files = [toc["root"]]
    for chapter in toc.get("chapters", []):
        files.append(chapter["file"])
    return files


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
    notebook = nbformat.read(path, as_version=4)
    first_code = next(c for c in notebook.cells if c.cell_type == "code").source
    assert 'os.environ.setdefault("MUJOCO_GL", "egl")' in first_code
    assert "import icm" in first_code
    assert "matplotlib.use(" not in "".join(c.source for c in notebook.cells)


def test_every_chapter_is_in_the_table_of_contents_and_exists():
    listed = set(toc_files())
    on_disk = {str(p.relative_to(ROOT).with_suffix(""))
               for p in (ROOT / "book").iterdir() if p.suffix in (".ipynb", ".md")}
    assert listed == on_disk


def test_build_configuration_makes_failures_fatal():
    config = yaml.safe_load((ROOT / "_config.yml").read_text())
    assert config["execute"]["execute_notebooks"] == "force"
    assert config["execute"]["raise_on_error"] is True
    assert config["execute"]["allow_errors"] is False


@pytest.fixture(scope="session")
def built_book(tmp_path_factory):
    """Builds the whole book once, as CI does: -W (warnings fatal), --keep-going."""
    out = tmp_path_factory.mktemp("book")
    jupyter_book = pathlib.Path(sys.executable).parent / "jupyter-book"
    completed = subprocess.run(
        [str(jupyter_book), "build", str(ROOT), "-W", "--keep-going", "--path-output", str(out)],
        capture_output=True, text=True, cwd=ROOT)
    log = completed.stdout + completed.stderr
    assert completed.returncode == 0, "book build failed:\n" + log[-6000:]
    return out / "_build" / "html"


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
