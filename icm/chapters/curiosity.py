"""The chapter "Which curiosity?" (book/curiosity.ipynb): its claims in words about
the buttons (`SIGNAL_CLAIMS`, checked by `signal_claims` on a
`icm.experiments.curiosity.SignalComparison`), the rods (`REWARD_CLAIMS`, by
`reward_claims` on a `RewardComparison`) and a coin (`COIN_CLAIMS`, by `coin_claims`
on what `icm.experiments.coin_rewards.outcome_rewards` pays), its bold claims with a
word of strength (`BOLD_CLAIMS`), its tables (`signal_table`, `reward_table`), and its
family of paired verdicts (`PAIRED`, `paired_verdicts`, `paired_words`) with their
replication on a fresh root (`replicate`, `run_replications`).
"""

import numpy as np

from icm import _validate, stats
from icm.chapters import replication, verdicts
from icm.chapters.words import percent
from icm.experiments.curiosity import (RewardComparison, SignalComparison,
                                      run_signal_comparison)
from icm.experiments.goal_oriented_results import TASKS
from icm.experiments.rod_toppling import RODS
from icm.experiments.seeding import REPLICATION_ROOTS
from icm.learners import goal_oriented, interest


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
(`signal_claims`)."""


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
(`reward_claims`)."""


VERDICT_CLAIMS = {
    "clear_is_holm": "each paired difference called clear survives Holm's correction for "
                     "the chapter's whole family of paired comparisons at a family-wise 5%",
}
"""The claim behind the chapter's word "clear" (`verdict_claims`)."""


def verdict_claims(paired):
    """Whether the chapter's paired verdicts are Holm's over its whole family: each one
    was corrected in a family of all of them, and each called clear has an adjusted
    p-value within the family-wise rate.

    Args:
      paired: the chapter's verdicts, as `paired_verdicts` gives them ({name: {"clear",
        "p_holm", "n_family", ...}}).

    Returns:
      {"clear_is_holm": bool}.
    """
    if not isinstance(paired, dict):
        raise _validate.ArgumentTypeError(f"paired must be the chapter's verdicts, as "
                                          f"paired_verdicts gives them, got "
                                          f"{_validate.show(paired)}")
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
    if replications is None:
        replications = replication.load_replications().get("curiosity", {})
    return replications.get("verdicts", {})


def paired_claims(comparison, replications=None):
    """{claim name: whether it holds}, for each of `PAIRED_CLAIMS`, from
    `paired_verdicts` and the stored replications (`replications`,
    default those of assets/replications.json for this chapter)."""
    _validate.instance("comparison", comparison, SignalComparison,
                       "a SignalComparison (from icm.experiments.curiosity."
                       "run_signal_comparison)")
    v = paired_verdicts(comparison)["random_vs_progress_green"]
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
    for name, v in paired_verdicts(comparison).items():
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


CHANCE_SHARE = 1.0 / 6.0
"""The share of presses a learner pressing at random gives each of the six buttons."""
TRAPPED_SHARE = 0.5
"""A learner is *trapped* by a source of noise when it spends more than this share of
its presses on the noisy button (of its late episodes at the wobbly rod), the whole
band of that share above it; *not trapped* when the whole band is below it."""
EQUAL_SHARE_TOLERANCE = 0.01
"""How far from chance a button's share of presses may be for the chapter to say that a
learner presses every button equally."""
LEARNED_SHARE = 0.9
"""The share of seeds in which a rod must be predicted well for the chapter to say that
a learner learns it (`REWARD_CLAIMS`): the lower end of the share's 95% interval
(`icm.stats.share_interval`) must be at least this."""
RED_FIRST_SHARE = 0.9
"""The share of seeds in which red must be mastered before green, under each learner,
for the chapter to say that easy comes before hard whatever the signal: the lower end
of the share's 95% interval (`icm.stats.share_interval`) must be at least this."""
TASKS_AND_NOTHING = ("red", "green", "nothing")
"""What a press of the console can do: open the red box, the green box, or nothing."""


