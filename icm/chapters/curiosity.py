"""The chapter "Which curiosity?" (book/curiosity.ipynb): its claims in words about
the buttons (`SIGNAL_CLAIMS`, checked by `icm.experiments.curiosity.SignalComparison.
claims`), the rods (`REWARD_CLAIMS`, by `RewardComparison.claims`) and a coin
(`COIN_CLAIMS`, by `coin_claims` on what `icm.experiments.coin_rewards.outcome_rewards`
pays), and its bold claims with a word of strength (`BOLD_CLAIMS`).
"""

import numpy as np

from icm import _validate, stats
from icm.experiments.curiosity import CHANCE_SHARE, RewardComparison, SignalComparison
from icm.experiments.rod_toppling import RODS


SIGNAL_CLAIMS = {
    "red_first_share": "under each signal and place of interest, pressing at random "
                       "included, red is mastered before green in at least 90% of the seeds "
                       "(the lower end of the share's 95% interval)",
    "random_not_slower": "pressing at random masters red and green no later than learning "
                         "progress (its means within learning progress's bands or below)",
    "novelty_region_fastest": "novelty per region has the lowest mean mastery trial of "
                              "green (the lowest mean only: no comparison is claimed "
                              "clear)",
    "novelty_task_balanced": "novelty per task opens red, green and nothing equally often",
    "task_not_trapped": "with interest per task, no signal is trapped by the noisy button",
    "region_error_trapped": "with interest per region, prediction error is trapped",
    "region_progress_drawn_not_trapped": "with interest per region, learning progress is "
                                         "not trapped, though it presses the noisy button "
                                         "more than chance",
    "region_novelty_equal": "novelty per region spreads its presses evenly: each button's "
                            "mean share is within the tolerance of chance",
    "noise_delays_green": "with the noisy button, green's mean mastery trial is later for "
                          "each of the eight learners (signal and place of interest)",
}
"""The claims of the chapter "Which curiosity?" about the buttons
(`SignalComparison.claims`)."""


REWARD_CLAIMS = {
    "error_trapped": "prediction error is trapped by the wobbly rod, and predicts red well "
                     "in fewer seeds than without it",
    "progress_learns_anyway": "learning progress predicts red and blue well in at least "
                              "90% of the seeds with the wobbly rod (the lower end of "
                              "each share's 95% interval)",
    "progress_not_immune": "learning progress is trapped by the wobbly rod too, in where "
                           "it spends its time: more than half of its late episodes end "
                           "there (the whole 95% band of that share above one half)",
    "novelty_random_not_trapped_but_slow": "novelty and the random walk are not trapped, "
                                           "and neither predicts red well in most seeds",
}
"""The claims of the chapter "Which curiosity?" about the rods
(`RewardComparison.claims`)."""


VERDICT_CLAIMS = {
    "clear_is_holm": "each paired difference called clear survives Holm's correction for "
                     "the chapter's whole family of paired comparisons at a family-wise 5%",
}
"""The claim behind the chapter's word "clear" (`verdict_claims`)."""


def verdict_claims(comparison):
    """Whether the chapter's paired verdicts are Holm's over its whole family: each one
    was corrected in a family of all of them, and each called clear has an adjusted
    p-value within the family-wise rate.

    Args:
      comparison: the chapter's `SignalComparison`.

    Returns:
      {"clear_is_holm": bool}.
    """
    paired = comparison.paired_verdicts()
    return {"clear_is_holm": bool(paired) and all(
        v["n_family"] == len(paired) and (not v["clear"] or v["p_holm"] <= stats.FAMILY_RATE)
        for v in paired.values())}


