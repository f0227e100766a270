"""The book says only what its code computes: no result, and no setting, is typed in its
prose. A number in a chapter's text or captions must be glued from the notebook's own
run (`{glue:text}`), or be one of the few typed numbers listed here, each with the
reason it may be typed: a value of the model that is not a result (an encoding, a cell
of the grid), the paper's own words, or arithmetic the sentence shows.

What is left out before looking for numbers: glue and other roles, citations, math,
inline code, links, quotations (the paper's words), references to the paper's
figures, sections and equations, and the statements of the exercises: a `{exercise}`
directive block, or what lies between `{exercise-start}` and `{exercise-end}`, whose
numbers are the problem's parameters, given to the student. Only the statement is
skipped: the solutions (`{solution}` blocks, `{solution-start}` to `{solution-end}`)
and the explanations of a question's answer (`{div} icm-quiz-explanation`, even inside
an exercise) quote results, and are read like the rest of the chapter.
"""

import re

import nbformat
import pytest

from conftest import ROOT

NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))

_ROLE = re.compile(r"\{[\w:-]+\}`[^`]*`")
_MATH = re.compile(r"\$\$.*?\$\$|\$[^$\n]+\$", re.S)
_CODE = re.compile(r"```.*?```|`[^`\n]*`", re.S)
_LINK = re.compile(r"\]\([^)]*\)")
_BLOCK_QUOTE = re.compile(r"^>.*$", re.M)  # the paper's words, quoted
_QUOTE = re.compile(r"\"[^\"\n]*\"|“[^”\n]*”")
_REFERENCE = re.compile(
    r"\b(?:[Ff]igures?|[Ss]ections?|[Ee]quations?|[Cc]hapters?|[Tt]ables?)\s+"
    r"\d+(?:\.\d+)*[a-z]?(?:\s*(?:,|and|or|to)\s*\d+(?:\.\d+)*[a-z]?)*"
    r"|\(([a-c])\)|\b[Ff]igure\s+\d+\([a-c]\)")
_LIST_MARKER = re.compile(r"^\s*\d+\.\s", re.M)
_NUMBER = re.compile(r"(?<![\w.])\d+(?:[.,]\d+)*%?(?![\w])")
_EXERCISE_BLOCK = re.compile(r"^(?P<fence>:{3,})\{exercise\}.*?^(?P=fence)[ \t]*$", re.M | re.S)
_EXERCISE_SPAN = re.compile(r"^```\{exercise-start\}.*?^```\{exercise-end\}[ \t]*\n```",
                            re.M | re.S)
_QUIZ_EXPLANATION = re.compile(
    r"^(?P<fence>:{3,})\{div\}[ \t]*icm-quiz-explanation.*?^(?P=fence)[ \t]*$", re.M | re.S)

ALLOWED = {
    # Everywhere: the model's encodings and the grid's geometry, which are not results.
    "*": [
        "5 x 3",            # the paper's grid of hand positions
        "0 off, 1 red, 2 green",  # the lights' encoding in an observation
        "1 open",           # the boxes' encoding
        "0 standing, 1 toppled",  # the rods' encoding
    ],
    "button_experiment": [
        # The labels of the arrows of the paper's Figure 2, which the caption reads out.
        "(1) observe, (2) ask the predictor for the effect of an action, (3) pass the "
        "predicted effect, a task, to the interest module, (4) get back its interest. "
        "Steps 2 to 4",
    ],
    "goal_oriented_interest": [
        "2 to k-1",  # which histories the paper's definition leaves out (a definition)
    ],
    "simulated_icub": [
        "cell (2, 2)",  # a cell of the grid, named in the text (the map's hatched cell)
    ],
    "rod_toppling": [
        "cell (0, 0)", "cell (2, 2)", "(2, 2)",  # cells of the grid, named in the text
        "Columns 0-4", "rows 0-2",  # the grid's numbering
        "runs count from 0", "run 0",  # the runs' numbering: run 0 is the first run
    ],
}


