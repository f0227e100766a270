"""Which curiosity? The interest signals compared on the same tasks, with and without a
noisy world (the chapter "Which curiosity?").

`run_signal_comparison` runs the goal-oriented learner on the buttons once per signal
(`icm.learners.interest.SIGNALS`), place of interest (`interest_per`, "task" or
"region") and world (with or without the noisy button), all on the same seeds;
`run_reward_comparison` runs the Q-learner on the rods once per intrinsic reward
(`icm.learners.q_learning.REWARDS`), with and without the wobbly rod. Both return the
runs and the numbers the chapter quotes, each a mean over seeds with its 95%
percentile-bootstrap band. What each reward pays for a coin is
`icm.experiments.coin_rewards`; the chapter's claims in words and their checks are
`icm.chapters.curiosity`.
"""

import dataclasses
import itertools

import numpy as np

from icm import _streams, _validate
from icm.experiments import goal_oriented as _goal_oriented
from icm.experiments.goal_oriented_results import TASKS, GoalOrientedResult
from icm.experiments import rod_toppling as _rod_toppling
from icm.experiments._memory import FIXED_BYTES, check_memory
from icm.experiments._progress import progress_bar
from icm.experiments.results import percent
from icm.learners import goal_oriented, interest, predictors, q_learning
from icm.stats import (bootstrap_band, comes_first, corrected_verdicts, paired_gaps,
                       share_interval)

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


def _band(values):
    """(mean, low, high) of a 1-d array of per-seed values, floats (NaN if empty)."""
    return _bands({"x": values})["x"]


def _bands(columns):
    """{name: (mean, low, high)} for per-seed values {name: [seed]} (all over the same
    seeds: one bootstrap for all of them), NaN for an empty column."""
    names = [name for name, v in columns.items() if np.size(v)]
    out = {name: (float("nan"),) * 3 for name in columns}
    if names:
        stacked = np.stack([np.asarray(columns[name], dtype=float) for name in names], axis=1)
        mean, low, high = bootstrap_band(stacked)
        for i, name in enumerate(names):
            out[name] = (float(mean[i]), float(low[i]), float(high[i]))
    return out


def _runs_memory(needs):
    """An upper bound on the memory of runs made one after the other, all of whose
    results are kept, from each run's (peak, kept) bound: every result, and twice the
    largest run's working memory besides its result. Twice: the allocator keeps some
    of a run's freed memory for the next (glibc's heap, between the kept results and
    at its top; measured: 400 seeds x 200 trials, 16 runs, 196 MB allocated at most,
    220 MB resident)."""
    return sum(kept for _, kept in needs) + 2 * max(peak - kept for peak, kept in needs)


