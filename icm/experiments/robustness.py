"""What the paper's results depend on: the settings the paper does not publish, swept
one pair at a time, with the paper's claims measured at every grid point.

Each learner is a `Study`: its run function, the run length of its chapter, the
unpublished settings (`Setting`, each with the library's default and a grid of
values) and the claims the paper makes about it (`Claim`). `run_robustness` sweeps
every pair of a study's settings (the others held at their defaults) with
`icm.experiments.sweep`, on the same seeds at every point, and keeps for every seed
whether each claim held in it.

A claim *holds* at a grid point when the share of seeds in which it held is at least
its threshold, and *fails* when the share is below it; the share is measured on a
sample of seeds, so both are decided from the share's 95% Wilson interval
(`icm.stats.share_interval`, `icm.stats.verdict`): "holds" when the whole interval is
at or above the threshold, "fails" when it is all below, "unclear" when it straddles
the threshold.

The choices the paper does not make and the maps do not sweep are measured one at a
time in `icm.experiments.robustness_readings`; the chapter's claims, tables and
numbers are in `icm.chapters.robustness`.
"""

import dataclasses

import numpy as np

from icm import _validate
from icm.envs import buttons, rods
from icm.experiments._progress import progress_bar
from icm.experiments.actor_critic import run_actor_critic
from icm.experiments.goal_oriented import CHAPTER_TRIALS, run_goal_oriented
from icm.experiments.goal_oriented_results import TASKS
from icm.experiments.rod_toppling import run_rod_toppling
from icm.experiments.sweep import sweep
from icm.stats import VERDICTS, bootstrap_band, comes_first, share_interval, verdict

CLAIM_SHARE = 0.9
"""The share of seeds in which an order or a learning claim must hold ("red mastered
first in at least 90% of seeds"; the paper gives no share)."""
MAJORITY = 0.5
"""The share of seeds for "interest moves to the hard task later", which the paper
states "on average": it must hold in at least half of the runs."""
INTERACTION_ALPHA = 0.05
"""How often a whole map may show an interaction that is not there: the bands of
`RobustnessResult.interaction` are at the level 1 - INTERACTION_ALPHA / (points)."""
INTERACTION_RESAMPLES = 2000
"""Bootstrap resamples of the interaction bands (their level is high: see
`RobustnessResult.interaction`)."""


@dataclasses.dataclass(frozen=True)
class Sweep:
    """An unpublished setting and the values a sweep tries, from its
    `icm._settings.Setting` (whose `swept` are the values).

    Attributes:
      name: the run function's argument.
      label: what the figures and tables call it (the setting's label).
      default: the library's value (the run function's default), one of `values`.
      values: the grid, in order.
    """

    name: str
    label: str
    default: object
    values: tuple


@dataclasses.dataclass(frozen=True)
class Claim:
    """A claim of the paper, measured per seed.

    Attributes:
      name: the per-seed column (True where the claim held in that seed).
      text: the claim in words.
      threshold: the share of seeds in which it must hold.
    """

    name: str
    text: str
    threshold: float


@dataclasses.dataclass(frozen=True)
class Study:
    """One learner's settings and claims, and how to run it.

    Attributes:
      name: the study's key in `STUDIES`.
      title: the learner and its task, in words.
      run_fn: the experiment (`run_goal_oriented`, ...).
      fixed: arguments held fixed in every run (the run length of its chapter).
      settings: the swept settings (`Sweep` objects).
      claims: the measured claims (`Claim` objects).
      per_seed: the function that turns a run into one dict per seed with a boolean
        column per claim (the `per_seed` argument of `sweep`).
    """

    name: str
    title: str
    run_fn: object
    fixed: dict
    settings: tuple
    claims: tuple
    per_seed: object

    def setting(self, name):
        """The `Sweep` of setting `name`."""
        names = [s.name for s in self.settings]
        return self.settings[names.index(_validate.one_of("setting", name, tuple(names)))]

    def claim(self, name):
        """The `Claim` called `name`."""
        names = [c.name for c in self.claims]
        return self.claims[names.index(_validate.one_of("claim", name, tuple(names)))]

    def pairs(self):
        """Every pair of settings, as (first, second) names, in the settings' order."""
        names = [s.name for s in self.settings]
        return [(a, b) for i, a in enumerate(names) for b in names[i + 1:]]

    def defaults(self):
        """{setting name: its default}."""
        return {s.name: s.default for s in self.settings}


