"""The chapter "Actor-critic" (book/actor_critic.ipynb): the claims about Figure 6 it
states in words (`CLAIMS`) and their check on a run (`claims`), how the learner paid
for green learns red (`red_from_first_press`, `PAID_CLAIMS`), and its table of runs
(`comparison_table`), all read from an `ActorCriticResult`."""

import numpy as np

from icm import _validate
from icm.chapters.words import measures_table, percent
from icm.experiments.actor_critic_results import LATE_TRIALS, ActorCriticResult
from icm.experiments.results import check_results
from icm.stats import share_interval


CLAIMS = {
    "red_sooner": "the red error reaches zero for good sooner than the green one on average",
    "red_first_mostly": "the red error reaches zero first in most seeds",
    "green_below_only_before_red_press": "the green error is below the red one only before "
                                         "the red button was first pressed",
}
"""The claims about Figure 6 that the book states in words (`claims`)."""


def claims(result):
    """{claim name: whether it holds in `result`, an `ActorCriticResult`}, for each of
    `CLAIMS` (checked on the book's run when it is built, and by the tests on their own
    seeds)."""
    result = _validate.instance("result", result, ActorCriticResult,
                                "an ActorCriticResult (from icm.experiments.run_actor_critic)")
    s = result.summary()
    return {"red_sooner": s["red_zero_mean"] < s["green_zero_mean"],
            "red_first_mostly": s["red_first"] > 0.5,
            "green_below_only_before_red_press":
                result.green_below_red_only_before_red_press()}


def comparison_table(results):
    """A Markdown table of the numbers that tell actor-critic runs apart, one column per
    run.

    Args:
      results: a dict {column label: ActorCriticResult}.

    Returns:
      A Markdown string (display it with `IPython.display.Markdown`); the trials
      marked † are means over the seeds whose error does reach 0.
    """
    check_results("results", results, ActorCriticResult)
    summaries = {id(r): r.summary() for r in results.values()}

    def shown(value, fmt):  # fmt: a format spec, or a function such as `percent`
        return fmt(value) if callable(fmt) else f"{value:{fmt}}"

    def number(key, fmt):
        return lambda r: shown(summaries[id(r)][key], fmt)

    def pair(key, fmt):
        return lambda r: (f"{shown(summaries[id(r)]['red_' + key], fmt)} / "
                          f"{shown(summaries[id(r)]['green_' + key], fmt)}")

    table = measures_table(results, [
        ("seeds", lambda r: str(r.n_seeds)),
        ("error 0 from trial (mean†): red / green", pair("zero_mean", ".1f")),
        ("green learned", number("green_zero_share", percent)),
        ("red first", number("red_first", percent)),
        ("green below red at some trial", number("green_below_red", percent)),
        (f"presses opening red / green, last {LATE_TRIALS} trials",
         pair("late_practice_share", percent)),
        ("largest abs(V)", number("max_abs_value", ".3g")),
    ])
    return table + "\n\n† mean over the seeds whose error reaches 0 for good within the run."


def red_from_first_press(result):
    """How the learner of `result` (an `ActorCriticResult`, e.g. paid for green) learns
    red: among the seeds whose red error reaches zero for good, in how many it does so
    from the first trial in which a press opened the red box, with that share's 95%
    Wilson interval; how many of those trials held a single such press; the median of
    that trial; and the learner's mean probability of pressing green then and at the
    end. A dict {"learned", "n_seeds", "from_first", "share", "low", "high", "single",
    "first_median", "green_probability_then", "green_probability_end"}."""
    _validate.instance("result", result, ActorCriticResult)
    zero = result.zero_trial[:, 0]
    red_presses = result.practice[:, :, 0]  # presses that opened the red box, per trial
    pressed = red_presses > 0
    first = np.where(pressed.any(axis=1), np.argmax(pressed, axis=1) + 1, -1)
    learned = zero >= 1
    if not learned.any():
        raise ValueError("result: no seed learns red, so nothing to count")
    from_first = learned & (zero == first)
    k, n = int(from_first.sum()), int(learned.sum())
    low, high = share_interval(k, n)
    seeds = np.flatnonzero(from_first)
    green = result.press_probability[:, :, 1]
    return {"learned": n, "n_seeds": result.n_seeds, "from_first": k, "share": k / n,
            "low": low, "high": high,
            "single": int((red_presses[seeds, first[seeds] - 1] == 1).sum()),
            "first_median": float(np.median(first[learned])),
            "green_probability_then": float(green[seeds, first[seeds] - 1].mean()),
            "green_probability_end": float(green[:, -1].mean())}


PAID_CLAIMS = {
    "red_from_first_red_press": "paid for green, the learner's red error is zero for good "
                                "from the first trial with a press that opened the red box, "
                                "in at least 90% of the seeds that learn red (the lower end "
                                "of the share's 95% interval)",
    "red_press_early": "that trial comes early: its median is within the first 10 trials, "
                       "while the learner still presses green less often than at the end",
}
"""What the chapter says of how the learner paid for green learns red (checked on the
book's run by `paid_claims`, and by the tests on their own seeds)."""


def paid_claims(result):
    """{claim name: whether it holds} for each of `PAID_CLAIMS`, on `result` (the
    learner paid for green)."""
    found = red_from_first_press(result)
    return {"red_from_first_red_press": found["low"] >= 0.9,
            "red_press_early": found["first_median"] <= 10
            and found["green_probability_then"] < found["green_probability_end"]}


STRONG_WORDS = {
    "one press of the red button teaches the predictor what it does in every layout":
        ("tests/test_learners.py::test_action_weight_decides_whether_red_generalises_"
         "across_layouts", "rule"),
    "(an action is a button's place: red's never changes)": (
        "tests/test_envs.py::test_red_never_moves_and_green_is_never_on_red", "rule"),
    "green one on average and first in most seeds": ("red_first_mostly", "majority"),
}
"""The chapter's sentences with a word of strength beside a result, and the checks that
carry them (book/_ext/claim_words.py): {a fragment of the sentence: (claim name, or the
test that checks a rule of the code, kind)}."""