def check_choices(name, values, allowed):
    """`values` as a tuple of distinct members of `allowed`, else raises."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise _validate.ArgumentTypeError(f"{name} must be a sequence of {allowed}, got "
                                          f"{_validate.show(values)}")
    values = tuple(_validate.one_of(f"{name}[i]", v, allowed) for v in values)
    if not values or len(set(values)) != len(values):
        raise ValueError(f"{name} must list distinct values of {allowed}, at least one, "
                         f"got {values!r}")
    return values


def button_numbers(result):
    """The numbers that compare goal-oriented runs, from one `GoalOrientedResult`, each
    a (mean, low, high) over the seeds unless said otherwise:

    - "red_mastery", "green_mastery": the mastery trial, over the seeds that master
      the task; "red_mastered", "green_mastered": the share of seeds that do;
    - "red_first": the share of seeds that master red strictly before green (a plain
      number);
    - "red_presses", "green_presses", "nothing_presses": presses per run that opened
      the red box, the green box, or nothing (3 presses a trial);
    - "button_share": the share of all presses on each button, a list of
      (mean, low, high), one per button;
    - "noisy_share": the share on the noisy button (NaN without it).
    """
    _validate.instance("result", result, GoalOrientedResult,
                       "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    out, per_seed = {}, {}
    for i, task in enumerate(TASKS):
        trials = result.mastery_trial[:, i]
        out[f"{task}_mastery"] = _band(trials[trials >= 1])
        per_seed[f"{task}_mastered"] = (trials >= 1).astype(float)
        per_seed[f"{task}_presses"] = result.practice[:, :, i].sum(axis=1)
    total = result.settings["presses_per_trial"] * result.n_trials
    per_seed["nothing_presses"] = total - result.practice.sum(axis=(1, 2))
    shares = result.button_share.mean(axis=1)  # [seed, button]
    for b in range(shares.shape[1]):
        per_seed[b] = shares[:, b]
    bands = _bands(per_seed)
    out.update({name: band for name, band in bands.items() if isinstance(name, str)})
    out["red_first"] = result.red_first_fraction()
    out["button_share"] = [bands[b] for b in range(shares.shape[1])]
    out["noisy_share"] = out["button_share"][5] if shares.shape[1] > 5 else \
        (float("nan"),) * 3
    return out


TASKS_AND_NOTHING = ("red", "green", "nothing")
"""What a press of the console can do: open the red box, the green box, or nothing."""


def _comparison_key(results, names, key):
    """`key` if it is a key of `results` (a tuple of strings and bools), else raises:
    an ArgumentTypeError for a part that is not a string or bool (a list, say), a
    ValueError listing the keys for one that names no run."""
    for part in key:
        if not isinstance(part, (str, bool, np.bool_)):
            raise _validate.ArgumentTypeError(f"{names} must be strings and booleans, got "
                                              f"{_validate.show(key)}")
    if key not in results:
        raise ValueError(f"{names} must be one of {sorted(results)}, got {key!r}")
    return key


@dataclasses.dataclass(frozen=True)
class SignalComparison:
    """What `run_signal_comparison` measured.

    Attributes:
      settings: the arguments of the comparison, as a dict.
      results: {(signal, interest_per, noisy_button): GoalOrientedResult}, every run
        on the same seeds.
    """

    settings: dict
    results: dict
    _numbers: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)

    def numbers(self, signal, interest_per="task", noisy_button=False):
        """`button_numbers` of one run of the comparison (computed once)."""
        key = _comparison_key(self.results, "(signal, interest_per, noisy_button)",
                              (signal, interest_per, noisy_button))
        if key not in self._numbers:
            self._numbers[key] = button_numbers(self.results[key])
        return self._numbers[key]

    def summary(self):
        """The numbers the chapter quotes, as a flat dict: keys
        "<signal>_<interest_per>_<plain|noisy>_<quantity>" with quantity red_mastery,
        green_mastery (means over the seeds that master), red_mastered,
        green_mastered, red_first, red_presses, green_presses, noisy_share, and the
        95% band of the shares and mastery trials as ..._low and ..._high."""
        out = {}
        for (signal, per, noisy), result in self.results.items():
            prefix = f"{signal}_{per}_{'noisy' if noisy else 'plain'}_"
            numbers = self.numbers(signal, per, noisy)
            for name in ("red_mastery", "green_mastery", "red_mastered", "green_mastered",
                         "red_presses", "green_presses", "noisy_share"):
                mean, low, high = numbers[name]
                out[prefix + name] = mean
                out[prefix + name + "_low"] = low
                out[prefix + name + "_high"] = high
            out[prefix + "red_first"] = numbers["red_first"]
        return out

    def claims(self):
        """{claim name: whether it holds in this comparison}, for each of
        `SIGNAL_CLAIMS` (a comparison of every signal, both places of interest and
        both worlds): what the chapter states in words, checked on the book's runs
        when it is built, and by the tests on theirs."""
        runs = set(self.results)
        signals, designs = self.settings["signals"], self.settings["designs"]
        needed = {(s, d, w) for s in interest.SIGNALS for d in goal_oriented.INTEREST_PER
                  for w in (False, True)}
        if not needed <= runs:
            raise ValueError("the chapter's claims need every signal, both places of "
                             "interest and both worlds: run_signal_comparison with its "
                             "default signals, designs and noisy")
        n = self.numbers
        plain = [(s, d) for s in signals for d in designs]
        progress, random = n("learning_progress", "task"), n("random", "task")
        balanced = [n("novelty", "task")[f"{t}_presses"][0] for t in TASKS_AND_NOTHING]
        per_region = {s: n(s, "region", True)["noisy_share"] for s in signals}
        return {
            "red_first_share": all(low >= RED_FIRST_SHARE
                                   for _, _, low, _ in self.red_first_intervals().values()),
            "random_not_slower": all(random[f"{t}_mastery"][0] <= progress[f"{t}_mastery"][2]
                                     for t in ("red", "green")),
            "novelty_region_fastest": self.fastest() == ("novelty", "region"),
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

    def red_first_intervals(self):
        """For each learner (signal, place of interest) of the world without the noisy
        button: (seeds in which red is mastered strictly before green, seeds, and the
        95% interval of that share, `icm.stats.share_interval`), as
        {(signal, interest_per): (count, n, low, high)}."""
        out = {}
        for (signal, per, noisy), result in self.results.items():
            if noisy:
                continue
            red, green = result.mastery_trial[:, 0], result.mastery_trial[:, 1]
            count, n = int(comes_first(red, green).sum()), len(red)
            out[(signal, per)] = (count, n, *share_interval(count, n))
        return out

    PAIRED = {"novelty_region_vs_random_green": (("novelty", "region"), ("random", "task"),
                                                 "green"),
              "random_vs_progress_red": (("random", "task"), ("learning_progress", "task"),
                                         "red"),
              "random_vs_progress_green": (("random", "task"),
                                           ("learning_progress", "task"), "green")}
    """The chapter's paired comparisons of mastery trials in the world without the noisy
    button: {name: (arm, baseline, task)}, arm and baseline (signal, interest_per)."""

    def paired_verdicts(self):
        """The chapter's family of paired comparisons (`PAIRED`), corrected together
        (`icm.stats.corrected_verdicts`: Holm at a family-wise 5%, sign-flip p-values):
        for each, over the seeds in which both arms master the task (the same seeds),
        the mean difference of the mastery trials (arm minus baseline; negative:
        the arm masters sooner) with its 95% bootstrap band, its p-values, whether it
        is clear, the seeds compared and the family's size. {name: dict}."""
        family, bands, counts = {}, {}, {}
        for name, (arm, baseline, task) in self.PAIRED.items():
            i = TASKS.index(task)
            a = self.results[(*arm, False)].mastery_trial[:, i]
            b = self.results[(*baseline, False)].mastery_trial[:, i]
            family[name] = paired_gaps(a, b)
            bands[name], counts[name] = _band(family[name]), len(family[name])
        corrected = corrected_verdicts(family)
        return {name: {"mean": bands[name][0], "low": bands[name][1],
                       "high": bands[name][2], "p": v["p"], "p_holm": v["p_holm"],
                       "clear": v["clear"], "n_seeds": counts[name],
                       "n_family": v["n_family"]}
                for name, v in corrected.items()}

    def paired_words(self, replications=None):
        """The chapter's words for each of `paired_verdicts`: {name: "-1.4 trials (-3.5
        to +0.9): no clear difference"}, "clearly sooner" or "clearly later" for a
        clear one (the arm against the baseline), followed by ", not replicated on a
        fresh root" where the stored replication (`replications`, default that of
        assets/replications.json for this chapter) did not hold it."""
        from icm.experiments import replication

        if replications is None:
            replications = replication.load_replications().get("curiosity", {})
        stored = replications.get("verdicts", {})
        out = {}
        for name, v in self.paired_verdicts().items():
            words = "no clear difference"
            if v["clear"]:
                words = "clearly sooner" if v["mean"] < 0 else "clearly later"
                if stored.get(name, {}).get("replicated") is False:
                    words += ", not replicated on a fresh root"
            out[name] = (f"{v['mean']:+.1f} trials ({v['low']:+.1f} to {v['high']:+.1f}): "
                         f"{words}")
        return out

    def fastest(self):
        """(signal, interest_per) of the world without the noisy button that masters
        green the soonest (the lowest mean mastery trial)."""
        plain = [(s, d) for (s, d, noisy) in self.results if not noisy]
        return min(plain, key=lambda sd: self.numbers(*sd)["green_mastery"][0])

    def seed_summaries(self):
        """One dict per seed: each run's mastery trials (-1 if never) and, with the
        noisy button, its share of presses, keyed like `summary`."""
        rows = [dict() for _ in range(self.settings["n_seeds"])]
        for (signal, per, noisy), result in self.results.items():
            prefix = f"{signal}_{per}_{'noisy' if noisy else 'plain'}_"
            shares = result.button_share.mean(axis=1)
            for k, row in enumerate(rows):
                row[prefix + "red_mastery_trial"] = int(result.mastery_trial[k, 0])
                row[prefix + "green_mastery_trial"] = int(result.mastery_trial[k, 1])
                if noisy:
                    row[prefix + "noisy_share"] = float(shares[k, 5])
        return rows

    def table(self, noisy_button=False):
        """A Markdown table, one row per (signal, interest_per) of the world with or
        without the noisy button: mastery trials of red and green (mean over the seeds
        that master, 95% band, share that master), red first, presses per task, and
        the noisy button's share of presses."""
        noisy_button = _validate.boolean("noisy_button", noisy_button)
        worlds = sorted({noisy for _, _, noisy in self.results})
        if noisy_button not in worlds:
            raise ValueError(f"noisy_button must be one of the worlds this comparison ran "
                             f"({', '.join(map(str, worlds))}), got {noisy_button!r}")
        lines = ["| signal | interest per | red mastered, trial | green mastered, trial "
                 "| red first | presses opening red / green / nothing | noisy button, "
                 "share of presses |", "|" + "---|" * 7]
        for (signal, per, noisy), result in self.results.items():
            if noisy != noisy_button:
                continue
            n = self.numbers(signal, per, noisy)
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
    """Reruns the paired comparisons of `SignalComparison.PAIRED` named in `directions`
    ({name: "less" or "greater", the direction the chapter found}) on the first
    `n_seeds` seeds of a fresh root (default the chapter's of
    `replication.REPLICATION_ROOTS`), with the chapter's trials, and tests each in its
    direction: {name: `replication.replicated` dict}."""
    from icm.experiments import replication

    root = replication.REPLICATION_ROOTS["curiosity"] if root is None else root
    for name in directions:
        _validate.one_of("directions' names", name, tuple(SignalComparison.PAIRED))
    fresh = run_signal_comparison(n_seeds=n_seeds, n_trials=CHAPTER_RUN["n_trials"],
                                  signals=("learning_progress", "novelty", "random"),
                                  noisy=(False,), seed=root, progress=False)
    out = {}
    for name, direction in directions.items():
        arm, baseline, task = SignalComparison.PAIRED[name]
        i = TASKS.index(task)
        a = fresh.results[(*arm, False)].mastery_trial[:, i]
        b = fresh.results[(*baseline, False)].mastery_trial[:, i]
        out[name] = replication.replicated(paired_gaps(a, b), direction)
    return out