def interest_centres(result):
    """[seed, task], the interest-weighted mean trial of each task (red, green) in each
    run: `GoalOrientedResult.interest_centre` of one seed's curve. NaN where a run never
    showed any interest in the task."""
    interest = result.interest  # [seed, trial, task]
    trials = np.arange(1, interest.shape[1] + 1, dtype=float)
    mass = interest.sum(axis=1)
    moment = np.einsum("stk,t->sk", interest, trials)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(mass > 0, moment / np.where(mass > 0, mass, 1.0), np.nan)


def goal_oriented_claims(result):
    """Per seed of a `GoalOrientedResult`: its `seed_summaries()`, and whether each
    claim held in that run.

    - "red_first": red is mastered strictly before green (`seed_summaries`);
    - "interest_later": the run showed interest in both tasks and its interest in
      green is centred on a later trial than its interest in red
      (`interest_centres`);
    - "green_mastered": green is mastered within the run.
    """
    centres = interest_centres(result)
    red, green = centres[:, TASKS.index("red")], centres[:, TASKS.index("green")]
    later = ~np.isnan(red) & ~np.isnan(green) & (green > red)
    rows = result.seed_summaries()
    for row, is_later in zip(rows, later.tolist()):
        row["interest_later"] = bool(is_later)
        row["green_mastered"] = row["green_mastery_trial"] >= 1
    return rows


def actor_critic_claims(result):
    """Per seed of an `ActorCriticResult`: its `seed_summaries()` ("red_first": the red
    error reaches 0 for good strictly before the green one), and "green_learned": the
    green error reaches 0 for good within the run."""
    rows = result.seed_summaries()
    for row in rows:
        row["green_learned"] = row["green_zero_trial"] >= 1
    return rows


def rod_claims(result):
    """Per seed of a `RodTopplingResult`: its `seed_summaries()` ("red_first": red is
    predicted well, reading "all", strictly before blue), and

    - "red_toppled_first": the first topple of red comes before the first of blue;
    - "blue_found": blue is toppled at least once within the run.
    """
    rows = result.seed_summaries()
    red_first_topple = comes_first(result.first_topple("red"), result.first_topple("blue"))
    for row, toppled_first in zip(rows, red_first_topple.tolist()):
        row["red_toppled_first"] = bool(toppled_first)
        row["blue_found"] = row["first_blue_topple"] >= 1
    return rows


WORLD_SETTINGS = {"presses_per_trial": buttons.PRESSES_PER_TRIAL,
                  "max_moves": rods.MAX_MOVES, "off_grid": rods.OFF_GRID}
"""The settings of the worlds (not of a learner) that a study may sweep or read
otherwise."""
STUDY_WORLDS = {"goal_oriented": ("presses_per_trial",), "actor_critic": ("presses_per_trial",),
                "rod_toppling": ("max_moves", "off_grid")}
"""The world settings of each study's experiment (keys of `WORLD_SETTINGS`)."""
NOT_MEASURED = {
    ("actor_critic", "epsilon"): 'it is used only with action_selection="epsilon_greedy", '
                                 "and the book's actor-critic picks by softmax",
}
"""Unpublished settings of a study that `run_readings` does not measure, with the
reason (every other unpublished setting is swept by the maps or has other readings)."""


def _sweep(run_fn, name):
    """The `Sweep` of setting `name` of `run_fn` (a learner setting, or one of
    `WORLD_SETTINGS`), from its `icm._settings.Setting`."""
    specs = {**WORLD_SETTINGS, **run_fn.settings_class.specs()}
    spec = specs[name]
    if spec.swept is None:
        raise ValueError(f"{name} is not one of the settings the robustness study sweeps "
                         f"(its Setting has no swept values)")
    if spec.default not in spec.swept:
        raise ValueError(f"the default {name} {spec.default!r} must be on its grid "
                         f"{spec.swept}")
    return Sweep(name, spec.label, spec.default, tuple(spec.swept))


def _study(name, title, run_fn, fixed, settings, claims, per_seed):
    return Study(name, title, run_fn, dict(fixed),
                 tuple(_sweep(run_fn, n) for n in settings),
                 tuple(Claim(*c) for c in claims), per_seed)