def typed_numbers(text, allowed):
    """The numbers typed in `text` (a chapter's markdown), with the line each is on,
    once roles, math, code, links, quotes and references are left out, and the
    `allowed` phrases."""
    for pattern in (_CODE, _ROLE, _MATH, _LINK, _BLOCK_QUOTE, _REFERENCE, _LIST_MARKER):
        text = pattern.sub(" ", text)
    # One line per paragraph (or list item), so that a phrase may span lines.
    text = re.sub(r"\n(?!\n|\s*[-*|#])", " ", text)
    text = re.sub(r"[ \t]+", " ", text)
    text = _QUOTE.sub(" ", text)
    for phrase in allowed:
        text = text.replace(phrase, " ")
    found = []
    for line in text.splitlines():
        for match in _NUMBER.finditer(line):
            found.append((match.group(), line.strip()))
    return found


def without_exercise_statements(text):
    """`text` (a chapter's markdown, its cells joined in order) less the statements of
    its exercises (see the module's docstring): the explanations of questions inside
    an exercise are kept, and so is everything outside one."""
    def explanations(span):
        return "\n\n".join(m.group(0) for m in _QUIZ_EXPLANATION.finditer(span.group(0)))

    text = _EXERCISE_SPAN.sub(explanations, text)
    return _EXERCISE_BLOCK.sub(" ", text)


def chapter_text(path):
    """The markdown of a notebook (less the exercises' statements) and the captions of
    its figures, one string."""
    nb = nbformat.read(path, as_version=4)
    parts = [without_exercise_statements(
        "\n\n".join(c.source for c in nb.cells if c.cell_type == "markdown"))]
    for cell in nb.cells:
        figure = cell.metadata.get("mystnb", {}).get("figure", {})
        if "caption" in figure:
            parts.append(figure["caption"])
    return "\n\n".join(parts)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_no_result_or_setting_is_typed_in_a_chapter(path):
    allowed = ALLOWED["*"] + ALLOWED.get(path.stem, [])
    found = typed_numbers(chapter_text(path), allowed)
    assert found == [], (
        f"{path.name} types numbers in its prose: glue them from the notebook's code "
        f"({{glue:text}}), or, for a value of the model that is not a result, add the "
        f"phrase to ALLOWED with its reason:\n" + "\n".join(
            f"  {number!r} in: {line[:110]}" for number, line in found))


def test_no_result_or_setting_is_typed_in_the_preface():
    # The preface cannot glue (it is not a notebook): it says what the chapters
    # measure, and how long they take, in words.
    found = typed_numbers((ROOT / "book" / "preface.md").read_text(), ALLOWED["*"])
    assert found == [], "preface.md types numbers:\n" + "\n".join(
        f"  {number!r} in: {line[:110]}" for number, line in found)


def test_the_scanner_finds_typed_results_and_leaves_glued_ones():
    text = ("Red is mastered first in 97% of the 200 seeds, at trial {glue:text}`red:.1f`; "
            "see Figure 5 and section 4.1, and $k = 5$.\n> the paper's 50%\n")
    assert [n for n, _ in typed_numbers(text, [])] == ["97%", "200"]
    assert typed_numbers("the grid is 5 x 3", ["5 x 3"]) == []


def test_exercise_statements_are_skipped_and_solutions_and_explanations_are_read():
    text = "\n\n".join([
        "Before: 11 seeds.",
        ":::{exercise} Extend: try 12 seeds\n:label: ex-a\n\nRun 13 seeds.\n:::",
        "After the block: 14 seeds.",
        "```{exercise-start} Predict\n:label: ex-b\n```\n\nOf 15 seeds, how many?",
        ":::{div} icm-quiz-explanation\n16 of them.\n:::\n\n```{exercise-end}\n```",
        "```{solution-start} ex-b\n```\n\nThe solution: 17 seeds.\n\n```{solution-end}\n```",
        "::::{exercise} Nested\n:::{hint}\n18\n:::\n19\n::::",
        ":::{solution} ex-a\n20 seeds\n:::",
    ])
    left = without_exercise_statements(text)
    found = [n for n, _ in typed_numbers(left, [])]
    assert found == ["11", "14", "16", "17", "20"]