def _signals(comparison):
    return _validate.instance("comparison", comparison, SignalComparison,
                              "a SignalComparison (from icm.experiments.curiosity."
                              "run_signal_comparison)")


def _rewards(comparison):
    return _validate.instance("comparison", comparison, RewardComparison,
                              "a RewardComparison (from icm.experiments.curiosity."
                              "run_reward_comparison)")


def signal_claims(comparison):
    """{claim name: whether it holds in `comparison`, a `SignalComparison` of every
    signal, both places of interest and both worlds}, for each of `SIGNAL_CLAIMS`: what
    the chapter states in words, checked on the book's runs when it is built, and by
    the tests on theirs."""
    comparison = _signals(comparison)
    runs = set(comparison.results)
    signals, designs = comparison.settings["signals"], comparison.settings["designs"]
    needed = {(s, d, w) for s in interest.SIGNALS for d in goal_oriented.INTEREST_PER
              for w in (False, True)}
    if not needed <= runs:
        raise ValueError("the chapter's claims need every signal, both places of "
                         "interest and both worlds: run_signal_comparison with its "
                         "default signals, designs and noisy")
    n = comparison.numbers
    plain = [(s, d) for s in signals for d in designs]
    progress, random = n("learning_progress", "task"), n("random", "task")
    balanced = [n("novelty", "task")[f"{t}_presses"][0] for t in TASKS_AND_NOTHING]
    per_region = {s: n(s, "region", True)["noisy_share"] for s in signals}
    return {
        "red_first_share": all(low >= RED_FIRST_SHARE for _, _, low, _
                               in comparison.red_first_intervals().values()),
        "random_not_slower": all(random[f"{t}_mastery"][0] <= progress[f"{t}_mastery"][2]
                                 for t in ("red", "green")),
        "novelty_region_fastest": comparison.fastest() == ("novelty", "region"),
        "novelty_task_balanced": max(balanced) - min(balanced) <= 1,
        "task_not_trapped": all(n(s, "task", True)["noisy_share"][2] < TRAPPED_SHARE
                                for s in signals),
        "region_error_trapped": per_region["prediction_error"][1] > TRAPPED_SHARE,
        "region_progress_drawn_not_trapped":
            per_region["learning_progress"][2] < TRAPPED_SHARE
            and per_region["learning_progress"][1] > CHANCE_SHARE,
        "region_novelty_equal": all(abs(share[0] - CHANCE_SHARE) < EQUAL_SHARE_TOLERANCE
                                    for share in n("novelty", "region", True)
                                    ["button_share"]),
        "noise_delays_green": all(n(*sd, True)["green_mastery"][0]
                                  > n(*sd)["green_mastery"][0] for sd in plain),
    }


def reward_claims(comparison):
    """{claim name: whether it holds in `comparison`, a `RewardComparison` of every
    reward in both worlds}, for each of `REWARD_CLAIMS`: what the chapter states in
    words, checked on the book's runs when it is built, and by the tests on theirs."""
    comparison = _rewards(comparison)
    needed = {(r, w) for r in ("prediction_error", "learning_progress", "novelty",
                               "random") for w in (False, True)}
    if not needed <= set(comparison.results):
        raise ValueError("the chapter's claims need the rewards prediction_error, "
                         "learning_progress, novelty and random in both worlds")
    n = comparison.numbers
    error, progress = n("prediction_error", True), n("learning_progress", True)
    slow = [n(r, True) for r in ("novelty", "random")]
    return {
        "error_trapped": error["wobbly_share_late"][1] > TRAPPED_SHARE
        and error["red_well"][0] < n("prediction_error", False)["red_well"][0],
        "progress_learns_anyway": all(  # each rod's interval's lower end
            stats.share_interval(int((well >= 1).sum()), len(well))[0] >= LEARNED_SHARE
            for well in comparison.results[("learning_progress", True)].predicted_well.T),
        "progress_not_immune": progress["wobbly_share_late"][1] > TRAPPED_SHARE,
        "novelty_random_not_trapped_but_slow": all(
            m["wobbly_share_late"][2] < TRAPPED_SHARE and m["red_well"][0] < 0.5
            for m in slow),
    }