def run_replications():
    """The replications of every paired verdict the chapter's run (`CHAPTER_RUN`) calls
    clear (`replicate`), as assets/replications.json keeps them: {"root", "n_seeds",
    "of": `CHAPTER_RUN`, "verdicts": {name: ...}}."""
    from icm.experiments import replication

    chapter = run_signal_comparison(**CHAPTER_RUN, noisy=(False,), progress=False)
    found = chapter.paired_verdicts()
    directions = {name: "less" if v["mean"] < 0 else "greater"
                  for name, v in found.items() if v["clear"]}
    return {"root": replication.REPLICATION_ROOTS["curiosity"], "n_seeds": REPLICATION_SEEDS,
            "of": CHAPTER_RUN, "verdicts": replicate(directions)}


def run_signal_comparison(n_seeds=100, n_trials=100, signals=interest.SIGNALS,
                          designs=goal_oriented.INTEREST_PER, noisy=(False, True), seed=0,
                          progress=True):
    """Runs the goal-oriented learner on the buttons once per signal, place of interest
    and world, all on the same seeds (`run_goal_oriented`, its other settings at their
    defaults).

    Args:
      n_seeds: runs per setting (>= 1).
      n_trials: trials per run (>= 1).
      signals: the interest signals to compare (default all of `SIGNALS`).
      designs: where interest lives, "task" and/or "region" (default both).
      noisy: the worlds: False (five buttons), True (with the noisy button).
      seed: the root seed (see `run_goal_oriented`), the same for every setting.
      progress: a progress bar over the settings.

    Returns:
      A `SignalComparison`.

    Raises:
      ValueError: for a bad count, an unknown signal or design, a repeated one, or
        runs whose results this machine's memory could not hold.
    """
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    signals = check_choices("signals", signals, interest.SIGNALS)
    designs = check_choices("designs", designs, goal_oriented.INTEREST_PER)
    noisy = check_choices("noisy", noisy, (False, True))
    seed = _validate.root_seed("seed", seed)
    _validate.boolean("progress", progress)
    grid = list(itertools.product(signals, designs, noisy))
    check_memory("run_signal_comparison", {"runs": len(grid), "n_seeds": n_seeds,
                                           "n_trials": n_trials},
                 _runs_memory([_goal_oriented.memory_needed(
                     n_seeds, n_trials, interest_per=per, noisy_button=noisy_button)
                     for _, per, noisy_button in grid]))
    results = {}
    for signal, per, noisy_button in progress_bar(grid, len(grid), "interest signals",
                                                  progress, unit="run"):
        results[(signal, per, noisy_button)] = _goal_oriented.run_goal_oriented(
            n_seeds=n_seeds, n_trials=n_trials, interest=signal, interest_per=per,
            noisy_button=noisy_button, seed=seed, progress=False)
    settings = dict(n_seeds=n_seeds, n_trials=n_trials, signals=signals, designs=designs,
                    noisy=noisy, seed=seed)
    return SignalComparison(settings, results)


