"""Shared fixtures: the book, built once per test session as CI builds it."""

import pathlib
import subprocess
import sys

import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[1]


def toc_files():
    """The book's pages in table-of-contents order (paths without suffix)."""
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    chapters = list(toc.get("chapters", []))
    for part in toc.get("parts", []):
        chapters += part["chapters"]
    return [toc["root"]] + [chapter["file"] for chapter in chapters]


@pytest.fixture(scope="session")
def built_book(tmp_path_factory):
    """Builds the whole book once, as CI does: -W (warnings fatal), --keep-going, every
    notebook executed; returns the folder of the HTML."""
    out = tmp_path_factory.mktemp("book")
    jupyter_book = pathlib.Path(sys.executable).parent / "jupyter-book"
    completed = subprocess.run(
        [str(jupyter_book), "build", str(ROOT), "-W", "--keep-going", "--path-output", str(out)],
        capture_output=True, text=True, cwd=ROOT)
    log = completed.stdout + completed.stderr
    assert completed.returncode == 0, "book build failed:\n" + log[-6000:]
    return out / "_build" / "html"
