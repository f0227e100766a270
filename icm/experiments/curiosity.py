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
from icm.experiments.progress import progress_bar
from icm.learners import goal_oriented, interest, predictors, q_learning
from icm.stats import (bootstrap_band, comes_first, corrected_verdicts, paired_gaps,
                       share_interval)


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