PAIRED = {"novelty_region_vs_random_green": (("novelty", "region"), ("random", "task"),
                                             "green"),
          "random_vs_progress_red": (("random", "task"), ("learning_progress", "task"),
                                     "red"),
          "random_vs_progress_green": (("random", "task"),
                                       ("learning_progress", "task"), "green")}
"""The chapter's paired comparisons of mastery trials in the world without the noisy
button: {name: (arm, baseline, task)}, arm and baseline (signal, interest_per)."""


def paired_family(comparison, names=None):
    """The mastery trials of `PAIRED`'s comparisons (those named in `names`, default
    all) in `comparison` (a `SignalComparison` of the world without the noisy button),
    arm minus baseline on the seeds where both master the task
    (`icm.chapters.verdicts.differences`): {name: per-seed differences}."""
    comparison = _signals(comparison)
    family = {}
    for name in PAIRED if names is None else names:
        arm, baseline, task = PAIRED[_validate.one_of("names[i]", name, tuple(PAIRED))]
        i = TASKS.index(task)
        family[name] = verdicts.differences(
            comparison.results[(*arm, False)].mastery_trial[:, i],
            comparison.results[(*baseline, False)].mastery_trial[:, i], events=True)
    return family


def paired_verdicts(comparison):
    """The chapter's family of paired comparisons (`PAIRED`), decided together
    (`icm.chapters.verdicts.decide`: Holm at a family-wise 5%, sign-flip p-values): for
    each, over the seeds in which both arms master the task (the same seeds), the mean
    difference of the mastery trials (arm minus baseline; negative: the arm masters
    sooner) with its 95% bootstrap band, its p-values, whether it is clear, the seeds
    compared and the family's size. {name: dict}."""
    return verdicts.decide(paired_family(comparison))


def paired_words(comparison, replications=None):
    """The chapter's words for each of `paired_verdicts`: {name: "-1.4 trials (-3.5
    to +0.9): no clear difference"}, "clearly sooner" or "clearly later" for a
    clear one (the arm against the baseline, `icm.chapters.verdicts.phrase`), followed
    by ", not replicated on a fresh root" where the stored replication (`replications`,
    default that of assets/replications.json for this chapter) did not hold it."""
    if replications is None:
        replications = replication.load_replications().get("curiosity", {})
    stored = replications.get("verdicts", {})
    out = {}
    for name, v in paired_verdicts(comparison).items():
        kept = stored.get(name)
        words = verdicts.phrase(v["mean"], v["clear"], "sooner", "later", replication=(
            None if kept is None else verdicts.replication_words(kept, detail=False)))
        out[name] = (f"{v['mean']:+.1f} trials ({v['low']:+.1f} to {v['high']:+.1f}): "
                     f"{words}")
    return out