STUDIES = {
    "goal_oriented": _study(
        "goal_oriented", "goal-oriented learner, button console (Figure 5)",
        run_goal_oriented, {"n_trials": CHAPTER_TRIALS},
        ("action_weight", "presses_per_trial", "reading"),
        [("red_first", "red mastered first", CLAIM_SHARE),
         ("interest_later", "interest moves to green later", MAJORITY),
         ("green_mastered", "green mastered too", CLAIM_SHARE)],
        goal_oriented_claims),
    "actor_critic": _study(
        "actor_critic", "intrinsic actor-critic, button console (Figure 6)",
        run_actor_critic, {"n_trials": 100},
        ("action_weight", "presses_per_trial", "variant"),
        [("red_first", "red predicted well first", CLAIM_SHARE),
         ("green_learned", "green predicted well too", CLAIM_SHARE)],
        actor_critic_claims),
    "rod_toppling": _study(
        "rod_toppling", "Q-learner on the rods (Figure 7)",
        run_rod_toppling, {"n_episodes": 300},
        ("initial_q", "epsilon"),
        [("red_toppled_first", "red toppled first", CLAIM_SHARE),
         ("red_first", "red predicted well first", CLAIM_SHARE),
         ("blue_found", "blue found", CLAIM_SHARE)],
        rod_claims),
}
"""The three learners' studies, by name."""


def check_study(study):
    """The `Study` named `study` (one of `STUDIES`), or `study` itself if it is one."""
    if isinstance(study, Study):
        return study
    return STUDIES[_validate.one_of("study", study, tuple(STUDIES))]