def rod_numbers(result):
    """The numbers that compare Q-learner runs, from one `RodTopplingResult`, each a
    (mean, low, high) over the seeds unless said otherwise:

    - "<rod>_share" and "<rod>_share_late", for every rod of the run and "none": the
      share of episodes that ended with it toppled (with no topple), over all episodes
      and over the second half;
    - "red_well", "blue_well": the share of seeds in which the rod is predicted well
      (reading "all", see `icm.experiments.rod_toppling.READINGS`);
    - "red_well_episode", "blue_well_episode": that episode, over the seeds where it
      comes.
    """
    _validate.instance("result", result, _rod_toppling.RodTopplingResult,
                       "a RodTopplingResult (from icm.experiments.run_rod_toppling)")
    out, per_seed = {}, {}
    late = slice(result.n_episodes // 2, None)
    for rod in result.rod_names + (None,):
        name = rod or "none"
        per_seed[f"{name}_share"] = result.topple_shares(rod)
        per_seed[f"{name}_share_late"] = result.topple_shares(rod, late)
    for i, rod in enumerate(_rod_toppling.RODS):
        well = result.predicted_well[:, i]
        per_seed[f"{rod}_well"] = (well >= 1).astype(float)
        out[f"{rod}_well_episode"] = _band(well[well >= 1])
    out.update(_bands(per_seed))
    return out


@dataclasses.dataclass(frozen=True)
class RewardComparison:
    """What `run_reward_comparison` measured.

    Attributes:
      settings: the arguments of the comparison, as a dict.
      results: {(reward, wobbly_rod): RodTopplingResult}, every run on the same seeds.
    """

    settings: dict
    results: dict
    _numbers: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)

    def numbers(self, reward, wobbly_rod=False):
        """`rod_numbers` of one run of the comparison (computed once)."""
        key = _comparison_key(self.results, "(reward, wobbly_rod)", (reward, wobbly_rod))
        if key not in self._numbers:
            self._numbers[key] = rod_numbers(self.results[key])
        return self._numbers[key]

    def summary(self):
        """The numbers the chapter quotes, as a flat dict: keys
        "<reward>_<plain|wobbly>_<quantity>" (quantities of `rod_numbers`, means, with
        their bands as ..._low and ..._high)."""
        out = {}
        for (reward, wobbly), result in self.results.items():
            prefix = f"{reward}_{'wobbly' if wobbly else 'plain'}_"
            for name, (mean, low, high) in self.numbers(reward, wobbly).items():
                out[prefix + name] = mean
                out[prefix + name + "_low"] = low
                out[prefix + name + "_high"] = high
        return out

    def claims(self):
        """{claim name: whether it holds in this comparison}, for each of
        `REWARD_CLAIMS` (a comparison of every reward in both worlds): what the
        chapter states in words, checked on the book's runs when it is built, and by
        the tests on theirs."""
        needed = {(r, w) for r in ("prediction_error", "learning_progress", "novelty",
                                   "random") for w in (False, True)}
        if not needed <= set(self.results):
            raise ValueError("the chapter's claims need the rewards prediction_error, "
                             "learning_progress, novelty and random in both worlds")
        n = self.numbers
        error, progress = n("prediction_error", True), n("learning_progress", True)
        slow = [n(r, True) for r in ("novelty", "random")]
        return {
            "error_trapped": error["wobbly_share_late"][1] > TRAPPED_SHARE
            and error["red_well"][0] < n("prediction_error", False)["red_well"][0],
            "progress_learns_anyway": all(  # each rod's interval's lower end
                share_interval(int((well >= 1).sum()), len(well))[0] >= LEARNED_SHARE
                for well in self.results[("learning_progress", True)].predicted_well.T),
            "progress_not_immune": progress["wobbly_share_late"][1] > TRAPPED_SHARE,
            "novelty_random_not_trapped_but_slow": all(
                m["wobbly_share_late"][2] < TRAPPED_SHARE and m["red_well"][0] < 0.5
                for m in slow),
        }

    def seed_summaries(self):
        """One dict per seed: each run's share of episodes ending at the wobbly rod
        (runs with it) and the episodes from which red and blue are predicted well."""
        rows = [dict() for _ in range(self.settings["n_seeds"])]
        for (reward, wobbly), result in self.results.items():
            prefix = f"{reward}_{'wobbly' if wobbly else 'plain'}_"
            shares = result.topple_shares("wobbly") if wobbly else None
            for k, row in enumerate(rows):
                row[prefix + "red_well_episode"] = int(result.predicted_well[k, 0])
                row[prefix + "blue_well_episode"] = int(result.predicted_well[k, 1])
                if wobbly:
                    row[prefix + "wobbly_share"] = float(shares[k])
        return rows

    def table(self):
        """A Markdown table, one row per (reward, world): the share of episodes ending
        at each rod over the second half of the runs, and how many seeds predict red
        and blue well (and from which episode, median)."""
        lines = ["| reward | wobbly rod | episodes ending at red / blue / wobbly / none, "
                 "second half | red predicted well: seeds (episode) "
                 "| blue predicted well: seeds (episode) |", "|" + "---|" * 5]
        for reward, wobbly in self.results:
            n = self.numbers(reward, wobbly)
            shares = " / ".join(
                f"{n[f'{rod}_share_late'][0]:.2f}" if f"{rod}_share_late" in n else "-"
                for rod in ("red", "blue", "wobbly", "none"))
            cells = [reward.replace("_", " "), "yes" if wobbly else "no", shares]
            for rod in _rod_toppling.RODS:
                episode = n[f"{rod}_well_episode"][0]
                cells.append(f"{percent(n[f'{rod}_well'][0])} "
                             f"({'-' if np.isnan(episode) else f'{episode:.0f}'})")
            lines.append("| " + " | ".join(cells) + " |")
        return "\n".join(lines)


