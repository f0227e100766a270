"""The student's path through each chapter (issue 26): objectives first, takeaways
last, at most `reading_path.MAX_WORDS` words of prose outside the folds, and no visible
code cell that only does the book's bookkeeping (glue, claim checks).

The counting lives in book/_ext/reading_path.py, which `python book/_ext/reading_path.py
HTML_DIR` also prints; the checks here are also run on made-up notebooks and pages, so
that a counter that saw nothing could not pass."""

import json
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "book" / "_ext"))

import reading_path  # noqa: E402 (book/_ext)

CHAPTERS = reading_path.chapters()


@pytest.mark.parametrize("notebook", CHAPTERS, ids=lambda p: p.stem)
def test_every_chapter_opens_with_objectives_and_ends_with_takeaways(notebook):
    path = reading_path.notebook_path(notebook)
    assert path["objectives_first"], f"{notebook.name}: no objectives block after the title"
    assert path["takeaways_last"], f"{notebook.name}: no takeaways block before the exercises"


@pytest.mark.parametrize("notebook", CHAPTERS, ids=lambda p: p.stem)
def test_no_visible_code_cell_does_bookkeeping(notebook):
    path = reading_path.notebook_path(notebook)
    assert path["visible_bookkeeping"] == [], \
        f"{notebook.name}: cells {path['visible_bookkeeping']} glue or check claims in view"


def _notebook(tmp_path, cells):
    path = tmp_path / "made_up.ipynb"
    path.write_text(json.dumps({"cells": cells, "metadata": {}, "nbformat": 4,
                                "nbformat_minor": 5}))
    return path


def _md(text, tags=()):
    return {"cell_type": "markdown", "metadata": {"tags": list(tags)}, "source": text}


def _code(text, tags=()):
    return {"cell_type": "code", "metadata": {"tags": list(tags)}, "source": text,
            "outputs": [], "execution_count": None}


def test_the_path_checks_fail_on_a_chapter_without_them(tmp_path):
    bare = _notebook(tmp_path, [_md("# Title\n\nSome story.\n"),
                                _code("glue('x', 1, display=False)"),
                                _code("glue('y', 2, display=False)", ["remove-cell"]),
                                _md("## Exercises\n")])
    path = reading_path.notebook_path(bare)
    assert not path["objectives_first"] and not path["takeaways_last"]
    assert path["visible_bookkeeping"] == [1]
    good = _notebook(tmp_path, [
        _md("# Title\n\n:::{admonition} Learning objectives\n:class: icm-objectives\n"
            "- explain\n:::\n"),
        _code("result = run()"),
        _md("## Summary\n\n:::{admonition} Key takeaways\n:class: icm-takeaways\n- one\n:::\n"),
        _md("## Exercises\n")])
    assert reading_path.notebook_path(good) == {
        "visible_code": 1, "visible_bookkeeping": [], "objectives_first": True,
        "takeaways_last": True}


def test_words_in_folds_code_and_solutions_are_not_counted(tmp_path):
    page = tmp_path / "page.html"
    page.write_text(
        "<html><body><article class='bd-article'><p>one two three</p>"
        "<details><summary>How do we know?</summary><p>four five</p></details>"
        "<div class='cell'><div class='cell_input'><pre>x = 1</pre></div></div>"
        "<div class='solution dropdown'><p>six seven</p></div>"
        "</article></body></html>")
    assert reading_path.visible_words(page) == 3


@pytest.mark.book
def test_every_chapter_reads_in_about_twenty_minutes(built_book):
    rows = reading_path.report(built_book)
    long = {r["chapter"]: r["words"] for r in rows if r["words"] > reading_path.MAX_WORDS}
    assert not long, f"chapters over {reading_path.MAX_WORDS} words outside folds: {long}"
