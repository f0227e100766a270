"""The study "robustness": what the paper's results depend on, the settings the paper
does not publish swept one pair at a time, with the paper's claims measured at every
grid point (`python -m icm study robustness`: one map point and its seeds a unit).

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
time in `icm.studies.readings`; the chapter's claims, tables and numbers are in
`icm.chapters.robustness`.
"""

import dataclasses

import numpy as np

from icm import _validate
from icm.envs import buttons, rods
from icm.experiments.actor_critic import run_actor_critic
from icm.experiments.goal_oriented import CHAPTER_TRIALS, run_goal_oriented
from icm.experiments.goal_oriented_results import TASKS
from icm.experiments.rod_episodes import WELL_PREDICTED_ERROR
from icm.experiments.rod_toppling import run_rod_toppling
from icm.experiments.sweep import run_point, sweep
from icm.stats import comes_first, share_interval, verdict
from icm.studies import registry
from icm.studies.maps import RobustnessResult

CLAIM_SHARE = 0.9
"""The share of seeds in which an order or a learning claim must hold ("red mastered
first in at least 90% of seeds"). The paper gives no share: it reports an order as what
its learner does, so nearly every run must show it; one in ten may go otherwise."""
MAJORITY = 0.5
"""The share of seeds for "interest moves to the hard task later", which the paper
states "on average" (its Figure 5 averages the interest of many trials), leaving room
for runs that go the other way: it must hold in at least half of the runs."""


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
      text: the claim in words, short (the maps' titles, the tables' columns).
      threshold: the share of seeds in which it must hold.
      meaning: when it holds in one run, in words (the chapter's table of claims).
    """

    name: str
    text: str
    threshold: float
    meaning: str


@dataclasses.dataclass(frozen=True)
class Study:
    """One learner's settings and claims, and how to run it.

    Attributes:
      name: the study's key in `STUDIES`.
      title: the learner and its task, in words, with the paper's figure it rebuilds.
      short: the learner alone, for the tables' rows.
      run_fn: the experiment (`run_goal_oriented`, ...).
      fixed: arguments held fixed in every run (the run length of its chapter).
      settings: the swept settings (`Sweep` objects).
      claims: the measured claims (`Claim` objects).
      per_seed: the function that turns a run into one dict per seed with a boolean
        column per claim (the `per_seed` argument of `sweep`).
    """

    name: str
    title: str
    short: str
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


def _study(name, title, short, run_fn, fixed, settings, claims, per_seed):
    return Study(name, title, short, run_fn, dict(fixed),
                 tuple(_sweep(run_fn, n) for n in settings),
                 tuple(Claim(*c) for c in claims), per_seed)


STUDIES = {
    "goal_oriented": _study(
        "goal_oriented", "goal-oriented learner, button console (the paper's Figure 5)",
        "goal-oriented learner", run_goal_oriented, {"n_trials": CHAPTER_TRIALS},
        ("action_weight", "presses_per_trial", "reading"),
        [("red_first", "red mastered first", CLAIM_SHARE,
          "red is mastered (the predictor right about red's box for every press and "
          "layout, for good) at an earlier trial than green; a red never mastered does "
          "not count"),
         ("interest_later", "interest moves to green later", MAJORITY,
          "the interest-weighted mean trial is later for green than for red (a run with "
          "no interest in one of them does not count)"),
         ("green_mastered", "green mastered too", CLAIM_SHARE,
          "green is mastered within the run")],
        goal_oriented_claims),
    "actor_critic": _study(
        "actor_critic", "intrinsic actor-critic, button console (the paper's Figure 6)",
        "actor-critic", run_actor_critic, {"n_trials": 100},
        ("action_weight", "presses_per_trial", "variant"),
        [("red_first", "red predicted well first", CLAIM_SHARE,
          "red's prediction error reaches 0 for good (to the end of the run) at an "
          "earlier trial than green's"),
         ("green_learned", "green predicted well too", CLAIM_SHARE,
          "green's prediction error reaches 0 for good within the run")],
        actor_critic_claims),
    "rod_toppling": _study(
        "rod_toppling", "Q-learner on the rods (the paper's Figure 7)",
        "Q-learner on the rods", run_rod_toppling, {"n_episodes": 300},
        ("initial_q", "epsilon"),
        [("red_toppled_first", "red toppled first", CLAIM_SHARE,
          "the first topple of red comes before the first of blue"),
         ("red_first", "red predicted well first", CLAIM_SHARE,
          f"red's error is below {WELL_PREDICTED_ERROR:g} on every move that topples it, "
          f"found or not (chapter 5's reading \"all\"), from an earlier episode than "
          f"blue's"),
         ("blue_found", "blue found", CLAIM_SHARE,
          "the run topples blue at least once")],
        rod_claims),
}
"""The three learners' studies, by name."""


def check_study(study):
    """The `Study` named `study` (one of `STUDIES`), or `study` itself if it is one."""
    if isinstance(study, Study):
        return study
    return STUDIES[_validate.one_of("study", study, tuple(STUDIES))]


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


# --- the study "robustness": one map point and its seeds a unit ---------------------

ROBUSTNESS_SEED = 0
"""The root seed of the maps' runs (that of `run_robustness`'s default)."""


def units(settings):
    """The study's units: [learner (a key of `STUDIES`), first setting, its value, second setting, its value]
    for every point of every pair's map of every learner (`pair_grids`)."""
    out = []
    for name, study in STUDIES.items():
        for (a, b), grid in pair_grids(study):
            out.extend([name, a, va, b, vb] for va in grid[a] for vb in grid[b])
    return out


def run_unit(settings, unit):
    """One map point and its block of seeds: the rows `run_robustness`'s sweep keeps for
    it (the point, `seed_index`, a boolean per claim)."""
    name, a, va, b, vb = unit
    study = STUDIES[name]
    others = {n: v for n, v in study.defaults().items() if n not in (a, b)}
    fixed = {**study.fixed, **others}
    if settings.get("length") is not None:
        key = "n_trials" if "n_trials" in fixed else "n_episodes"
        fixed[key] = settings["length"]
    return registry.plain(run_point(study.run_fn, settings["seeds"], ROBUSTNESS_SEED,
                                    fixed, {a: va, b: vb}, per_seed=study.per_seed))


SEED_SECONDS = 0.0005
"""CPU seconds a seed of one map point costs, roughly, at its chapter's run length, in
proportion to the length: the 76 points at 200 seeds took 0.04 to 0.08 s each
(2026-12-05)."""


def unit_seconds(settings, unit):
    """A rough figure of one unit's CPU seconds (`SEED_SECONDS`): `Study.unit_seconds`."""
    fixed = STUDIES[unit[0]].fixed
    chapter = fixed.get("n_trials", fixed.get("n_episodes"))
    length = 1.0 if settings.get("length") is None else settings["length"] / chapter
    return SEED_SECONDS * settings["seeds"] * length


def assemble(settings, units, results):
    """The study's file: {"n_seeds", "seed", "length", "maps": {learner: {"a|b": rows}}}."""
    maps = {}
    for (name, a, _, b, _), rows in zip(units, results):
        maps.setdefault(name, {}).setdefault(f"{a}|{b}", []).extend(rows)
    return {"n_seeds": settings["seeds"], "seed": ROBUSTNESS_SEED,
            "length": settings.get("length"), "maps": maps}


def results_of(data):
    """The `RobustnessResult` of each learner from a robustness study's dict (as
    `python -m icm study robustness` writes it): {name: result}."""
    import pandas as pd

    return {name: RobustnessResult(
                STUDIES[name], {"n_seeds": data["n_seeds"], "seed": data["seed"]},
                {tuple(pair.split("|")): pd.DataFrame(rows) for pair, rows in maps.items()})
            for name, maps in data["maps"].items()}


registry.register(registry.Study(
    name="robustness",
    description="the maps of what the results depend on: every pair of each learner's "
                "unpublished settings (icm.studies.robustness), one map point and its "
                "seeds a unit",
    seeds=(200, "per map point, the same at every point"),
    options={"length": (0, 0, "trials (episodes on the rods) per run; 0: each "
                              "learner's chapter's")},
    units=units, run_unit=run_unit, assemble=assemble, unit_seconds=unit_seconds,
    seeding=(f"every map point runs seeds 0..n-1 of root seed {ROBUSTNESS_SEED} "
             "(the same seeds at every point, as in robustness.run_robustness)"),
    check=lambda settings: {**settings, "length": settings["length"] or None}))
