"""The words of strength in a chapter's bold claims, and the checks they need.

A chapter's sentences in bold are its claims. A bold claim that says "clear",
"clearly", "always", "never", "every", "exactly", "fastest" or "most" must be listed in
its chapter's registry (a dict {bold text: (claim name, kind)} in the library, next to
the claims it checks: `CLAIM_KINDS` below says which registry is whose), its claim
name must be one the chapter checks when it is built (`results.require`), and the
check's kind must be one the word allows (`WORD_KINDS`). tests/test_claim_words.py
runs `problems` on every chapter, and on made-up ones.
"""

import re

KINDS = {
    "all": "holds in every case checked: every seed, every point of a map, every "
           "learner (not a share below one)",
    "corrected": "clear after Holm's correction for the chapter's family of comparisons "
                 "(icm.stats.corrected_verdicts), or a verdict named as not clear",
    "exact": "an equality checked exactly",
    "majority": "a share above one half in every case it is claimed for",
    "share": "a share at or above a threshold below one (e.g. 90% of the seeds)",
    "mean": "a comparison of means, without an interval",
}
"""The kinds of check a claim can have."""
WORD_KINDS = {
    "clear": {"corrected"}, "clearly": {"corrected"},
    "always": {"all"}, "never": {"all"}, "every": {"all"},
    "exactly": {"exact"},
    "fastest": {"corrected"},
    "most": {"corrected", "majority"},
}
"""For each word of strength, the kinds of check that can carry it: "every" needs a
check over every case, "clear" and "fastest" a corrected comparison, "most" (most
seeds) a majority in each case or (the most X) a corrected comparison."""
_BOLD = re.compile(r"\*\*(.+?)\*\*", re.DOTALL)


def normalise(text):
    """`text` with every run of white space made one space, stripped."""
    return " ".join(text.split())


def bold_spans(markdown):
    """The bold spans of a Markdown text, each normalised (`normalise`)."""
    return [normalise(m.group(1)) for m in _BOLD.finditer(markdown)]


def strength_words(text):
    """The words of `WORD_KINDS` in `text` (whole words, any case), in order."""
    found = re.findall(r"[A-Za-z]+", text.lower())
    return [word for word in found if word in WORD_KINDS]


def problems(markdown_cells, registry, checked):
    """What is wrong with a chapter's bold claims, in words (an empty list: nothing).

    Args:
      markdown_cells: the chapter's Markdown cells (texts).
      registry: {bold text (normalised): (claim name, kind of `KINDS`)}.
      checked: the claim names the chapter checks when it is built.
    """
    registry = {normalise(text): entry for text, entry in registry.items()}
    out = []
    for cell in markdown_cells:
        for span in bold_spans(cell):
            words = strength_words(span)
            if not words:
                continue
            if span not in registry:
                out.append(f"bold claim with {', '.join(words)} has no check: {span!r}")
                continue
            name, kind = registry[span]
            if kind not in KINDS:
                out.append(f"{span!r}: unknown kind {kind!r} (allowed: {sorted(KINDS)})")
                continue
            if name not in checked:
                out.append(f"{span!r}: its claim {name!r} is not checked by the chapter")
            for word in words:
                if kind not in WORD_KINDS[word]:
                    out.append(f"{span!r}: {word!r} needs a check of kind "
                               f"{' or '.join(sorted(WORD_KINDS[word]))}, its claim "
                               f"{name!r} is {kind!r}")
    return out
