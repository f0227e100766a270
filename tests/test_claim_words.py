"""The words of strength in the chapters' bold claims ("clear", "always", "every",
"exactly", "fastest", "most", ...) each need a check of matching strength
(book/_ext/claim_words.py; the convention is in CONTRIBUTING, "Claims"): checked on
every chapter, and on made-up ones that must fail."""

import json
import re
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "book" / "_ext"))

import claim_words  # noqa: E402 (book/_ext)

from icm import chapters  # noqa: E402

CHAPTERS = {"curiosity": chapters.curiosity.BOLD_CLAIMS,
            "robustness": chapters.robustness.BOLD_CLAIMS, "forming_actions": {}}
"""The chapters whose bold claims are checked, with their registries (Forming actions'
verdicts are glued words, Holm-corrected in icm.chapters.forming_actions; its bold
text says none of the words)."""


def _cells(chapter):
    notebook = json.loads((ROOT / "book" / f"{chapter}.ipynb").read_text())
    text = lambda cell: "".join(cell["source"])
    return ([text(c) for c in notebook["cells"] if c["cell_type"] == "markdown"],
            [text(c) for c in notebook["cells"] if c["cell_type"] == "code"])


def _checked(code_cells):
    """The claim names a chapter checks when it is built: the keys of every claims dict
    it passes to `results.require(..., chapters.module.X_CLAIMS)`."""
    names = set()
    for code in code_cells:
        for module, attribute in re.findall(r"require\([^;]*?,\s*(?:icm\.)?chapters\."
                                            r"(\w+)\.(\w+_CLAIMS)\)", code):
            names |= set(getattr(getattr(chapters, module), attribute))
    return names


@pytest.mark.parametrize("chapter", sorted(CHAPTERS))
def test_every_strong_word_in_a_bold_claim_has_a_check_of_its_strength(chapter):
    markdown, code = _cells(chapter)
    checked = _checked(code)
    assert claim_words.problems(markdown, CHAPTERS[chapter], checked) == []
    # Every registered claim is still in the chapter (a stale entry hides nothing).
    spans = {s for cell in markdown for s in claim_words.bold_spans(cell)}
    assert set(map(claim_words.normalise, CHAPTERS[chapter])) <= spans


MADE_UP = """- **Red is always mastered first**: in {glue:text}`share:.0%` of the seeds.
- **Green comes later.**"""


def test_a_made_up_always_over_a_90_percent_check_fails():
    registry = {"Red is always mastered first": ("red_first", "share")}
    found = claim_words.problems([MADE_UP], registry, {"red_first"})
    assert len(found) == 1 and "'always' needs a check of kind all" in found[0]


def test_a_made_up_always_over_an_every_seed_check_passes():
    registry = {"Red is always mastered first": ("red_first", "all")}
    assert claim_words.problems([MADE_UP], registry, {"red_first"}) == []


def test_a_strong_bold_claim_without_a_check_or_with_an_unchecked_one_fails():
    assert "has no check" in claim_words.problems([MADE_UP], {}, set())[0]
    registry = {"Red is always mastered first": ("red_first", "all")}
    assert "not checked" in claim_words.problems([MADE_UP], registry, {"other"})[0]
    clear = "The margin is **clearly better** than chance."
    wrong = claim_words.problems([clear], {"clearly better": ("margin", "mean")}, {"margin"})
    assert "'clearly' needs a check of kind corrected" in wrong[0]
    assert claim_words.problems([clear], {"clearly better": ("margin", "corrected")},
                                {"margin"}) == []


def test_the_words_are_whole_words():
    assert claim_words.strength_words("Everything is mostly unclear") == []
    assert claim_words.strength_words("Every seed, most seeds, Clearly") == [
        "every", "most", "clearly"]