@dataclasses.dataclass(frozen=True)
class RobustnessResult:
    """What `run_robustness` measured for one study.

    Attributes:
      study: the `Study`.
      settings: the arguments of the run (n_seeds, seed).
      frames: {(setting, setting): DataFrame}, the sweep of each pair (the other
        settings at their defaults): one row per grid point and seed, with the
        settings, `seed_index` and a boolean column per claim.
    """

    study: Study
    settings: dict
    frames: dict
    _cache: dict = dataclasses.field(default_factory=dict, init=False, repr=False,
                                     compare=False)

    @property
    def n_seeds(self):
        """Seeds per grid point."""
        return self.settings["n_seeds"]

    def points(self):
        """One row per measured grid point (points shared by two pairs' sweeps, which
        ran the same seeds, once): every setting's value, the seeds, and per claim the
        share of seeds in which it held (`<claim>`), its 95% interval (`<claim>_low`,
        `<claim>_high`) and the verdict (`<claim>_verdict`)."""
        if "points" not in self._cache:
            self._cache["points"] = self._points()
        return self._cache["points"].copy()

    def _points(self):
        import pandas as pd

        names = [s.name for s in self.study.settings]
        rows = self._seed_rows()
        claims = [c.name for c in self.study.claims]
        grouped = rows.groupby(names, sort=False)
        table = grouped[claims].agg(["sum", "count"])
        out = pd.DataFrame(index=table.index)
        for claim in self.study.claims:
            successes = table[(claim.name, "sum")].to_numpy().astype(np.int64)
            n = table[(claim.name, "count")].to_numpy().astype(np.int64)
            low, high = share_interval(successes, n)
            out["n_seeds"] = n
            out[claim.name] = successes / n
            out[claim.name + "_low"] = low
            out[claim.name + "_high"] = high
            out[claim.name + "_verdict"] = [verdict(lo, hi, claim.threshold)
                                            for lo, hi in zip(low, high)]
        return out.reset_index()

    def _point(self, point):
        point = {**self.study.defaults(), **point}
        for name, value in point.items():
            setting = self.study.setting(name)
            _validate.one_of(name, value, setting.values)
        table = self.points()
        match = np.ones(len(table), dtype=bool)
        for name, value in point.items():
            match &= (table[name] == value).to_numpy()
        if not match.any():
            varied = {n: v for n, v in point.items() if v != self.study.setting(n).default}
            raise ValueError(f"the point {varied} was not measured: at most two settings "
                             f"differ from their defaults in a map of pairs")
        return table[match].iloc[0]

    def share(self, claim, **point):
        """(share, low, high): the share of seeds in which `claim` held at `point`
        (settings not given at their defaults), with its 95% interval.

        Raises:
          ValueError: for an unknown claim or setting, a value off the grid, or a point
            that changes more than two settings.
        """
        claim = self.study.claim(claim).name
        row = self._point(point)
        return (float(row[claim]), float(row[claim + "_low"]), float(row[claim + "_high"]))

    def verdict(self, claim, **point):
        """"holds", "unclear" or "fails": what `point` says about `claim` (see
        `share`)."""
        claim = self.study.claim(claim).name
        return str(self._point(point)[claim + "_verdict"])

    def pair_table(self, claim, pair):
        """The map of `claim` over `pair` (the other settings at their defaults), as a
        dict of arrays [second setting's value, first setting's value]: "share",
        "low", "high" (its 95% interval) and "verdict"."""
        claim = self.study.claim(claim)
        held = self.seed_table(claim.name, pair)
        successes = held.sum(axis=0)
        low, high = share_interval(successes, np.full_like(successes, held.shape[0]))
        verdicts = np.array([verdict(lo, hi, claim.threshold)
                             for lo, hi in zip(low.ravel(), high.ravel())], dtype=object)
        return {"share": successes / held.shape[0], "low": low, "high": high,
                "verdict": verdicts.reshape(successes.shape)}

    def holding_values(self, claim, setting):
        """The values of `setting` at which `claim` holds, the other settings at their
        defaults, in grid order."""
        setting = self.study.setting(setting)
        return [v for v in setting.values if self.verdict(claim, **{setting.name: v})
                == "holds"]

    def holds_from(self, claim, setting):
        """The value of `setting` (the others at their defaults) from which `claim`
        holds at every larger value of the grid and at no smaller one; None when the
        values at which it holds are not such a tail of the grid (or are none)."""
        values = list(self.study.setting(setting).values)
        held = self.holding_values(claim, setting)
        for i in range(len(values)):
            if held == values[i:]:
                return values[i]
        return None

    def seed_table(self, claim, pair):
        """[seed, second setting's value, first setting's value], whether `claim`
        held in each seed at each point of the map of `pair` (a boolean array)."""
        claim = self.study.claim(claim).name
        pair = self._check_pair(pair)
        a, b = (self.study.setting(n) for n in pair)
        rows = self._seed_rows()
        for name, value in self.study.defaults().items():
            if name not in pair:
                rows = rows[rows[name] == value]
        out = np.zeros((self.n_seeds, len(b.values), len(a.values)), dtype=bool)
        column = {v: j for j, v in enumerate(a.values)}
        line = {v: i for i, v in enumerate(b.values)}
        out[rows["seed_index"].to_numpy(), rows[b.name].map(line).to_numpy(),
            rows[a.name].map(column).to_numpy()] = rows[claim].to_numpy(bool)
        return out

    def interaction(self, claim, pair):
        """How much the two settings of `pair` interact for `claim`, at every point of
        their map.

        The interaction at (a, b) is the classic contrast of the shares,
        share(a, b) - share(a, b0) - share(a0, b) + share(a0, b0) (a0, b0: the
        defaults): how far changing both moves the share from what changing each
        alone predicts. It is 0 where the two effects add up. Its band is a
        percentile bootstrap over the seeds (`icm.stats.bootstrap_band`, the seeds
        resampled together at all points, since every point ran the same seeds), at
        the level 1 - `INTERACTION_ALPHA` / (number of points), so that the whole map,
        not each point, is wrong less than that share of the time.

        Returns:
          A dict of arrays [second setting's value, first setting's value]:
          "contrast", "low", "high".
        """
        pair = self._check_pair(pair)
        key = ("interaction", self.study.claim(claim).name, pair)
        if key in self._cache:
            return self._cache[key]
        held = self.seed_table(claim, pair).astype(float)
        a, b = (self.study.setting(n) for n in pair)
        ia, ib = a.values.index(a.default), b.values.index(b.default)
        contrast = (held - held[:, :, [ia]] - held[:, [ib], :]
                    + held[:, [ib], :][:, :, [ia]])
        level = 1 - INTERACTION_ALPHA / contrast[0].size
        mean, low, high = bootstrap_band(contrast, level=level, resamples=INTERACTION_RESAMPLES,
                                         seed=self.settings["seed"])
        self._cache[key] = {"contrast": mean, "low": low, "high": high}
        return self._cache[key]

    def interacts(self, claim, pair):
        """Whether the settings of `pair` interact for `claim`: the band of the
        interaction (see `interaction`) excludes 0 at some point of their map."""
        found = self.interaction(claim, pair)
        return bool(np.any((found["low"] > 0) | (found["high"] < 0)))

    def strongest_interaction(self, claim, pair):
        """(contrast, low, high, a, b): the interaction of largest size on the map of
        `pair` for `claim`, its band, and the values of the pair's two settings there
        (see `interaction`)."""
        pair = self._check_pair(pair)
        found = self.interaction(claim, pair)
        i, j = np.unravel_index(np.argmax(np.abs(found["contrast"])), found["contrast"].shape)
        a, b = (self.study.setting(n) for n in pair)
        return (float(found["contrast"][i, j]), float(found["low"][i, j]),
                float(found["high"][i, j]), a.values[j], b.values[i])

    def _check_pair(self, pair):
        if not isinstance(pair, (tuple, list)) or tuple(pair) not in self.frames:
            raise ValueError(f"pair must be one of {list(self.frames)}, got {pair!r}")
        return tuple(pair)

    def _seed_rows(self):
        """Every seed's row at every measured point, the settings all filled in."""
        if "rows" in self._cache:
            return self._cache["rows"]
        import pandas as pd

        names = [s.name for s in self.study.settings]
        defaults = self.study.defaults()
        tables = [frame.assign(**{n: defaults[n] for n in names if n not in frame.columns})
                  for frame in self.frames.values()]
        self._cache["rows"] = pd.concat(tables).drop_duplicates(names + ["seed_index"])
        return self._cache["rows"]

    def summary(self):
        """The numbers the book quotes, as a dict: for each claim, its share of seeds
        at the defaults (`<claim>`), the lowest and highest share on the whole map
        (`<claim>_min`, `<claim>_max`), and how many grid points it holds, fails or
        is unclear at (`<claim>_holds`, `_fails`, `_unclear`); and `n_points`, the
        grid points measured."""
        table = self.points()
        out = {"n_points": len(table), "n_seeds": self.n_seeds}
        for claim in self.study.claims:
            out[claim.name] = self.share(claim.name)[0]
            out[claim.name + "_min"] = float(table[claim.name].min())
            out[claim.name + "_max"] = float(table[claim.name].max())
            for v in VERDICTS:
                out[f"{claim.name}_{v}"] = int((table[claim.name + "_verdict"] == v).sum())
        return out