BOLD_CLAIMS = {
    "Novelty pays the coin exactly what it pays the sure outcome": ("novelty_blind", "exact"),
}
"""The bold claims of the chapter "Which curiosity?" that use a word of strength
("every", "exactly", ...; book/_ext/claim_words.py), each with the claim that checks
it (`COIN_CLAIMS`, `SIGNAL_CLAIMS`) and the kind of that check: "exact" (an array
equality)."""
STRONG_WORDS = {
    'How sure are "red before green" and "a clear difference"?': ("clear_is_holm",
                                                                   "corrected"),
    "Each clear one is rerun on a fresh": ("clear_is_holm", "corrected"),
    "the likelier one of them looks clear by luck": ("clear_is_holm", "corrected"),
    # Every sentence that quotes a glued paired verdict ("clearly sooner", "no clear
    # difference") quotes Holm's.
    "{glue:text}`paired_": ("clear_is_holm", "corrected"),
    "a difference is called clear only if it survives it": ("clear_is_holm", "corrected"),
}
"""The chapter's sentences with a word of strength beside a result, other than the bold
claims, and the check that carries each (book/_ext/claim_words.py): the definition of
"clear" in the fold on how sure its verdicts are."""


COIN_CLAIMS = {
    "error_pays_the_coin": "prediction error keeps paying for a coin and all but stops "
                           "paying for a sure outcome (less than a hundredth of the coin's)",
    "progress_pays_little": "learning progress pays a coin more than zero, and less than "
                            "prediction error pays it",
    "novelty_blind": "novelty pays a coin exactly what it pays a sure outcome",
}
"""The claims of the chapter "Which curiosity?" about what each reward pays for a coin
(`coin_claims`)."""


