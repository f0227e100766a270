"""book/_ext/shared_navigation.py: the source pages' navigation, computed once per set
of links, is the navigation the theme computes for each page (the HTML written is the
same bytes), and it is computed fewer times than there are source pages."""

import subprocess
import sys

from conftest import ROOT

CONF = """
import sys
sys.path[:0] = [{ext!r}, {src!r}]
extensions = ["sphinx.ext.autodoc", "sphinx.ext.viewcode"] + {extra!r}
html_theme = "sphinx_book_theme"
"""
INDEX = """Home
====

.. toctree::

   first
   second/page
"""


def _project(folder, extra):
    """A small book like ours: two documents in the table of contents (one in a
    folder), autodoc on modules at three depths, viewcode's source pages for them."""
    source = folder / "source"
    code = folder / "code"
    for package in ("pkg", "pkg/sub", "pkg/sub/deep"):
        (code / package).mkdir(parents=True, exist_ok=True)
        for module in ("__init__", "mod", "other"):
            (code / package / f"{module}.py").write_text(
                '"""A module."""\n\n\ndef f():\n    """A function."""\n    return 1\n')
    (source / "second").mkdir(parents=True)
    (source / "conf.py").write_text(CONF.format(ext=str(ROOT / "book" / "_ext"),
                                                src=str(code), extra=extra))
    (source / "index.rst").write_text(INDEX)
    (source / "first.rst").write_text(
        "First\n=====\n\nSection\n-------\n\n.. automodule:: pkg.mod\n   :members:\n\n"
        ".. automodule:: pkg.sub.mod\n   :members:\n\n.. automodule:: pkg.other\n   :members:\n"
        "\n.. automodule:: pkg.sub.other\n   :members:\n\n.. automodule:: pkg\n   :members:\n")
    (source / "second" / "page.rst").write_text(
        "Second\n======\n\n.. automodule:: pkg.sub.deep.mod\n   :members:\n\n"
        ".. automodule:: pkg.sub.deep\n   :members:\n\n.. automodule:: pkg.sub\n   :members:\n\n"
        ".. automodule:: pkg.sub.deep.other\n   :members:\n")
    return source


BUILD = """
import sys
from sphinx.application import Sphinx
source, out, doctrees = sys.argv[1:4]
app = Sphinx(source, source, out, doctrees, "html", status=None, warning=sys.stderr,
             warningiserror=True, freshenv=True)
app.build()
print(len(app.builder.__dict__.get("_icm_shared_navigation", {})))
"""


def _build(folder, extra):
    """Builds the small book in a process of its own (Sphinx registers its nodes once
    per process): (navigations computed and kept, {HTML file: bytes})."""
    source = _project(folder, extra)
    out = folder / "html"
    done = subprocess.run([sys.executable, "-c", BUILD, source, out, folder / "doctrees"],
                          capture_output=True, text=True, cwd=folder)
    assert done.returncode == 0 and not done.stderr.strip(), done.stderr[-4000:]
    return int(done.stdout.split()[-1]), {
        path.relative_to(out): path.read_bytes() for path in out.rglob("*.html")}


def test_the_source_pages_navigation_is_shared_and_unchanged(tmp_path):
    _, alone = _build(tmp_path / "alone", [])
    computed, shared = _build(tmp_path / "shared", ["shared_navigation"])
    sources = [path for path in shared if path.parts[0] == "_modules"]
    assert len(sources) == 10  # the source pages, in three folders, and their index
    assert alone.keys() == shared.keys()
    for path in alone:
        assert alone[path] == shared[path], path
    # One navigation per folder of non-document pages (the index and the search pages
    # at the top share theirs), not one per page.
    assert 0 < computed < len(sources)