def run_reward_comparison(n_seeds=100, n_episodes=300, rewards=q_learning.REWARDS,
                          wobbly=(False, True), seed=0, progress=True):
    """Runs the Q-learner on the rods once per intrinsic reward and world, all on the
    same seeds (`run_rod_toppling`, its other settings at their defaults).

    Args:
      n_seeds: runs per setting (>= 1).
      n_episodes: episodes per run (>= 1).
      rewards: the rewards to compare (default all of `REWARDS`).
      wobbly: the worlds: False (red and blue), True (with the wobbly rod).
      seed: the root seed, the same for every setting.
      progress: a progress bar over the settings.

    Returns:
      A `RewardComparison`.

    Raises:
      ValueError: for a bad count, an unknown reward, a repeated one, or runs whose
        results this machine's memory could not hold.
    """
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    n_episodes = _validate.integer_at_least("n_episodes", n_episodes, 1)
    rewards = check_choices("rewards", rewards, q_learning.REWARDS)
    wobbly = check_choices("wobbly", wobbly, (False, True))
    seed = _validate.root_seed("seed", seed)
    _validate.boolean("progress", progress)
    grid = list(itertools.product(rewards, wobbly))
    check_memory("run_reward_comparison", {"runs": len(grid), "n_seeds": n_seeds,
                                           "n_episodes": n_episodes},
                 _runs_memory([_rod_toppling.memory_needed(
                     n_seeds, n_episodes, reward=reward, wobbly_rod=wobbly_rod)
                     for reward, wobbly_rod in grid]))
    results = {}
    for reward, wobbly_rod in progress_bar(grid, len(grid), "intrinsic rewards", progress,
                                           unit="run"):
        results[(reward, wobbly_rod)] = _rod_toppling.run_rod_toppling(
            n_seeds=n_seeds, n_episodes=n_episodes, reward=reward, wobbly_rod=wobbly_rod,
            seed=seed, progress=False)
    settings = dict(n_seeds=n_seeds, n_episodes=n_episodes, rewards=rewards, wobbly=wobbly,
                    seed=seed)
    return RewardComparison(settings, results)