def late_tries(paid):
    """The slice of the later half of the tries of `outcome_rewards`' result (the
    tries the chapter averages over)."""
    n_tries = next(iter(paid.values())).shape[1]
    return slice(n_tries // 2, None)


def coin_claims(paid):
    """{claim name: whether it holds}, for each of `COIN_CLAIMS`, from what
    `outcome_rewards` returned (with the rewards prediction_error, learning_progress
    and novelty), over the later half of the tries (`late_tries`)."""
    if not isinstance(paid, dict) or not {(r, k) for r in ("prediction_error",
                                                          "learning_progress", "novelty")
                                          for k in ("coin", "sure")} <= set(paid):
        raise _validate.ArgumentTypeError(
            f"paid must be what outcome_rewards returns for prediction_error, "
            f"learning_progress and novelty, got {_validate.show(paid)}")
    late = late_tries(paid)
    mean = {key: float(values[:, late].mean()) for key, values in paid.items()}
    return {
        "error_pays_the_coin": mean[("prediction_error", "sure")]
        < mean[("prediction_error", "coin")] / 100,
        "progress_pays_little": 0 < mean[("learning_progress", "coin")]
        < mean[("prediction_error", "coin")],
        "novelty_blind": bool(np.array_equal(paid[("novelty", "coin")],
                                             paid[("novelty", "sure")])),
    }


def red_first_parts(comparison):
    """How often red is mastered before green in the world without the noisy button,
    from `SignalComparison.red_first_intervals`, in two parts the chapter quotes apart:
    (the weakest learner's count, e.g. "in 100 of the 100 seeds", and the lowest lower
    end of the learners' 95% intervals, e.g. "96.3%"). The share is rounded down to one
    decimal, so that the sentence stays true (and a bound below 1 never reads as
    100.0%).

    Args:
      comparison: a `SignalComparison`.

    Raises:
      ValueError: for a comparison without the world without the noisy button.
    """
    _validate.instance("comparison", comparison, SignalComparison,
                       "a SignalComparison (from icm.experiments.curiosity."
                       "run_signal_comparison)")
    intervals = comparison.red_first_intervals()
    if not intervals:
        raise ValueError("comparison must hold runs without the noisy button "
                         "(noisy=(False, ...))")
    fewest = min(count for count, _, _, _ in intervals.values())
    n = min(n for _, n, _, _ in intervals.values())
    low = min(low for _, _, low, _ in intervals.values())
    shown = np.floor(1000 * low + 1e-9) / 10
    count = f"{fewest} of the {n}" if fewest == n else f"at least {fewest} of the {n}"
    return f"in {count} seeds", f"{shown:.1f}%"


def red_first_words(comparison):
    """The chapter's words for how often red is mastered before green in the world
    without the noisy button (`red_first_parts` in one phrase), e.g. "in 100 of the
    100 seeds: in at least 96.3% of seeds (the lower end of a 95% interval)" (the
    sentence around it says "under each learner").

    Args:
      comparison: a `SignalComparison`.
    """
    count, bound = red_first_parts(comparison)
    return (f"{count}: in at least {bound} of seeds (the lower end of a "
            f"{stats.LEVEL:.0%} interval)")


PAIRED_CLAIMS = {
    "random_sooner_on_green": "seed by seed, pressing at random masters green sooner than "
                              "learning progress: the paired difference is negative, clear "
                              "after Holm's correction over the chapter's family, and not "
                              "contradicted by its replication on a fresh root",
}
"""The claim behind the chapter's words "on green, pressing at random is faster than
learning progress" (`paired_claims`)."""


def _stored_verdicts(replications):
    """The stored replications of the chapter's paired verdicts ({name: dict})."""
    from icm.experiments import replication

    if replications is None:
        replications = replication.load_replications().get("curiosity", {})
    return replications.get("verdicts", {})


def paired_claims(comparison, replications=None):
    """{claim name: whether it holds}, for each of `PAIRED_CLAIMS`, from
    `SignalComparison.paired_verdicts` and the stored replications (`replications`,
    default those of assets/replications.json for this chapter)."""
    _validate.instance("comparison", comparison, SignalComparison,
                       "a SignalComparison (from icm.experiments.curiosity."
                       "run_signal_comparison)")
    v = comparison.paired_verdicts()["random_vs_progress_green"]
    stored = _stored_verdicts(replications).get("random_vs_progress_green", {})
    return {"random_sooner_on_green": bool(v["clear"] and v["mean"] < 0
                                           and stored.get("replicated") is not False)}


NOISY_TASK_CLAIMS = {
    "error_task_above_chance": "with interest per task, prediction error spends a little "
                               "more of its presses on the noisy button than chance (the "
                               "whole 95% band of its share above 1/6)",
    "novelty_task_below_chance": "with interest per task, novelty spends less of its presses "
                                 "on the noisy button than chance (the whole 95% band of its "
                                 "share below 1/6)",
}
"""The claims behind the chapter's words "though prediction error's share sits a little
above chance and novelty's below" (`noisy_task_claims`)."""


def noisy_task_claims(comparison):
    """{claim name: whether it holds}, for each of `NOISY_TASK_CLAIMS`, from the runs
    with the noisy button and interest per task of a `SignalComparison`."""
    _validate.instance("comparison", comparison, SignalComparison,
                       "a SignalComparison (from icm.experiments.curiosity."
                       "run_signal_comparison)")
    error = comparison.numbers("prediction_error", "task", True)["noisy_share"]
    novelty = comparison.numbers("novelty", "task", True)["noisy_share"]
    return {"error_task_above_chance": error[1] > CHANCE_SHARE,
            "novelty_task_below_chance": novelty[2] < CHANCE_SHARE}


def gap_words(mean, low, high):
    """A paired difference of mastery trials (arm minus baseline, negative: the arm
    masters sooner) with its band, in plain words: ("2.1 trials sooner", "0.7 to 3.7
    trials sooner"); a band that holds zero reads "from 3.5 trials sooner to 0.9
    later", and a gap that rounds to 0.0 reads "less than 0.1 trials later" (a student
    read "0.0 trials later" as a typo)."""
    direction = "sooner" if mean < 0 else "later"
    gap = f"{abs(mean):.1f} trials {direction}"
    if gap.startswith("0.0 "):
        gap = f"less than 0.1 trials {direction}"
    if high < 0:
        band = f"{-high:.1f} to {-low:.1f} trials sooner"
    elif low > 0:
        band = f"{low:.1f} to {high:.1f} trials later"
    else:
        band = f"from {-low:.1f} trials sooner to {high:.1f} later"
    return gap, band


def paired_plain_words(comparison, replications=None):
    """The chapter's words for each of `SignalComparison.paired_verdicts`, in two parts
    a sentence puts around its two learners: {name: (gap, detail)}, e.g. ("2.1 trials
    sooner", "95% band 0.7 to 3.7 trials sooner: a clear difference"). The verdict is
    "a clear difference" (Holm's, `paired_verdicts`) or "no clear difference", followed
    by ", not replicated on a fresh root" where the stored replication (`replications`,
    default that of assets/replications.json for this chapter) did not hold it."""
    _validate.instance("comparison", comparison, SignalComparison,
                       "a SignalComparison (from icm.experiments.curiosity."
                       "run_signal_comparison)")
    stored = _stored_verdicts(replications)
    out = {}
    for name, v in comparison.paired_verdicts().items():
        gap, band = gap_words(v["mean"], v["low"], v["high"])
        verdict = "a clear difference" if v["clear"] else "no clear difference"
        if v["clear"] and stored.get(name, {}).get("replicated") is False:
            verdict += ", not replicated on a fresh root"
        out[name] = (gap, f"{stats.BAND_LEVEL:.0%} band {band}: {verdict}")
    return out


def red_box_openings(comparison, signal, interest_per="task"):
    """Where one learner's openings of the red box come from, with the noisy button:
    (presses of the red button per run, red boxes opened by the noisy button per run),
    means over the seeds. The red button is lit red in every layout, so each of its
    presses opens the red box, and every other opening is the noisy button's.

    Args:
      comparison: a `SignalComparison` with runs with the noisy button.
      signal: the learner's signal; interest_per: "task" or "region".
    """
    _validate.instance("comparison", comparison, SignalComparison,
                       "a SignalComparison (from icm.experiments.curiosity."
                       "run_signal_comparison)")
    comparison.numbers(signal, interest_per, True)  # checks the key
    result = comparison.results[(signal, interest_per, True)]
    presses = result.button_share[:, :, result.settings["red_button"]].sum(axis=1) \
        * result.settings["presses_per_trial"]
    opened = result.practice[:, :, 0].sum(axis=1)  # TASKS: red first
    return float(np.rint(presses).mean()), float((opened - np.rint(presses)).mean())


def noise_delays(comparison):
    """The learners (signal, interest_per), among those a `SignalComparison` ran in both
    worlds, whose mean mastery trial of green (over the seeds that master it) is later
    with the noisy button than without: a list, in the comparison's order (the claim
    "noise_delays_green" asks for all of them)."""
    _validate.instance("comparison", comparison, SignalComparison,
                       "a SignalComparison (from icm.experiments.curiosity."
                       "run_signal_comparison)")
    both = [(s, d) for (s, d, noisy) in comparison.results
            if not noisy and (s, d, True) in comparison.results]
    return [(s, d) for s, d in both
            if comparison.numbers(s, d, True)["green_mastery"][0]
            > comparison.numbers(s, d)["green_mastery"][0]]


def well_intervals(comparison, reward, wobbly_rod=False):
    """For one run of a `RewardComparison`, per rod of
    `icm.experiments.rod_toppling.RODS`: (seeds in which the rod comes to be predicted
    well, seeds, and the 95% interval of that share, `icm.stats.share_interval`), as
    {rod: (count, n, low, high)}."""
    _validate.instance("comparison", comparison, RewardComparison,
                       "a RewardComparison (from icm.experiments.curiosity."
                       "run_reward_comparison)")
    comparison.numbers(reward, wobbly_rod)  # checks the key
    well = comparison.results[(reward, wobbly_rod)].predicted_well
    out = {}
    for i, rod in enumerate(RODS):
        count, n = int((well[:, i] >= 1).sum()), well.shape[0]
        out[rod] = (count, n, *stats.share_interval(count, n))
    return out