def signal_table(comparison, noisy_button=False):
    """A Markdown table of `comparison` (a `SignalComparison`), one row per (signal,
    interest_per) of the world with or without the noisy button: mastery trials of red
    and green (mean over the seeds that master, 95% band, share that master), red
    first, presses per task, and the noisy button's share of presses."""
    comparison = _signals(comparison)
    noisy_button = _validate.boolean("noisy_button", noisy_button)
    worlds = sorted({noisy for _, _, noisy in comparison.results})
    if noisy_button not in worlds:
        raise ValueError(f"noisy_button must be one of the worlds this comparison ran "
                         f"({', '.join(map(str, worlds))}), got {noisy_button!r}")
    lines = ["| signal | interest per | red mastered, trial | green mastered, trial "
             "| red first | presses opening red / green / nothing | noisy button, "
             "share of presses |", "|" + "---|" * 7]
    for (signal, per, noisy), result in comparison.results.items():
        if noisy != noisy_button:
            continue
        n = comparison.numbers(signal, per, noisy)
        cells = [signal.replace("_", " "), per]
        for task in TASKS:
            mean, low, high = n[f"{task}_mastery"]
            cells.append(f"{mean:.1f} [{low:.1f}, {high:.1f}] "
                         f"({percent(n[f'{task}_mastered'][0])} of seeds)")
        cells.append(percent(n['red_first']))
        cells.append(" / ".join(f"{n[f'{t}_presses'][0]:.0f}"
                                for t in ("red", "green", "nothing")))
        mean, low, high = n["noisy_share"]
        cells.append("-" if np.isnan(mean) else f"{mean:.3f} [{low:.3f}, {high:.3f}]")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def reward_table(comparison):
    """A Markdown table of `comparison` (a `RewardComparison`), one row per (reward,
    world): the share of episodes ending at each rod over the second half of the runs,
    and how many seeds predict red and blue well (and from which episode: the mean over
    the seeds that get there)."""
    comparison = _rewards(comparison)
    lines = ["| reward | wobbly rod | episodes ending at red / blue / wobbly / none, "
             "second half | red predicted well: seeds (episode) "
             "| blue predicted well: seeds (episode) |", "|" + "---|" * 5]
    for reward, wobbly in comparison.results:
        n = comparison.numbers(reward, wobbly)
        shares = " / ".join(
            f"{n[f'{rod}_share_late'][0]:.2f}" if f"{rod}_share_late" in n else "-"
            for rod in ("red", "blue", "wobbly", "none"))
        cells = [reward.replace("_", " "), "yes" if wobbly else "no", shares]
        for rod in RODS:
            episode = n[f"{rod}_well_episode"][0]
            cells.append(f"{percent(n[f'{rod}_well'][0])} "
                         f"({'-' if np.isnan(episode) else f'{episode:.0f}'})")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


CHAPTER_RUN = {"n_seeds": 100, "n_trials": 100, "seed": 0}
"""The arguments of the chapter's `run_signal_comparison`, whose clear paired verdicts
`run_replications` replicates (the chapter checks that it ran these)."""
REPLICATION_SEEDS = 200
"""Seeds of a replication of a paired verdict (`replicate`). The chapter's one clear
verdict, pressing at random against learning progress in green's mastery trial, is
-2.1 trials with a per-seed spread (standard deviation) of about 7.5 over 100 seeds;
with 200 seeds the standard error is about 0.53, and a one-sided paired test at 5%
detects it with a probability of about 0.99 (normal approximation: z = 2.1 / 0.53 = 4.0
against 1.645). The six runs it needs take well under a CPU-minute."""


def replicate(directions, root=None, n_seeds=REPLICATION_SEEDS):
    """Reruns the paired comparisons of `PAIRED` named in `directions` ({name: "less" or
    "greater", the direction the chapter found}) on the first `n_seeds` seeds of a
    fresh root (default the chapter's of `icm.experiments.seeding.REPLICATION_ROOTS`),
    with the chapter's trials, and tests each in its direction: {name:
    `icm.chapters.replication.replicated` dict}."""
    root = REPLICATION_ROOTS["curiosity"] if root is None else root
    for name in directions:
        _validate.one_of("directions' names", name, tuple(PAIRED))
    fresh = run_signal_comparison(n_seeds=n_seeds, n_trials=CHAPTER_RUN["n_trials"],
                                  signals=("learning_progress", "novelty", "random"),
                                  noisy=(False,), seed=root, progress=False)
    family = paired_family(fresh, list(directions))
    return {name: replication.replicated(family[name], direction)
            for name, direction in directions.items()}


def run_replications():
    """The replications of every paired verdict the chapter's run (`CHAPTER_RUN`) calls
    clear (`replicate`), as assets/replications.json keeps them: {"root", "n_seeds",
    "of": `CHAPTER_RUN`, "verdicts": {name: ...}}."""
    chapter = run_signal_comparison(**CHAPTER_RUN, noisy=(False,), progress=False)
    found = paired_verdicts(chapter)
    directions = {name: "less" if v["mean"] < 0 else "greater"
                  for name, v in found.items() if v["clear"]}
    return {"root": REPLICATION_ROOTS["curiosity"], "n_seeds": REPLICATION_SEEDS,
            "of": CHAPTER_RUN, "verdicts": replicate(directions)}
