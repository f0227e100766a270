"""The words of strength in the chapters' prose ("every", "always", "never", "in every
seed", "at every point", "clear", "exactly", "most", causal "because", "only because",
"so ... no", ...) each need a check of matching strength (book/_ext/claim_words.py; the
convention is in CONTRIBUTING, "Claims"): checked on every chapter, as written and with
the built book's glued phrases in place, and on made-up ones, one planted overclaim of
each pattern, that must fail."""

import ast
import json
import re
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "book" / "_ext"))

import claim_words  # noqa: E402 (book/_ext)

from icm import chapters  # noqa: E402

NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))
UNDER_REWRITE = set()
"""Chapters 3, 6 and 7, whose words other branches are rewriting (issue 44): their flags
are listed (`test_the_chapters_under_rewrite_are_listed`), not yet required empty."""


def registry(chapter):
    """A chapter's registry of words of strength: `STRONG_WORDS` of its module in
    `icm.chapters`, with its older `BOLD_CLAIMS` ({} for a chapter with no module)."""
    module = getattr(chapters, chapter, None)
    return {**getattr(module, "BOLD_CLAIMS", {}), **getattr(module, "STRONG_WORDS", {})}


def prose_and_code(chapter):
    """(the chapter's prose: Markdown cells and figure captions, its code cells)."""
    cells = json.loads((ROOT / "book" / f"{chapter}.ipynb").read_text())["cells"]
    text = lambda cell: "".join(cell["source"])
    captions = [c["metadata"].get("mystnb", {}).get("figure", {}).get("caption", "")
                for c in cells]
    return ([text(c) for c in cells if c["cell_type"] == "markdown"] + captions,
            [text(c) for c in cells if c["cell_type"] == "code"])


def _dict_keys(node):
    """The constant string keys of a dict literal, or of `dict(...)` keywords."""
    if isinstance(node, ast.Dict):
        return {k.value for k in node.keys if isinstance(k, ast.Constant)}
    return set()


