"""The chapter "Goal-oriented interest" (book/goal_oriented_interest.ipynb): the
claims of the paper about Figure 5 it states in words (`CLAIMS`) and their check on a
run (`claims`, on the chapter's run when it is built and on the tests' own seeds), the
clause it quotes about the curves' peaks (`describe_peaks`), and its table of runs
(`comparison_table`), all read from a `GoalOrientedResult`."""

from icm import _validate
from icm.chapters.words import measures_table, percent
from icm.experiments.goal_oriented_results import GoalOrientedResult
from icm.experiments.results import check_results


CLAIMS = {
    "red_first_mostly": "red is mastered first in most seeds",
    "red_sooner": "red is mastered sooner than green on average",
    "red_fades_first": "the mean interest in red fades before the interest in green",
    "green_stays_longer": "the interest in green is spent later than the interest in red",
}
"""The claims of the paper about Figure 5 that the book states (`claims`)."""


def _result(result):
    return _validate.instance("result", result, GoalOrientedResult,
                              "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")


def claims(result):
    """{claim name: whether it holds in `result`, a `GoalOrientedResult`}, for each of
    `CLAIMS`: what the chapter states in words, checked on the book's run when it is
    built (and by the tests on their own seeds)."""
    s = _result(result).summary()
    return {
        "red_first_mostly": s["red_first"] > 0.5,
        "red_sooner": s["red_mastery_mean"] < s["green_mastery_mean"],
        "red_fades_first": 0 < s["red_fade_trial"] < s["green_fade_trial"]
        or (s["red_fade_trial"] > 0 > s["green_fade_trial"]),
        "green_stays_longer": s["green_interest_centre"] > s["red_interest_centre"],
    }


def describe_peaks(result):
    """In words, whether the mean interest in green peaks after the mean interest in red
    in `result` (a `GoalOrientedResult`), as the paper's "interest rise slower" would
    have it: a clause that the chapter quotes, phrased from the data."""
    result = _result(result)
    red, green = result.peak_trial("red"), result.peak_trial("green")
    if green > red:
        return (f"the mean curves agree, green's peaking at trial {green}, after red's "
                f"at trial {red}")
    if green == red:
        return f"the mean curves do not show it: both peak at trial {red}"
    return (f"the mean curves show the opposite, green's peaking at trial {green}, "
            f"before red's at trial {red}")


def comparison_table(results):
    """A Markdown table of the numbers that tell runs apart, one column per run.

    Args:
      results: a dict {column label: GoalOrientedResult}.

    Returns:
      A Markdown string (display it with `IPython.display.Markdown`).
    """
    check_results("results", results, GoalOrientedResult)
    summaries = {id(r): r.summary() for r in results.values()}

    def pair(key, fmt):
        return lambda r: (f"{summaries[id(r)]['red_' + key]:{fmt}} / "
                          f"{summaries[id(r)]['green_' + key]:{fmt}}")

    return measures_table(results, [
        ("seeds", lambda r: str(r.n_seeds)),
        ("mastered, mean trial: red / green", pair("mastery_mean", ".1f")),
        ("red mastered first", lambda r: percent(summaries[id(r)]['red_first'])),
        ("peak interest: red / green", pair("peak_interest", ".3f")),
        ("centre of interest, trial: red / green", pair("interest_centre", ".1f")),
        ("interest below 10% of its peak from trial: red / green", pair("fade_trial", "")),
        ("most practised at trial: red / green", pair("practice_peak_trial", "")),
    ])

_LEARNERS = "tests/test_learners.py::"
_GOAL = "tests/test_goal_oriented.py::"

STRONG_WORDS = {
    "a task is most interesting just after the robot starts getting it right": (
        _LEARNERS + "test_progress_after_one_surprise_then_correct_predictions", "rule"),
    "Green, the most interesting task, is expected from button": (
        _LEARNERS + "test_greedy_agent_presses_the_button_whose_predicted_task_is_most_"
                    "interesting", "rule"),
    "The unlit ones were never pressed, so every press the predictor remembers": (
        _LEARNERS + "test_ties_go_to_the_most_recent_experience", "rule"),
    "buttons then aim at red, the most interesting task": (
        _LEARNERS + "test_ties_are_broken_at_random_and_epsilon_one_is_uniform", "rule"),
    "confidence band around every mean": (
        "tests/test_stats.py::test_the_bootstrap_band_is_95_percent_by_default",
        "rule"),
    "presses (every button, every layout) and stays right": (
        "tests/test_experiments.py::test_mastery_trial_is_where_the_error_reaches_zero_"
        "for_good", "rule"),
    "Each sentence in bold is tested on this run whenever the page is built": (
        "red_first_mostly", "majority"),
    "\"no green\" for every unlit button included": (
        "tests/test_experiments.py::test_mastery_trial_is_where_the_error_reaches_zero_"
        "for_good", "rule"),
    "which records every press of the run above": (
        _LEARNERS + "test_agent_turns_predictions_into_tasks_and_scores_errors", "rule"),
    "one red press teaches \"button": (
        _LEARNERS + "test_action_weight_decides_whether_red_generalises_across_layouts",
        "rule"),
    "read as printed, it opens red at most": (
        "tests/test_experiments.py::test_read_as_printed_green_is_mastered_sooner_and_"
        "red_practised_less", "rule"),
    "the buttons mostly tie at zero": (
        "tests/test_experiments.py::test_the_literal_reading_has_almost_no_interest_in_red",
        "rule"),
    "of equally near presses, the predictor takes the most recent": (
        _LEARNERS + "test_ties_go_to_the_most_recent_experience", "rule"),
    "most of all just after the first right guesses": (
        _LEARNERS + "test_progress_after_one_surprise_then_correct_predictions", "rule"),
    "but opens red at most": (
        "tests/test_experiments.py::test_read_as_printed_green_is_mastered_sooner_and_"
        "red_practised_less", "rule"),
    "Red is easy because the predictor looks for the same button first": (
        "plain_red_first_less", "causal"),
}
"""The chapter's sentences with a word of strength beside a result, and the checks that
carry them (book/_ext/claim_words.py): {a fragment of the sentence: (a claim the
chapter checks when built, or the test that checks a rule of the code, kind)}. "Red is
easy because ..." is causal: the chapter removes the cause (a plain Hamming distance)
and checks that red's lead goes with it."""
