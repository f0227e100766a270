"""The chapter "What the result depends on" (book/robustness.ipynb) in words: its maps
of the unpublished settings (`maps`) and the other readings of its unpublished choices
(`readings`), with the bold claims and words of strength of the whole chapter
(`BOLD_CLAIMS`, `STRONG_WORDS`).
"""

from icm.chapters.robustness import maps, readings

BOLD_CLAIMS = {
    "red comes first at every point of this map, whatever the presses and the "
    "reading": ("weight_above_settles_red", "all"),
    "Red is predicted well first at every point of this map": ("critic_red_everywhere",
                                                               "all"),
    "Red toppled first holds at every point of the map": ("rods_toppled_first_everywhere",
                                                          "all"),
}
"""The bold claims of the chapter "What the result depends on" that use a word of
strength (book/_ext/claim_words.py), each with the claim of `CHAPTER_CLAIMS` that
checks it and the kind of that check: "all", every point's verdict "holds" (a claim
that must hold at every point of a map is the conjunction of the points' own tests,
which needs no correction for their number: it fails if any one fails)."""

STRONG_WORDS = {
    **{text: (name, kind, "points") for text, (name, kind) in BOLD_CLAIMS.items()},
    "it holds at every point with an initial Q": ("rods_blue_needs_drive", "all", "points"),
    # Exercise 6.1's rule ("never" is -1), which the exercise's check holds answers to.
    'the trials counted from 1 and -1 meaning "never"': (
        "tests/test_exercises.py::test_a_typical_wrong_answer_fails_naming_the_case", "rule"),
    '"Never" is `-1`, the smallest number': (
        "tests/test_exercises.py::test_a_typical_wrong_answer_fails_naming_the_case", "rule"),
}
"""The chapter's sentences that say a word of strength about its maps, in the form the
reading of all prose takes (book/_ext/claim_words.py: {a fragment of the sentence: (claim
name, kind, the set an "all" claim is over)}): each claim about all the points of a map
is over the map's points (a finite set, each point decided by its own interval), never
over seeds. `BOLD_CLAIMS` holds the bold ones in the older form."""

__all__ = ["BOLD_CLAIMS", "STRONG_WORDS", "maps", "readings"]