def _attribute_value(node):
    """The value of `chapters.module.NAME` (or `icm.chapters...`), None otherwise."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
    parts = parts[::-1]
    if "chapters" not in parts:
        return None
    value = chapters
    for part in parts[parts.index("chapters") + 1:]:
        value = getattr(value, part, None)
    return value if isinstance(value, dict) else None


def checked_claims(code_cells):
    """The claim names a chapter checks when it is built: the keys of every claims dict
    it passes to `require(claims, texts)` (a dict literal), and the keys of the texts
    when they are a chapter module's dict (`require(result.claims(),
    chapters.x.CLAIMS)`)."""
    names = set()
    for code in code_cells:
        try:
            tree = ast.parse(code)
        except SyntaxError:  # a cell magic
            continue
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Call) and getattr(
                    node.func, "attr", getattr(node.func, "id", None)) == "require"):
                continue
            if node.args:
                names |= _dict_keys(node.args[0])
            if len(node.args) > 1:
                texts = _attribute_value(node.args[1])
                names |= set(texts or ()) if not isinstance(node.args[0], ast.Dict) \
                    else set()
    return names


def rule_tests():
    """Every test of tests/ as "tests/file.py::name": what a "rule" check may name."""
    ids = set()
    for path in (ROOT / "tests").glob("test_*.py"):
        for name in re.findall(r"^def (test_\w+)", path.read_text(), re.M):
            ids.add(f"tests/{path.name}::{name}")
    return ids


def glued_phrases(chapter, executed):
    """{glue name: text} of the phrases (strings) the built chapter glued."""
    glued = json.loads((executed / f"{chapter}.glue.json").read_text())
    out = {}
    for name, output in glued.items():
        plain = output.get("data", {}).get("text/plain")
        if plain is None:
            continue
        try:
            value = ast.literal_eval(plain)
        except (ValueError, SyntaxError):
            continue
        if isinstance(value, str):
            out[name] = value
    return out


CHECKED = [p.stem for p in NOTEBOOKS if p.stem not in UNDER_REWRITE]


@pytest.mark.parametrize("chapter", CHECKED)
def test_every_strong_word_in_a_chapters_prose_has_a_check_of_its_strength(chapter):
    markdown, code = prose_and_code(chapter)
    assert claim_words.problems(markdown, registry(chapter),
                                checked_claims(code) | rule_tests()) == []
    # Every registered fragment is still in the chapter (a stale entry hides nothing).
    assert claim_words.unused(markdown, registry(chapter)) == []


@pytest.mark.book
@pytest.mark.parametrize("chapter", CHECKED)
def test_every_glued_phrase_of_strength_has_a_check_of_its_strength(chapter, built_book):
    executed = built_book.parent / "jupyter_execute" / "book"
    markdown, code = prose_and_code(chapter)
    glued = glued_phrases(chapter, executed)
    assert claim_words.problems(markdown, registry(chapter),
                                checked_claims(code) | rule_tests(), glued) == []


def test_the_chapters_under_rewrite_are_listed():
    # Chapters 3, 6 and 7 are rewritten on other branches: the checker reads them too,
    # and what it flags there is that work's list (printed with -s).
    for chapter in sorted(UNDER_REWRITE):
        markdown, code = prose_and_code(chapter)
        flagged = claim_words.problems(markdown, registry(chapter),
                                       checked_claims(code) | rule_tests())
        print(f"{chapter}: {len(flagged)}", *flagged, sep="\n  ")


# --- planted overclaims: one of each pattern, each must fail ------------------------

PLANTED = {
    "every": ("Red is mastered first in every layout ({glue:text}`share:.0%` of seeds).",
              "share"),
    "always": ("Red is always mastered first ({glue:text}`share:.0%` of the seeds).",
               "share"),
    "never": ("The critic never diverges ({glue:text}`share:.1%` of the seeds).", "share"),
    "in every seed": ("Red came first in every seed of the study.", "all"),
    "at every point": ("Blue is found at every point of the map "
                       "({glue:text}`share:.0%`).", "share"),
    "in all N": ("The teacher was sooner in all 8 cases.", "mean"),
    "only because": ("It learns red only because red is easy.", "mean"),
    "because": ("It learns red ({glue:text}`share:.0%`) because red is easy.", "share"),
    "so ... no": ("Red is easy ({glue:text}`share:.0%`), so no practice is needed.",
                  "share"),
    "clear": ("The difference is clear ({glue:text}`gap:.2f`).", "mean"),
    "clearly": ("Growing up is **clearly better** ({glue:text}`gap:.2f`).", "mean"),
    "exactly": ("It ends exactly as scripted ({glue:text}`share:.0%`).", "share"),
    "fastest": ("Learning progress is the fastest ({glue:text}`trial:.0f`).", "mean"),
    "most": ("Red is mastered first in most seeds ({glue:text}`share:.0%`).", "mean"),
}
"""For each pattern of `claim_words.PATTERNS`, a sentence that says it, and a check too
weak to carry it."""


PLANTED_PLAIN = {
    "every": "Red is mastered first in every layout.",
    "always": "Red is always mastered first.",
    "never": "The critic never fails to learn red.",
    "in every seed": "Red came first in every seed.",
    "at every point": "Red is predicted well at every point of the map.",
    "in all N": "The teacher was sooner in all eight cases.",
    "only because": "It learns red only because red is easy.",
    "because": "Red is learned first because it is easy.",
    "so ... no": "Red is learned at once, so no practice is needed.",
    "clear": "Learning progress learns green with a clear lead.",
    "clearly": "Growing up learns clearly faster.",
    "exactly": "Red is mastered exactly when green is.",
    "fastest": "Novelty learns the fastest.",
    "most": "Red is mastered first most of the time.",
}
"""The same overclaims with no number and no bold text: a sentence that speaks of what
the learners did needs its check all the same."""


def test_every_pattern_has_a_planted_overclaim():
    assert set(PLANTED) == set(claim_words.PATTERNS) == set(PLANTED_PLAIN)


@pytest.mark.parametrize("pattern", sorted(PLANTED_PLAIN))
def test_a_planted_overclaim_without_a_number_fails_too(pattern):
    sentence = PLANTED_PLAIN[pattern]
    found = claim_words.problems([sentence], {}, set())
    assert len(found) == 1 and "with no check" in found[0] and pattern in found[0], found
    # The same word in a sentence about the rules, not about what the learners did,
    # is the code's to check.
    assert claim_words.problems(["Each trial lights every button once."], {}, set()) == []


@pytest.mark.parametrize("pattern", sorted(PLANTED))
def test_a_planted_overclaim_of_each_pattern_fails(pattern):
    sentence, weak = PLANTED[pattern]
    assert pattern in claim_words.strength_words(sentence)
    # Unregistered: no check at all.
    found = claim_words.problems([sentence], {}, set())
    assert len(found) == 1 and "with no check" in found[0] and pattern in found[0]
    # Registered with a check too weak for its words.
    fragment = sentence[:20]
    found = claim_words.problems([sentence], {fragment: ("c", weak)}, {"c"})
    assert any(f"{pattern!r} needs a check of kind" in f for f in found), found
    # Registered with a check of its strength, but one the chapter does not run.
    kinds = claim_words.WORD_KINDS[pattern]
    if kinds:
        strong = sorted(kinds)[0]
        entry = ("c", strong, "points") if strong == "all" else ("c", strong)
        assert [f for f in claim_words.problems([sentence], {fragment: entry}, {"c"})
                if pattern in f] == []
        assert "not checked" in claim_words.problems([sentence], {fragment: entry},
                                                     {"other"})[0]


CARRIED_BY = {
    "in every seed": set(), "at every point": {"all", "rule"}, "in all N": {"all", "rule"},
    "every": {"all", "rule"}, "always": {"all", "rule"}, "never": {"all", "rule"},
    "only because": {"causal"}, "because": {"causal", "rule"},
    "so ... no": {"causal", "rule"}, "clear": {"corrected"}, "clearly": {"corrected"},
    "exactly": {"exact"}, "fastest": {"corrected"},
    "most": {"corrected", "majority", "bound", "rule"},
}
"""What carries each word, written out here as the specification (the module's table is
what is tested against it): a mean never carries "never", "every" or "clear"."""


@pytest.mark.parametrize("pattern, kind", [
    (pattern, kind) for pattern in sorted(CARRIED_BY) for kind in sorted(claim_words.KINDS)])
def test_each_word_is_carried_by_the_checks_of_its_strength_and_no_other(pattern, kind):
    sentence = PLANTED[pattern][0]
    entry = ("c", kind, "points") if kind == "all" else ("c", kind)
    found = [f for f in claim_words.problems([sentence], {sentence[:20]: entry}, {"c"})
             if f"{pattern!r}" in f]
    if kind in CARRIED_BY[pattern]:
        assert found == [], found
    else:
        assert any(f"{pattern!r} needs a check of kind" in f for f in found), found


def test_every_seed_is_carried_by_no_check_and_all_needs_a_set_that_is_not_seeds():
    sentence = "Red came first in every seed ({glue:text}`share:.0%`)."
    for entry in [("c", "all", "points"), ("c", "bound"), ("c", "exact")]:
        found = claim_words.problems([sentence], {"Red came": entry}, {"c"})
        assert any("'in every seed' needs a check of kind nothing" in f for f in found)
    always = "Red is always first ({glue:text}`share:.0%`)."
    for over in (None, "seeds", "runs"):
        entry = ("c", "all") if over is None else ("c", "all", over)
        found = claim_words.problems([always], {"Red is": entry}, {"c"})
        assert len(found) == 1 and "is a sample" in found[0], found
    assert claim_words.problems([always], {"Red is": ("c", "all", "learners")},
                                {"c"}) == []
    # "in at least X% of the seeds" carries no universal word and needs no entry.
    assert claim_words.problems(["Red came first in at least {glue:text}`low:.0%` of "
                                 "the seeds."], {}, set()) == []


def test_a_glued_phrase_is_read_in_place():
    # The notebook shows the phrase's name; the build glues "in all 8 cases".
    cell = "With a teacher the robot pressed sooner {glue:text}`shown_sooner`."
    assert claim_words.problems([cell], {}, set()) == []
    found = claim_words.problems([cell], {}, set(), {"shown_sooner": "in all 8 cases"})
    assert len(found) == 1 and "in all N" in found[0]
    entry = {"{glue:text}`shown_sooner`": ("sooner", "all", "cases of the held-out seeds")}
    assert claim_words.problems([cell], entry, {"sooner"},
                                {"shown_sooner": "in all 8 cases"}) == []
    assert claim_words.problems([cell], entry, {"sooner"},
                                {"shown_sooner": "in 6 of 8 cases"}) == []


def test_all_prose_is_read_folds_lists_and_titles_not_code_or_maths():
    cell = """Some text.

:::{dropdown} Is red always first?
:class: note
In the fold, red is mastered first in every seed.
:::

- a list item that says **most** of it ({glue:text}`x:.0%`)

```python
# code is not prose: always, every seed
```

$$\\text{never}$$"""
    found = claim_words.problems([cell], {}, set())
    assert len(found) == 2, found
    assert "in every seed" in found[0] and "most" in found[1]
    # A fold's title is a sentence of its own (a question: not a result, no glue).
    assert "Is red always first?" in claim_words.sentences(cell)


def test_the_words_are_whole_words_and_descriptions_without_results_pass():
    assert claim_words.strength_words("Everything is mostly unclear, however") == []
    assert claim_words.strength_words("Every seed, most seeds, Clearly") == [
        "in every seed", "clearly", "most"]
    # A rule of the experiment, quoting no result, is not a claim about the data.
    assert claim_words.problems(["The boxes shut before every press."], {}, set()) == []
    # The same words beside a measured number are.
    assert claim_words.problems(["The boxes shut before every press "
                                 "({glue:text}`n:.0f`)."], {}, set())


def test_a_stale_entry_is_reported():
    assert claim_words.unused(["Red is **always** first."],
                              {"Red is": ("c", "all", "x"), "Gone": ("d", "all", "x")}) \
        == ["Gone"]
