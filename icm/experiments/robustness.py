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
(`share_interval`): "holds" when the whole interval is at or above the threshold,
"fails" when it is all below, "unclear" when it straddles the threshold.

The choices the paper does not make and the maps do not sweep are measured one at a
time (`run_readings`): for each, every other reading its `Setting` declares
(`icm._settings.Setting.other_readings`: an unpublished choice's other choices, or the
other values it lists), run on the same seeds as the book's reading, with the same
claims (`ReadingsResult`).
"""

import dataclasses
import statistics

import numpy as np

from icm import _validate
from icm.envs import buttons, rods
from icm.experiments._progress import progress_bar
from icm.experiments.actor_critic import run_actor_critic
from icm.experiments.goal_oriented import CHAPTER_TRIALS, TASKS, run_goal_oriented
from icm.experiments.results import in_seeds
from icm.experiments.rod_toppling import run_rod_toppling
from icm.experiments.sweep import sweep
from icm.stats import bootstrap_band, comes_first

CLAIM_SHARE = 0.9
"""The share of seeds in which an order or a learning claim must hold ("red mastered
first in at least 90% of seeds"; the paper gives no share)."""
MAJORITY = 0.5
"""The share of seeds for "interest moves to the hard task later", which the paper
states "on average": it must hold in at least half of the runs."""
LEVEL = 0.95
"""Confidence level of the interval around every measured share."""
INTERACTION_ALPHA = 0.05
"""How often a whole map may show an interaction that is not there: the bands of
`RobustnessResult.interaction` are at the level 1 - INTERACTION_ALPHA / (points)."""
INTERACTION_RESAMPLES = 2000
"""Bootstrap resamples of the interaction bands (their level is high: see
`RobustnessResult.interaction`)."""
VERDICTS = ("holds", "unclear", "fails")
"""What a grid point says about a claim (see the module's docstring)."""


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


@dataclasses.dataclass(frozen=True)
class Reading:
    """Another reading of a choice the paper does not make.

    Attributes:
      name: the run function's argument.
      label: what it is, in words (the setting's label).
      default: the book's reading.
      value: the other reading.
      source: why the book reads it so (the setting's source).
    """

    name: str
    label: str
    default: object
    value: object
    source: str

    @property
    def key(self):
        """(name, value): the reading's key in a `ReadingsResult`."""
        return (self.name, self.value)


def unpublished_settings(study):
    """{name: Setting} of the settings of a study's learner and world that the paper
    does not publish, in declaration order (the learner's, then the world's)."""
    study = _check_study(study)
    specs = {**study.run_fn.settings_class.specs(),
             **{n: WORLD_SETTINGS[n] for n in STUDY_WORLDS[study.name]}}
    return {name: spec for name, spec in specs.items() if not spec.published}


def readings(study):
    """The other readings `run_readings` measures for a study: for each unpublished
    setting that its maps do not sweep (and that is not in `NOT_MEASURED`), each value
    of its `Setting.other_readings()`, as `Reading` objects."""
    study = _check_study(study)
    out = []
    for name, spec in unpublished_settings(study).items():
        if (study.name, name) in NOT_MEASURED:
            continue
        for value in spec.other_readings():
            out.append(Reading(name, spec.label, spec.default, value, spec.source))
    return tuple(out)


def share_interval(successes, n, level=LEVEL):
    """The Wilson score interval of a share of `successes` out of `n`.

    Unlike mean +/- z standard errors it stays within [0, 1] and does not shrink to a
    point when every seed (or none) succeeds: 200 successes out of 200 give
    [0.981, 1].

    Args:
      successes: integer (or integer array) in 0..n.
      n: number of trials (integer >= 1, or an array like `successes`).
      level: confidence level in (0, 1).

    Returns:
      (low, high), floats (or arrays).

    Raises:
      ValueError: for counts that are not integers with 0 <= successes <= n, n >= 1,
        or a level outside (0, 1).
    """
    level = _validate.real("level", level, 0.0, 1.0, low_open=True, high_open=True)
    k, n_ = np.asarray(successes), np.asarray(n)
    for name, value in (("successes", k), ("n", n_)):
        if value.dtype.kind not in "iu":
            raise _validate.ArgumentTypeError(f"{name} must hold integers, got "
                                              f"{_validate.show(value)}")
    if np.any(n_ < 1) or np.any(k < 0) or np.any(k > n_):
        raise ValueError(f"successes must be in 0..n and n >= 1, got successes "
                         f"{_validate.show(k)} and n {_validate.show(n_)}")
    z = statistics.NormalDist().inv_cdf(0.5 + level / 2)  # not scipy: 2 s to import
    p = k / n_
    denominator = 1 + z**2 / n_
    centre = (p + z**2 / (2 * n_)) / denominator
    half = z * np.sqrt(p * (1 - p) / n_ + z**2 / (4 * n_**2)) / denominator
    # Exactly 0 (1) when no (every) seed succeeds, whatever the rounding.
    low = np.where(k == 0, 0.0, np.clip(centre - half, 0.0, 1.0))
    high = np.where(k == n_, 1.0, np.clip(centre + half, 0.0, 1.0))
    if low.ndim == 0:
        return float(low), float(high)
    return low, high


def verdict(low, high, threshold):
    """"holds" if the interval [low, high] is at or above `threshold`, "fails" if it
    is below it, "unclear" if it straddles it.

    Args:
      low, high: the interval of a share (numbers in [0, 1], low <= high).
      threshold: the share a claim needs, in [0, 1].

    Raises:
      ValueError: for a bound or threshold outside [0, 1] (NaN included), or low > high.
    """
    low = _validate.in_closed_interval("low", low, 0.0, 1.0)
    high = _validate.in_closed_interval("high", high, 0.0, 1.0)
    threshold = _validate.in_closed_interval("threshold", threshold, 0.0, 1.0)
    if low > high:
        raise ValueError(f"low must be at most high, got low {low!r} and high {high!r}")
    if low >= threshold:
        return "holds"
    if high < threshold:
        return "fails"
    return "unclear"


def _check_study(study):
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

    def shares_along(self, claim, setting, **point):
        """In words, the share of seeds in which `claim` held at each value of
        `setting` (the other settings at `point`, or at their defaults), e.g. "51% at
        1, 49% at 1.5, 97% at 3": a clause for the chapter (Markdown)."""
        setting = self.study.setting(setting)
        return ", ".join(f"{self.share(claim, **{**point, setting.name: v})[0]:.1%} at "
                         f"{_show(v)}" for v in setting.values)

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


def studies_table(studies=None):
    """A Markdown table of the studies: for each learner, the settings its maps sweep
    and the claims they measure, with the share of seeds each needs.

    Args:
      studies: names or `Study` objects (default all of `STUDIES`).
    """
    studies = [_check_study(s) for s in (STUDIES if studies is None else studies)]
    lines = ["| learner | settings swept | claims (share of seeds needed) |", "|---|---|---|"]
    for study in studies:
        lines.append(f"| {study.title} | {', '.join(s.label for s in study.settings)} | "
                     + "; ".join(f"{c.text} (≥ {c.threshold:.0%})" for c in study.claims)
                     + " |")
    return "\n".join(lines)


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
    study = _check_study(study)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    seed = _validate.root_seed("seed", seed)
    _validate.boolean("progress", progress)
    frames = {}
    for pair, grid in _pair_grids(study):
        others = {n: v for n, v in study.defaults().items() if n not in pair}
        frames[pair] = sweep(study.run_fn, grid, n_seeds=n_seeds, seed=seed, n_jobs=n_jobs,
                             progress=progress, per_seed=study.per_seed,
                             **study.fixed, **others)
    return RobustnessResult(study, {"n_seeds": n_seeds, "seed": seed}, frames)


def _pair_grids(study):
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
    study = _check_study(study)
    claim = study.claim(claim)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    for name in point:
        study.setting(name)
    result = study.run_fn(n_seeds=n_seeds, seed=seed, progress=False,
                          **study.fixed, **{**study.defaults(), **point})
    held = np.array([row[claim.name] for row in study.per_seed(result)], dtype=bool)
    low, high = share_interval(int(held.sum()), len(held))
    return verdict(low, high, claim.threshold), float(held.mean()), low, high


def dependency_table(results):
    """A Markdown table: for each learner and setting, the values (of those tried) at
    which each claim holds when only that setting changes.

    Args:
      results: a list of `RobustnessResult` objects.

    Returns:
      A Markdown string.
    """
    _check_results(results)
    lines = ["| learner | setting (default) | tried | claim | holds at |",
             "|---|---|---|---|---|"]
    for result in results:
        for setting in result.study.settings:
            tried = ", ".join(_show(v) for v in setting.values)
            for claim in result.study.claims:
                held = result.holding_values(claim.name, setting.name)
                where = "all" if len(held) == len(setting.values) else \
                    (", ".join(_show(v) for v in held) or "none")
                lines.append(f"| {result.study.title} | {setting.label} "
                             f"({_show(setting.default)}) | {tried} | {claim.text} "
                             f"(≥ {claim.threshold:.0%}) | {where} |")
    return "\n".join(lines)


def interaction_table(results):
    """A Markdown table: for each learner, claim and pair of settings, the strongest
    interaction on the pair's map (see `RobustnessResult.interaction`), in points of
    share, with its band and where it is, and whether the pair interacts.

    Args:
      results: a list of `RobustnessResult` objects.

    Returns:
      A Markdown string.
    """
    _check_results(results)
    lines = ["| learner | claim | pair | strongest interaction (points, band) | at | "
             "interact? |", "|---|---|---|---|---|---|"]
    for result in results:
        for claim in result.study.claims:
            for pair in result.study.pairs():
                a, b = (result.study.setting(n) for n in pair)
                contrast, low, high, va, vb = result.strongest_interaction(claim.name, pair)
                lines.append(
                    f"| {result.study.title} | {claim.text} | {a.label} x {b.label} "
                    f"| {100 * contrast:+.0f} ({100 * low:+.0f} to {100 * high:+.0f}) "
                    f"| {_show(va)}, {_show(vb)} "
                    f"| {'yes' if result.interacts(claim.name, pair) else 'no'} |")
    return "\n".join(lines)


def _check_results(results):
    if not isinstance(results, (list, tuple)) or not results:
        raise _validate.ArgumentTypeError(f"results must be a non-empty list of "
                                          f"RobustnessResult, got {_validate.show(results)}")
    for i, result in enumerate(results):
        _validate.instance(f"results[{i}]", result, RobustnessResult)
    return results


def _show(value):
    if value is None:  # a setting whose None is "none at all" (max_moves: no limit)
        return "none"
    return f"{value:g}" if isinstance(value, float) else str(value)


@dataclasses.dataclass(frozen=True)
class ReadingsResult:
    """What `run_readings` measured for one study: the book's run and one run per
    other reading, all on the same seeds.

    Attributes:
      study: the `Study`.
      settings: the arguments of the runs (n_seeds, seed).
      readings: the `Reading` objects measured, in order.
      runs: {None: the book's run, (name, value): the run with that reading}, the run
        results (e.g. `RodTopplingResult`).
      held: {None or (name, value): {claim: bool array [seed]}}, whether each claim
        held in each seed.
    """

    study: Study
    settings: dict
    readings: tuple
    runs: dict
    held: dict

    @property
    def n_seeds(self):
        """Seeds per run."""
        return self.settings["n_seeds"]

    def _key(self, reading):
        if reading is None:
            return None
        key = reading.key if isinstance(reading, Reading) else reading
        if not isinstance(key, tuple) or key not in self.held:
            raise ValueError(f"reading must be None (the book's) or one of "
                             f"{[r.key for r in self.readings]}, got {reading!r}")
        return key

    def run(self, reading=None):
        """The run of `reading` (a `Reading` or its (name, value) key; None: the
        book's)."""
        return self.runs[self._key(reading)]

    def share(self, claim, reading=None):
        """(share, low, high): the share of seeds in which `claim` held with
        `reading` (None: the book's), and its 95% Wilson interval."""
        claim = self.study.claim(claim).name
        held = self.held[self._key(reading)][claim]
        low, high = share_interval(int(held.sum()), len(held))
        return float(held.mean()), low, high

    def verdict(self, claim, reading=None):
        """"holds", "unclear" or "fails": what `reading` says about `claim`."""
        _, low, high = self.share(claim, reading)
        return verdict(low, high, self.study.claim(claim).threshold)

    def changed(self, reading):
        """The claims (names) whose verdict `reading` changes from the book's."""
        return [c.name for c in self.study.claims
                if self.verdict(c.name, reading) != self.verdict(c.name)]

    def changes(self):
        """The readings that change the verdict of at least one claim."""
        return [r for r in self.readings if self.changed(r)]

    def table(self):
        """A Markdown table: the book's reading, then one row per other reading, with
        the share of seeds in which each claim held and its verdict (✓ holds, ✗
        fails, ? unclear; in bold where it differs from the book's)."""
        marks = {"holds": "✓", "fails": "✗", "unclear": "?"}
        claims = self.study.claims
        lines = ["| choice | reading | " + " | ".join(
                     f"{c.text} (≥ {c.threshold:.0%})" for c in claims) + " |",
                 "|---|---|" + "---|" * len(claims)]

        def cells(reading):
            out = []
            for c in claims:
                share, verdict_ = self.share(c.name, reading)[0], self.verdict(c.name, reading)
                cell = f"{share:.1%} {marks[verdict_]}"
                if reading is not None and verdict_ != self.verdict(c.name):
                    cell = f"**{cell}**"
                out.append(cell)
            return out

        lines.append("| the book's | all as in the book | " + " | ".join(cells(None)) + " |")
        for r in self.readings:
            lines.append(f"| {r.label} (book: {_show(r.default)}) | {_show(r.value)} | "
                         + " | ".join(cells(r)) + " |")
        return "\n".join(lines)

    def describe(self):
        """In words, which of the other readings change a claim's verdict, and how: a
        clause for the chapter, computed from the data."""
        changed = self.changes()
        n = len(self.readings)
        if not changed:
            return (f"None of the {n} other readings changes the verdict of a claim: "
                    f"every claim holds, fails or stays unclear as with the book's")
        parts = []
        for r in changed:
            what = ", ".join(f"\"{self.study.claim(c).text}\" {self.verdict(c, r)} "
                             f"({self.share(c, r)[0]:.1%} of the seeds; with the book's "
                             f"{_show(r.default)}, it {self.verdict(c)}, "
                             f"{self.share(c)[0]:.1%})" for c in self.changed(r))
            parts.append(f"with {r.label} read as {_show(r.value)}, {what}")
        rest = n - len(changed)
        changes = "changes" if len(changed) == 1 else "change"
        return (f"Of the {n} other readings, {len(changed)} {changes} a claim's verdict: "
                + "; ".join(parts) + f". The other {rest} change none")


def readings_summary(results):
    """In words, over several `ReadingsResult` objects, which other readings change a
    claim's verdict and how many change none: a clause for the chapter (Markdown).

    Args:
      results: a list of `ReadingsResult` objects.
    """
    if not isinstance(results, (list, tuple)) or not results:
        raise _validate.ArgumentTypeError(f"results must be a non-empty list of "
                                          f"ReadingsResult, got {_validate.show(results)}")
    for i, result in enumerate(results):
        _validate.instance(f"results[{i}]", result, ReadingsResult)
    changed = [(result, r) for result in results for r in result.changes()]
    total = sum(len(result.readings) for result in results)
    if not changed:
        return f"none of the {total} other readings changes a claim's verdict"
    named = "; ".join(f"{r.label} read as {_show(r.value)} ({result.study.title}: "
                      + ", ".join(f"{result.study.claim(c).text} {result.verdict(c, r)}"
                                  for c in result.changed(r)) + ")"
                      for result, r in changed)
    verb = "changes" if len(changed) == 1 else "change"
    return (f"{len(changed)} of the {total} other readings {verb} a claim's verdict: "
            f"{named}; the other {total - len(changed)} change none")


def run_readings(study, n_seeds=200, seed=0, progress=True):
    """Runs a study's learner with the book's readings and with each other reading
    (`readings`), one at a time, all on the same seeds, and measures its claims.

    Args:
      study: "goal_oriented", "actor_critic" or "rod_toppling" (see `STUDIES`), or a
        `Study`.
      n_seeds: seeds per run (>= 1; the book uses 200).
      seed: the root seed (an integer >= 0, a Generator or None).
      progress: show a progress bar over the runs.

    Returns:
      A `ReadingsResult`.

    Raises:
      ValueError: for an unknown study or a bad n_seeds or seed.
    """
    study = _check_study(study)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    seed = _validate.root_seed("seed", seed)
    _validate.boolean("progress", progress)
    found = readings(study)
    runs, held = {}, {}
    for reading in progress_bar([None] + list(found), len(found) + 1,
                                f"other readings: {study.name}", progress, unit="run"):
        point = {} if reading is None else {reading.name: reading.value}
        key = None if reading is None else reading.key
        runs[key] = study.run_fn(n_seeds=n_seeds, seed=seed, progress=False, **study.fixed,
                                 **point)
        rows = study.per_seed(runs[key])
        held[key] = {c.name: np.array([row[c.name] for row in rows], dtype=bool)
                     for c in study.claims}
    return ReadingsResult(study, {"n_seeds": n_seeds, "seed": seed}, found, runs, held)


CHAPTER_CLAIMS = {
    "weight_threshold": "red first fails at every action weight below a threshold and "
                        "holds at every weight from it",
    "weight_above_settles_red": "above that threshold red comes first at every point of the "
                                "map, whatever the presses and the reading",
    "interest_needs_progress": "interest moves to green later with the progress reading "
                               "and fails with the literal one",
    "interest_weight_from": "interest moves to green later from some action weight on, "
                            "and not at the lowest weight tried",
    "interest_progress_any_presses": "with the progress reading and a weight from the "
                                     "threshold, interest moves later for every number of "
                                     "presses",
    "green_needs_two_presses": "green is mastered at every point but those with the fewest "
                               "presses per trial, where it fails",
    "critic_red_everywhere": "the actor-critic predicts red well first at every point",
    "printed_td_alone": "with the printed TD error and the other defaults, the actor-critic "
                        "predicts red well first and learns green",
    "printed_td_damage": "with the printed TD error, green fails with the weakest predictor "
                         "and with the fewest presses, where the standard one does not fail",
    "td_interacts": "the TD error interacts with the action weight and with the presses "
                    "for green",
    "rods_toppled_first_everywhere": "red toppled first fails at no point of the map",
    "rods_small_initial_q": "red is predicted well first only for initial values between "
                            "the smallest and the largest tried",
    "rods_epsilon": "red predicted well first holds at an epsilon other than the default, "
                    "and not at the largest tried",
    "rods_blue_needs_drive": "blue is found at every point with an initial Q above zero, "
                             "whatever epsilon, and fails with no initial Q and no random "
                             "moves (the chapter gives the other epsilons at no initial Q "
                             "by their shares and verdicts, not as a claim)",
    "presses_not_needed": "red first and the interest's order hold at every number of "
                          "presses tried",
}
"""The claims of the chapter "What the result depends on" about its maps
(`chapter_claims`)."""
BOLD_CLAIMS = {
    "Above the threshold, red comes first at every point of the maps, whatever the "
    "presses and the reading.": ("weight_above_settles_red", "all"),
    "Red is predicted well first at every point of these maps": ("critic_red_everywhere",
                                                                 "all"),
}
"""The bold claims of the chapter "What the result depends on" that use a word of
strength (book/_ext/claim_words.py), each with the claim of `CHAPTER_CLAIMS` that
checks it and the kind of that check: "all", every point's verdict "holds" (a claim
that must hold at every point of a map is the conjunction of the points' own tests,
which needs no correction for their number: it fails if any one fails)."""


def _every(result, claim, verdict_, **where):
    """Whether `claim` has the verdict `verdict_` at every measured point of `result`
    whose settings satisfy `where` ({setting: function of its value -> bool})."""
    table = result.points()
    for name, test in where.items():
        table = table[table[name].map(test)]
    return bool(len(table)) and bool((table[claim + "_verdict"] == verdict_).all())


def chapter_claims(goal, critic, rods_result):
    """{claim name: whether it holds}, for each of `CHAPTER_CLAIMS`: what the chapter
    "What the result depends on" states in words about its three maps, checked on the
    book's maps when it is built (and by the tests on theirs).

    Args:
      goal, critic, rods_result: the `RobustnessResult` objects of the studies
        "goal_oriented", "actor_critic" and "rod_toppling".
    """
    for name, result, study in (("goal", goal, "goal_oriented"), ("critic", critic,
                                "actor_critic"), ("rods_result", rods_result, "rod_toppling")):
        _validate.instance(name, result, RobustnessResult)
        if result.study.name != study:
            raise ValueError(f"{name} must be the study {study!r}, got "
                             f"{result.study.name!r}")
    weights = goal.study.setting("action_weight").values
    presses = goal.study.setting("presses_per_trial").values
    threshold = goal.holds_from("red_first", "action_weight")
    below = [w for w in weights if threshold is None or w < threshold]
    interest_from = goal.holds_from("interest_later", "action_weight")
    critic_weights = critic.study.setting("action_weight").values
    critic_presses = critic.study.setting("presses_per_trial").values
    qs = list(rods_result.study.setting("initial_q").values)
    epsilons = rods_result.study.setting("epsilon").values
    q_held = rods_result.holding_values("red_first", "initial_q")
    epsilon_held = rods_result.holding_values("red_first", "epsilon")
    default_epsilon = rods_result.study.setting("epsilon").default
    return {
        "weight_threshold": threshold is not None and bool(below) and all(
            goal.verdict("red_first", action_weight=w) == "fails" for w in below),
        "weight_above_settles_red": threshold is not None and _every(
            goal, "red_first", "holds", action_weight=lambda w: w >= threshold),
        "interest_needs_progress": goal.verdict("interest_later") == "holds"
        and goal.verdict("interest_later", reading="literal") == "fails",
        "interest_weight_from": interest_from is not None and interest_from > weights[0],
        "interest_progress_any_presses": threshold is not None and _every(
            goal, "interest_later", "holds", action_weight=lambda w: w >= threshold,
            reading=lambda r: r == "progress"),
        "green_needs_two_presses": _every(goal, "green_mastered", "fails",
                                          presses_per_trial=lambda p: p == presses[0])
        and _every(goal, "green_mastered", "holds",
                   presses_per_trial=lambda p: p != presses[0]),
        "critic_red_everywhere": _every(critic, "red_first", "holds"),
        "printed_td_alone": critic.verdict("red_first", variant="printed_td") == "holds"
        and critic.verdict("green_learned", variant="printed_td") == "holds",
        "printed_td_damage": all(
            critic.verdict("green_learned", variant="printed_td", **point) == "fails"
            and critic.verdict("green_learned", **point) != "fails"
            for point in ({"action_weight": critic_weights[0]},
                          {"presses_per_trial": critic_presses[0]})),
        "td_interacts": critic.interacts("green_learned", ("action_weight", "variant"))
        and critic.interacts("green_learned", ("presses_per_trial", "variant")),
        "rods_toppled_first_everywhere": not (rods_result.points()["red_toppled_first_verdict"]
                                              == "fails").any(),
        "rods_small_initial_q": bool(q_held) and q_held[0] != qs[0]
        and q_held[-1] != qs[-1]
        and q_held == qs[qs.index(q_held[0]):qs.index(q_held[-1]) + 1],
        "rods_epsilon": any(e != default_epsilon for e in epsilon_held)
        and epsilons[-1] not in epsilon_held,
        "rods_blue_needs_drive": _every(rods_result, "blue_found", "holds",
                                        initial_q=lambda q: q > 0)
        and rods_result.verdict("blue_found", initial_q=qs[0], epsilon=epsilons[0])
        == "fails" and qs[0] == 0 and epsilons[0] == 0,
        "presses_not_needed": all(goal.verdict(c, presses_per_trial=p) == "holds"
                                  for c in ("red_first", "interest_later") for p in presses),
    }


def chapter_numbers(goal, critic, rods_result):
    """The numbers and clauses the chapter "What the result depends on" quotes from
    its three maps, by the names its text uses.

    Args:
      goal, critic, rods_result: the `RobustnessResult` objects of the studies
        "goal_oriented", "actor_critic" and "rod_toppling".

    Returns:
      (numbers, clauses): two dicts, {name: a number or a word} and {name: a clause in
      Markdown}. Each study's `summary()` is there too, its keys prefixed with the study
      (``goal_``, ``critic_``, ``rods_``).
    """
    chapter_claims(goal, critic, rods_result)  # checks the arguments
    numbers, clauses = {}, {}
    for prefix, result in (("goal_", goal), ("critic_", critic), ("rods_", rods_result)):
        numbers.update({prefix + k: v for k, v in result.summary().items()})
    # The goal-oriented learner.
    weight = goal.study.setting("action_weight")
    presses = goal.study.setting("presses_per_trial").values
    threshold = goal.holds_from("red_first", "action_weight")
    above = goal.points().query("action_weight >= @threshold")
    numbers.update(
        default_weight=weight.default, goal_lowest_weight=threshold,
        goal_highest_failing_weight=max(w for w in weight.values if w < threshold),
        goal_red_first_above_min=float(above.red_first.min()),
        goal_later_progress_min=float(above.query("reading == 'progress'")
                                      .interest_later.min()),
        lowest_weight=weight.values[0],
        goal_later_lowest_weight=goal.share("interest_later",
                                            action_weight=weight.values[0])[0],
        goal_later_lowest_weight_verdict=goal.verdict("interest_later",
                                                      action_weight=weight.values[0]),
        goal_later_literal=goal.share("interest_later", reading="literal")[0],
        goal_later_weights_lowest=goal.holds_from("interest_later", "action_weight"),
        presses_low=min(presses), presses_high=max(presses),
        goal_green_one_press=goal.share("green_mastered", presses_per_trial=min(presses))[0],
        goal_presses_in_run=min(presses) * goal.study.fixed["n_trials"])
    clauses["goal_red_first_by_weight"] = goal.shares_along("red_first", "action_weight")
    # The actor-critic.
    weakest = critic.study.setting("action_weight").values[0]
    fewest = critic.study.setting("presses_per_trial").values[0]
    numbers.update(critic_weakest=weakest, critic_fewest=fewest)
    for name, point in (("printed", {"variant": "printed_td"}),
                        ("printed_weakest", {"variant": "printed_td", "action_weight": weakest}),
                        ("printed_fewest", {"variant": "printed_td",
                                            "presses_per_trial": fewest}),
                        ("weakest", {"action_weight": weakest}),
                        ("fewest", {"presses_per_trial": fewest})):
        numbers[f"critic_green_{name}"] = critic.share("green_learned", **point)[0]
    # The Q-learner on the rods.
    qs = rods_result.study.setting("initial_q").values
    epsilon = rods_result.study.setting("epsilon")
    held = rods_result.holding_values("red_first", "initial_q")
    numbers.update(
        rods_q_lowest=min(held), rods_q_highest=max(held), rods_q_none=qs[0],
        rods_epsilon_default=epsilon.default, rods_epsilon_largest=epsilon.values[-1],
        rods_epsilon_largest_verdict=rods_result.verdict("red_first",
                                                         epsilon=epsilon.values[-1]),
        rods_blue_positive_q_min=float(rods_result.points().query("initial_q > 0")
                                       .blue_found.min()))
    clauses.update(
        rods_red_first_by_q=rods_result.shares_along("red_first", "initial_q"),
        rods_red_first_by_epsilon=rods_result.shares_along("red_first", "epsilon"),
        rods_blue_q_none_by_epsilon=rods_result.shares_along("blue_found", "epsilon",
                                                             initial_q=qs[0]))
    toppled = rods_result.points()["red_toppled_first_verdict"]
    holds = int((toppled == "holds").sum())
    clauses["rods_toppled_first_points"] = (
        f"it holds at every one of the {len(toppled)} points" if holds == len(toppled) else
        f"it holds at {holds} of the {len(toppled)} points and is unclear at the others")
    # The fewest seeds, in words ("in every seed" rather than "in at least 100.0%").
    for name in ("goal_red_first_above_min", "critic_red_first_min",
                 "rods_red_toppled_first_min", "rods_blue_positive_q_min"):
        clauses[name.replace("_min", "_in")] = in_seeds(numbers[name])
    return numbers, clauses


def readings_numbers(found):
    """The numbers and clauses the chapter "What the result depends on" quotes from
    its other readings, by the names its text uses.

    Args:
      found: {study name: `ReadingsResult`}, for the three studies.

    Returns:
      (numbers, clauses), as `chapter_numbers`: per study its `describe()`; over
      all of them `readings_summary`; for the rods, the book's run, the run without a
      limit on moves and the run whose moves off the grid end the episode: the share
      of episodes that end on the time limit, of moves that run into the edge, of
      episodes that end there, the mean and the longest episode, and Figure 7's
      story and order (`RodTopplingResult.tells_the_papers_story`, `in_paper_order`).
    """
    if not isinstance(found, dict) or set(found) != set(STUDIES):
        raise _validate.ArgumentTypeError(f"found must be a dict of ReadingsResult by "
                                          f"study name ({', '.join(STUDIES)}), got "
                                          f"{_validate.show(found)}")
    for name, result in found.items():
        _validate.instance(f"found[{name!r}]", result, ReadingsResult)
    clauses = {f"readings_{name}": result.describe() for name, result in found.items()}
    clauses["readings_summary"] = readings_summary(list(found.values()))
    clauses["not_measured_epsilon"] = NOT_MEASURED[("actor_critic", "epsilon")]
    rod_runs = found["rod_toppling"]
    book = rod_runs.run()
    numbers = {"max_moves": book.settings["max_moves"],
               "time_limit_share": book.time_limit_share(), "edge_share": book.edge_share(),
               "edge_ended_share": rod_runs.run(("off_grid", "end")).edge_ended_share()}
    for name, run in (("book", book), ("no_limit", rod_runs.run(("max_moves", None))),
                      ("off_grid_ends", rod_runs.run(("off_grid", "end")))):
        numbers[f"{name}_length"] = float(run.episode_length.mean())
        numbers[f"{name}_longest"] = int(run.episode_length.max())
        numbers[f"{name}_order"] = run.red_before_blue_begins()
        numbers[f"{name}_story"] = float(run.tells_the_papers_story().mean())
    return numbers, clauses
