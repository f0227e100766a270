"""Shared fixtures: the book, built once per test session as CI builds it."""

import os
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
def built_book(tmp_path_factory, request):
    """Builds the whole book once, as CI does: every notebook executed afresh by
    book/_ext/execute_book.py (--force, into this build's own cache), then
    jupyter-book build with -W (warnings fatal) and --keep-going, which must take
    every notebook from that cache; returns the folder of the HTML.

    While working on the browser checks, ICM_BUILT_BOOK=<folder of the HTML> reuses a
    book built before (CI never sets it)."""
    reuse = os.environ.get("ICM_BUILT_BOOK")
    if reuse:
        return pathlib.Path(reuse)
    out = tmp_path_factory.mktemp("book")
    executed = subprocess.run(
        [sys.executable, str(ROOT / "book" / "_ext" / "execute_book.py"), "--force",
         "--path-output", str(out)], capture_output=True, text=True, cwd=ROOT)
    assert executed.returncode == 0, "executing the book failed:\n" + (
        executed.stdout + executed.stderr)[-6000:]
    reporter = request.config.pluginmanager.get_plugin("terminalreporter")
    for line in executed.stdout.splitlines():
        if reporter is not None and line.startswith(("executed", "book execution")):
            reporter.write_line(line)
    jupyter_book = pathlib.Path(sys.executable).parent / "jupyter-book"
    completed = subprocess.run(
        [str(jupyter_book), "build", str(ROOT), "-W", "--keep-going", "--path-output", str(out)],
        capture_output=True, text=True, cwd=ROOT)
    log = completed.stdout + completed.stderr
    assert completed.returncode == 0, "book build failed:\n" + log[-6000:]
    assert "Executing notebook" not in log, "the build executed a notebook itself:\n" + log
    return out / "_build" / "html"