def run_robustness(study, n_seeds=200, seed=0, n_jobs=1, progress=True):
    """Sweeps every pair of a study's settings and measures its claims at every point.

    Each pair's grid is swept with `icm.experiments.sweep` (the other settings at
    their defaults, the run length of the learner's chapter), `n_seeds` seeds per
    point, the same seeds at every point.

    Args:
      study: "goal_oriented", "actor_critic" or "rod_toppling" (see `STUDIES`), or a
        `Study`.
      n_seeds: seeds per grid point (>= 1; the book uses 200).
      seed: the root seed (an integer >= 0, a Generator or None).
      n_jobs: parallel jobs (joblib; -1 for one per core).
      progress: show a progress bar per pair.

    Returns:
      A `RobustnessResult`.

    Raises:
      ValueError: for an unknown study or a bad n_seeds, seed or n_jobs.
    """
    study = check_study(study)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    seed = _validate.root_seed("seed", seed)
    _validate.boolean("progress", progress)
    frames = {}
    for pair, grid in pair_grids(study):
        others = {n: v for n, v in study.defaults().items() if n not in pair}
        frames[pair] = sweep(study.run_fn, grid, n_seeds=n_seeds, seed=seed, n_jobs=n_jobs,
                             progress=progress, per_seed=study.per_seed,
                             **study.fixed, **others)
    return RobustnessResult(study, {"n_seeds": n_seeds, "seed": seed}, frames)


def pair_grids(study):
    """The grid to sweep for each pair of settings, without the points an earlier
    pair's grid already holds: where a setting's default row of the map was measured
    before (the other setting alone changed), its default is left out."""
    defaults = study.defaults()
    names = [s.name for s in study.settings]
    measured = set()

    def key(point):
        return tuple(point[n] for n in names)

    out = []
    for a, b in study.pairs():
        grid = {a: list(study.setting(a).values), b: list(study.setting(b).values)}
        for kept, dropped in ((a, b), (b, a)):
            line = [key({**defaults, kept: v}) for v in grid[kept]]
            if all(point in measured for point in line):
                grid[dropped] = [v for v in grid[dropped] if v != defaults[dropped]]
        for va in grid[a]:
            for vb in grid[b]:
                measured.add(key({**defaults, a: va, b: vb}))
        out.append(((a, b), grid))
    return out


def check_point(study, claim, n_seeds=200, seed=0, **point):
    """Measures one claim at one point of a study's settings, without a sweep.

    Args:
      study: a study's name or `Study`.
      claim: one of the study's claims.
      n_seeds: seeds (>= 1).
      seed: the root seed.
      **point: settings that differ from their defaults (any values the run accepts).

    Returns:
      (verdict, share, low, high).
    """
    study = check_study(study)
    claim = study.claim(claim)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    for name in point:
        study.setting(name)
    result = study.run_fn(n_seeds=n_seeds, seed=seed, progress=False,
                          **study.fixed, **{**study.defaults(), **point})
    held = np.array([row[claim.name] for row in study.per_seed(result)], dtype=bool)
    low, high = share_interval(int(held.sum()), len(held))
    return verdict(low, high, claim.threshold), float(held.mean()), low, high


def show_value(value):
    """A setting's value as the chapter's tables write it."""
    if value is None:  # a setting whose None is "none at all" (max_moves: no limit)
        return "none"
    return f"{value:g}" if isinstance(value, float) else str(value)


