"""The chapter "Rod toppling" (book/rod_toppling.ipynb): the claims about Figure 7's
story it states in words (`CLAIMS`, checked on a run by `claims`), the order of one
run's moments in words (`describe_order`), and the claims about the value of an
untried move (`INITIAL_Q_CLAIMS`, checked by `initial_q_claims` on runs at three
initial values), all read from the runs (each a `RodTopplingResult`)."""

from icm import _validate
from icm.chapters.verdicts import differences
from icm.experiments.rod_toppling import RodTopplingResult
from icm.stats import FAMILY_RATE, comes_first, paired_p_value


def _result(result):
    return _validate.instance("result", result, RodTopplingResult,
                              "a RodTopplingResult (from icm.experiments.run_rod_toppling)")


CLAIMS = {
    "red_toppled_first": "the first topple is red's in most seeds, and the median run "
                         "topples red first",
    "red_learned_first": "red is predicted well (on the pairs toppled) before blue in "
                         "most seeds, and sooner at the median",
    "red_learned_first_all": "red is predicted well (on every pair) before blue in most "
                             "seeds, and sooner at the median",
    "then_blue": "blue ends a larger share of the episodes in the second half of "
                 "training than in the first ten",
    "red_in_the_way": "in the second half of training red is toppled more often than blue",
}
"""The claims about Figure 7's story over the seeds that the book states in words
(`claims`)."""


def claims(result):
    """{claim name: whether it holds in `result`, a `RodTopplingResult`}, for each of
    `CLAIMS` (checked on the book's run when it is built, and by the tests on their own
    seeds)."""
    s = _result(result).summary()
    return {
        "red_toppled_first": s["red_toppled_first"] > 0.5
        and s["first_red_median"] < s["first_blue_median"],
        "red_learned_first": s["red_first_toppled"] > 0.5
        and s["red_well_median_toppled"] < s["blue_well_median_toppled"],
        "red_learned_first_all": s["red_first"] > 0.5
        and s["red_well_median"] < s["blue_well_median"],
        "then_blue": s["blue_share_second_half"] > s["blue_share_first_10"],
        "red_in_the_way": s["red_share_second_half"] > s["blue_share_second_half"],
    }


def describe_order(result, run, reading="all"):
    """In words, when red was predicted well (in `reading`) and blue first toppled in
    one run of `result` (a seed index), in the order they came: e.g. "blue is first
    toppled at episode 29, before red is predicted well at episode 43"."""
    result = _result(result)
    run = _validate.integer_in_range("run", run, 0, result.n_seeds - 1)
    red = int(result.well_predicted(reading)[run, 0])
    blue = int(result.first_topple("blue")[run])
    red_text = f"red is predicted well at episode {red}"
    blue_text = f"blue is first toppled at episode {blue}"
    if red < 1 and blue < 1:
        return (f"neither is red predicted well nor blue toppled in "
                f"{result.n_episodes} episodes")
    if red < 1:
        return f"{blue_text}, and red is never predicted well in {result.n_episodes} episodes"
    if blue < 1:
        return f"{red_text}, and blue is never toppled in {result.n_episodes} episodes"
    if red < blue:
        return f"{red_text}, before blue is first toppled, at episode {blue}"
    if blue < red:
        return f"{blue_text}, before {red_text}"
    return f"red is predicted well and blue first toppled in the same episode, {red}"


