"""Shared fixtures: the book, built once per test session as CI builds it, on a
machine made slow on purpose."""

import contextlib
import os
import pathlib
import subprocess
import sys

import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD_BOOK = ROOT / "book" / "_ext" / "build_book.py"
EXECUTE_BOOK = ROOT / "book" / "_ext" / "execute_book.py"


def toc_files():
    """The book's pages in table-of-contents order (paths without suffix)."""
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    chapters = list(toc.get("chapters", []))
    for part in toc.get("parts", []):
        chapters += part["chapters"]
    return [toc["root"]] + [chapter["file"] for chapter in chapters]


@contextlib.contextmanager
def cpu_burners(count=None):
    """Keeps every core busy (one process per core spinning in a loop, at normal
    priority) while the block runs: a machine made slow on purpose, as a student's
    laptop that is doing other work, a Binder fraction of a core or a shared CI
    runner."""
    if count is None:
        count = os.cpu_count() or 1
    # Each burner spins until its parent is gone, so that a test run killed before its
    # cleanup leaves no burner behind.
    spin = "import os\nparent = os.getppid()\nwhile os.getppid() == parent:\n    pass"
    burners = [subprocess.Popen([sys.executable, "-c", spin]) for _ in range(count)]
    try:
        yield len(burners)
    finally:
        for burner in burners:
            burner.kill()
        for burner in burners:
            burner.wait()


@pytest.fixture(scope="session")
def built_book(tmp_path_factory, request):
    """Builds the whole book once, as CI does, with `book/_ext/build_book.py --force
    --strict`: every notebook executed afresh into this build's own cache, then
    jupyter-book build with -W (warnings fatal), which must take every notebook from
    that cache; returns the folder of the HTML.

    The notebooks are executed while a CPU burner runs on every core (`cpu_burners`):
    the build must not fail because the machine is slow (see the rule in
    book/_ext/execute_book.py).

    While working on the browser checks, ICM_BUILT_BOOK=<folder of the HTML> reuses a
    book built before (CI never sets it)."""
    reuse = os.environ.get("ICM_BUILT_BOOK")
    if reuse:
        return pathlib.Path(reuse)
    out = tmp_path_factory.mktemp("book")
    with cpu_burners() as burning:
        completed = subprocess.run(
            [sys.executable, str(BUILD_BOOK), "--force", "--strict", "--path-output", str(out)],
            capture_output=True, text=True, cwd=ROOT)
    log = completed.stdout + completed.stderr
    assert completed.returncode == 0, "book build failed:\n" + log[-8000:]
    reporter = request.config.pluginmanager.get_plugin("terminalreporter")
    for line in completed.stdout.splitlines():
        if reporter is not None and line.startswith(("executed", "book execution")):
            reporter.write_line(line + (f" [{burning} CPU burners running]"
                                        if line.startswith("book execution") else ""))
    return out / "_build" / "html"
