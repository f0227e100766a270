"""The chapter "Forming actions" (book/forming_actions.ipynb) in words: its first half,
the strategies and variants of goal babbling (`strategies`); its second half, the
remedies, growing up and being shown (`remedies`); and its one family of paired
comparisons over both, decided together and replicated on a fresh root (`family`).
The runs are `icm.experiments.goal_babbling`'s, the stored studies
`icm.studies.forming_actions`' (`strategies` and `remedies`).
"""

from icm.chapters.forming_actions import family, remedies, strategies

STRONG_WORDS = {
    "we call a difference clear only when it survives Holm's correction":
        ("clear_is_holm", "corrected"),
    "Each clear verdict was rerun on a root seed no study uses":
        ("clear_is_holm", "corrected"),
    "the lower error is not only because the demonstrations": (
        "shown1_lower_without_demonstrations", "causal"),
    "A difference is called clear only when chance is an unlikely explanation": (
        "clear_is_holm", "corrected"),
    "{glue:text}`rem_shown_sooner`":
        ("shown_sooner_held_out", "all", "cases: each shown button in each condition "
                                          "with a teacher, medians of the held-out seeds"),
    # Last, so that a sentence's own entry comes first: every sentence that quotes a
    # glued verdict ("clearly lower", "no clear difference") quotes Holm's.
    "_verdict`": ("clear_is_holm", "corrected"),
}
"""The chapter's sentences with a word of strength beside a result, and the checks that
carry them (book/_ext/claim_words.py): {a fragment of the sentence: (claim name the
chapter checks when built, kind[, the set an "all" claim is over])}. The shown buttons'
"in all 8 cases" (a glued phrase) is over the 8 cases, each a comparison of medians of
the held-out seeds, which the sentence says."""

__all__ = ["STRONG_WORDS", "family", "remedies", "strategies"]