def initial_q_claims(default, untried_worth_nothing, untried_worth_a_surprise):
    """{claim name: whether it holds}, for each of `INITIAL_Q_CLAIMS`: what the value
    of an untried move does to the story, from runs on the same seeds at the default
    `initial_q`, at a lower one and at a higher one.

    Args:
      default, untried_worth_nothing, untried_worth_a_surprise: each a
        `RodTopplingResult`, the second with a lower `initial_q` than the first, the
        third a higher.

    Raises:
      TypeError: if a run is not a `RodTopplingResult`.
      ValueError: if the runs' initial Q values are not in that order.
    """
    runs = {"default": default, "untried_worth_nothing": untried_worth_nothing,
            "untried_worth_a_surprise": untried_worth_a_surprise}
    for name, run in runs.items():
        _validate.instance(name, run, RodTopplingResult,
                           "a RodTopplingResult (from icm.experiments.run_rod_toppling)")
    values = [run.settings["initial_q"] for run in runs.values()]
    if not values[1] < values[0] < values[2]:
        raise ValueError(f"the runs' initial_q must rise from untried_worth_nothing to "
                         f"default to untried_worth_a_surprise, got {values[1]!r}, "
                         f"{values[0]!r} and {values[2]!r}")
    d, low, high = (run.summary() for run in runs.values())
    # Red first or not, seed by seed, on the seeds the three runs share (the first ones:
    # a run's seeds are those of a longer run with the same root seed, in order).
    shared = min(run.n_seeds for run in runs.values())

    def red_first(run):
        well = run.well_predicted("toppled")[:shared]
        return comes_first(well[:, 0], well[:, 1]).astype(float)

    fewer_red_first = paired_p_value(differences(red_first(untried_worth_a_surprise),
                                                 red_first(default)), alternative="less")
    return {
        "low_stays_with_red": low["red_well_share"] < d["red_well_share"]
        and low["first_blue_median"] > d["first_blue_median"],
        "high_meets_blue_early": high["first_blue_median"] < d["first_blue_median"],
        "high_less_red_first": fewer_red_first < FAMILY_RATE,
    }


INITIAL_Q_CLAIMS = {
    "low_stays_with_red": "with untried moves worth less, red is predicted well on all its "
                          "pairs in fewer seeds and blue is first toppled later",
    "high_meets_blue_early": "with untried moves worth more, blue is first toppled sooner",
    "high_less_red_first": "with untried moves worth more, red comes first in fewer seeds "
                           f"(paired on the seeds the runs share, one-sided at {FAMILY_RATE:.0%})",
}
"""The claims about the value of an untried move that the book states in words
(`initial_q_claims`)."""


_RODS = "tests/test_rod_toppling.py::"

STRONG_WORDS = {
    "guesses, for every (cell, move), whether each rod will fall": (
        _RODS + "test_linear_predictor_table_holds_every_prediction", "rule"),
    "**the value of a move never tried**": (
        _RODS + "test_the_value_of_untried_moves_decides_the_story", "rule"),
    "found in the run's data rather than picked by hand": (
        _RODS + "test_moments_are_found_from_the_data", "rule"),
    "Not every run tells the paper's story": (
        _RODS + "test_the_run_figure7_shows_is_chosen_by_a_rule_and_described_in_its_order",
        "rule"),
    "every topple's error is a factor": (_RODS + "test_linear_predictor_update_by_hand",
                                         "rule"),
    "The seeds move almost in step at first": (
        _RODS + "test_linear_predictor_update_by_hand", "rule"),
    "on every pair it has toppled the rod from so far": (
        _RODS + "test_predicted_well_is_where_the_rod_error_falls_below_a_tenth_for_good",
        "rule"),
    "Read strictly, on every pair that topples the rod": (
        _RODS + "test_issue_claim_red_is_predicted_well_on_every_pair_before_blue", "rule"),
    "on *every* pair that topples the rod in the map": (
        _RODS + "test_predicted_well_is_where_the_rod_error_falls_below_a_tenth_for_good",
        "rule"),
    "since every pair must first be found": (
        _RODS + "test_issue_claim_red_is_predicted_well_on_every_pair_before_blue", "rule"),
    "The robot tries every move early": (
        _RODS + "test_the_value_of_untried_moves_decides_the_story", "rule"),
    "**They end exactly as on the tabular twin**": (
        _RODS + "test_the_physics_run_makes_the_same_episodes_as_the_tabular_twin",
        "exact"),
    "with every topple of the same pair": (_RODS + "test_linear_predictor_update_by_hand",
                                           "rule"),
    "or every pair ({glue:text}`red_first:.0%`)": (
        _RODS + "test_issue_claim_red_is_predicted_well_on_every_pair_before_blue", "rule"),
    "the same seed ends every episode as on the tabular twin": (
        _RODS + "test_the_physics_run_makes_the_same_episodes_as_the_tabular_twin",
        "rule"),
    "(the strict reading, `all`: every pair that topples it)": (
        _RODS + "test_predicted_well_is_where_the_rod_error_falls_below_a_tenth_for_good",
        "rule"),
}
"""The chapter's sentences with a word of strength beside a result, and the checks that
carry them (book/_ext/claim_words.py): {a fragment of the sentence: (a claim the
chapter checks when built, or the test that checks a rule of the code, kind)}."""
