"""The longer runs of "Growing up, and being shown", the second half of the chapter
"Forming actions": the paper's two remedies for exploration that takes too long,
maturational constraints and a teacher, against the three strategies, all on the same
seeds and budget, kept in assets/remedies_study.json because they take minutes.

`run_condition` runs one condition on seeds of one root seed with `run_goal_babbling`
(and `run_formed_actions`); `python -m icm study remedies` (`icm.experiments.studies`)
writes the file on every core or on a Dask cluster, one seed of one condition a unit
(`python -m icm.experiments.remedies_study` with the defaults; about two hours of
CPU); `load_study` reads it; a test reruns the first seeds of some of it (the first k
seeds of a root seed are the same in any larger run) and expects the same numbers.
The chapter's summaries, tables, verdicts and sentences are computed from it in
`icm.chapters.forming_actions`.
"""

import json

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.store import ASSETS, asset_path
from icm.experiments import (babbling_results, babbling_space, formed_actions, goal_babbling,
                             goal_babbling_study)
from icm.experiments.seeding import REPLICATION_ROOTS

STUDY_FILE = "remedies_study.json"
"""The file in assets/ that holds the study."""
CONDITIONS = {
    "random motor babbling": {"strategy": "random_motor"},
    "random goal babbling": {"strategy": "random_goal"},
    "learning progress": {},
    "growing up": {"maturation": "joint_range"},
    "shown button 2": {"demonstrations": (2,)},
    "shown buttons 0 and 4": {"demonstrations": (0, 4)},
    "shown all five": {"demonstrations": (0, 1, 2, 3, 4)},
}
"""The conditions compared, by label: `run_goal_babbling` arguments that differ from
its defaults (learning progress over fixed regions, no maturation, no teacher). One
button shown is the middle one, the one the book's runs of the paper's experiment
light red (`buttons.DEFAULT_RED_BUTTON`; the paper does not say which button is
red); two are the end buttons, 0 and 4 (not the two farthest from the resting
fingertip: button 1 is about as far as button 4)."""
ROOTS = goal_babbling_study.TUNING_ROOTS + goal_babbling_study.HELD_OUT_ROOTS
"""Root seeds on which every condition runs: those of `goal_babbling_study`, which no
test uses (the maturation's settings were chosen on its tuning roots, the first two)."""
N_SEEDS = 20
"""Seeds per root seed (80 per condition). The first 10 of each root were computed
first, in one process; the next 10 on the sweep engine, one seed a unit
(`icm.experiments.studies`); seed i of a root is the same either way."""
BUDGETS = goal_babbling_study.BUDGETS
"""Rollouts after which the presses formed so far are tested (`presses_formed`)."""
EARLY = 200
"""Coverage is also counted over the first this many rollouts."""
COVERAGE_CELL = 0.01
"""The side of a coverage map's cells (m), over the goal space's x and y."""
TEACHING = ("shown button 2", "shown buttons 0 and 4", "shown all five")
"""The conditions with a teacher, fewest buttons shown first."""
REACH_MOVEMENTS = 1000
"""Random movements per share of the joint range in the study's `touch_shares`."""
REACH_SEED = 0
"""Their seed."""


def run_reach(n_movements=REACH_MOVEMENTS):
    """How often random movements touch the console for each reachable range of
    `babbling_space.RANGE_SHARES` (`babbling_space.touch_shares` with `n_movements`
    movements per share, `REACH_MOVEMENTS` in the study, seed `REACH_SEED`): the
    study's "reach"."""
    return babbling_space.touch_shares(babbling_space.RANGE_SHARES, n_movements, REACH_SEED)


def coverage_edges():
    """The edges of a coverage map's cells: (x edges, y edges), `COVERAGE_CELL` apart
    over the goal space (`babbling_space.GOAL_LOW` to `GOAL_HIGH`)."""
    low, high = babbling_space.GOAL_LOW, babbling_space.GOAL_HIGH
    return tuple(np.linspace(low[i], high[i], int(round((high[i] - low[i]) / COVERAGE_CELL)) + 1)
                 for i in (0, 1))


def coverage_counts(result, stop=None):
    """How many of the robot's own rollouts (demonstrations left out) ended with the
    finger on the console or a cap, per cell of the console seen from above, over
    every seed of `result` and its first `stop` rollouts (all by default): an int
    array [x cell, y cell] (`coverage_edges`)."""
    stop = result.n_rollouts if stop is None else stop
    start = result.n_demonstrations
    points = result.outcomes[:, start:stop].reshape(-1, 3)
    touched = result.touched[:, start:stop].reshape(-1)
    counts, _, _ = np.histogram2d(points[touched, 0], points[touched, 1],
                                  bins=coverage_edges())
    return counts.astype(np.int64)


# The budgets at which a run tests its presses: the goal-babbling study's own function,
# since this study's BUDGETS are that study's.
budgets_of = goal_babbling_study.budgets_of


def run_condition(label, root, n_seeds=N_SEEDS, progress=False, first_run=0, threads=None,
                  n_rollouts=goal_babbling.DEFAULT_N_ROLLOUTS,
                  n_trials=formed_actions.DEFAULT_TRIALS):
    """Runs one condition on seeds first_run to first_run + n_seeds - 1 of one root seed
    and returns its entry of the study (the first k seeds of a root seed are the same
    in any larger run, so a shorter rerun checks them, and a study can be run one seed
    at a time: `icm.experiments.studies`).

    Args:
      label: a key of `CONDITIONS`.
      root: the root seed (an integer >= 0).
      n_seeds: seeds (>= 1).
      progress: show progress bars.
      first_run: the index of the first seed of the root seed (>= 0).
      threads: threads stepping the physics (as in `run_goal_babbling`; the results
        do not depend on it).
      n_rollouts: rollouts per seed (the study's is the default; fewer make a quick
        trial run, its presses tested at `budgets_of(n_rollouts)`).
      n_trials: trials of the goal-oriented learner on each seed's formed presses
        (`run_formed_actions`; the study's is the default, fewer make a quick trial
        run).

    Returns:
      A dict: "pressed" [seed][budget][button] (0 or 1, budgets `BUDGETS`),
      "first_press" [seed][button] (`GoalBabblingResult.first_presses`, -1 for
      never), "test_error" [seed] (final), "red_first" [seed] (0 or 1) and
      "as_scripted" [seed] (the goal-oriented learner on the formed presses, seeded
      with the root seed), "maturity" [seed][budget] (the maturational clock at the
      budgets), and "coverage" {"early": ..., "all": ...} (`coverage_counts` over
      the first `EARLY` rollouts and over all, summed over the seeds).
    """
    label = _validate.one_of("label", label, tuple(CONDITIONS))
    root = _validate.seed("root", root)
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)  # before the babbling
    arguments = {"strategy": "learning_progress", **CONDITIONS[label]}
    result = goal_babbling.run_goal_babbling(**arguments, n_seeds=n_seeds, seed=root,
                                             progress=progress, first_run=first_run,
                                             threads=threads, n_rollouts=n_rollouts)
    budgets = budgets_of(n_rollouts)
    pressed = formed_actions.presses_formed(result, budgets)  # [budget, seed, button]
    loop = formed_actions.run_formed_actions(result, n_trials=n_trials, seed=root,
                                            progress=progress, first_run=first_run)
    return {"pressed": np.moveaxis(pressed, 0, 1).astype(int).tolist(),
            "first_press": result.first_presses().tolist(),
            "test_error": result.final_test_error().tolist(),
            "red_first": loop.red_first().astype(int).tolist(),
            "as_scripted": loop.as_scripted_per_seed.tolist(),
            "maturity": result.maturity[:, np.array(budgets) - 1].tolist(),
            "coverage": {"early": coverage_counts(result, EARLY).tolist(),
                         "all": coverage_counts(result).tolist()}}


def load_study():
    """The study, read from assets/remedies_study.json: {"budgets": [...], "n_seeds": (per
    root seed), "n_rollouts": ..., "reach": `run_reach()`, "runs": {label: {root:
    entry}}} (entries as `run_condition` returns them for all the seeds of a root;
    roots as strings, as JSON keys are), and "produced_by" (`icm.experiments.studies`:
    the settings, versions, seeds and units that produced it)."""
    return json.loads(asset_path(STUDY_FILE).read_text())


RUN_LOG = STUDY_FILE + ".runs.jsonl"
"""The file in assets/ that records the runs that wrote the study (one JSON line per
run: backend, workers, wall seconds, every unit's CPU seconds; see
`icm.experiments.studies.run_study`)."""


def study_times():
    """How much computing the study file took, from its run log (`RUN_LOG`) and its
    "produced_by": a dict with "seeds_per_condition", "conditions", "units_computed"
    (the units run by the engine; the imported ones, recorded with 0 CPU seconds, are
    not counted), "cpu_hours"
    (their CPU time, summed over the units), "wall_hours" (the runs' wall time),
    "workers" and "backend" (of the last run), and "imported_seeds_per_condition" (the
    seeds kept from the earlier file after the check recorded in "produced_by", 0 if
    none)."""
    study = load_study()
    runs = [json.loads(line) for line in asset_path(RUN_LOG).read_text().splitlines()
            if line.strip()]
    runs = [r for r in runs if r["settings"] == study["produced_by"]["settings"]]
    if not runs:
        raise ValueError(f"{RUN_LOG} has no run of the study's settings "
                         f"{study['produced_by']['settings']}")
    last = runs[-1]
    imported = study["produced_by"].get("imported", {}).get("seeds_per_root", 0)
    computed = [cpu for cpu in last["unit_cpu_seconds"] if cpu > 0]  # imported: 0
    return {"seeds_per_condition": study["n_seeds"] * len(ROOTS),
            "conditions": len(study["runs"]), "units_computed": len(computed),
            "cpu_hours": sum(last["unit_cpu_seconds"]) / 3600,
            "wall_hours": sum(r["wall_seconds"] for r in runs) / 3600,
            "workers": last["n_jobs"], "backend": last["backend"],
            "imported_seeds_per_condition": imported * len(ROOTS)}


def main():
    """Runs the study on every core and writes assets/remedies_study.json
    (`python -m icm study remedies` does the same with more choices: a Dask cluster,
    fewer seeds, ...; a run stopped half-way continues from its journal); with the
    argument "test-error", writes assets/remedies_test_error.json
    (`run_test_error_split`)."""
    import sys

    from icm.experiments import studies

    if sys.argv[1:] == ["test-error"]:
        path = ASSETS / TEST_ERROR_FILE
        path.write_text(json.dumps(run_test_error_split(progress=True)) + "\n")
        print(f"wrote {path}")
        return
    path = ASSETS / STUDY_FILE
    studies.run_study("remedies", path, seeds=N_SEEDS * len(ROOTS))
    print(f"wrote {path}")


def check_study(study):
    """`study` if it is a study dict (as `load_study` returns it), else raises an
    `ArgumentTypeError`."""
    if not isinstance(study, dict) or not {"runs", "budgets", "n_seeds"} <= set(study):
        raise _validate.ArgumentTypeError(f"study must be a study dict (from icm.experiments."
                                          f"remedies_study.load_study), got "
                                          f"{_validate.show(study)}")
    return study


def pooled(study, label, roots=None):
    """One condition's entries over `roots` (default: every root seed it ran on), as
    arrays with the seeds of all of them on the first axis: "pressed" [seed, budget,
    button], "first_press" [seed, button], "test_error", "red_first", "as_scripted"
    [seed], "maturity" [seed, budget], and "coverage" {"early": ..., "all": ...}
    summed over the roots."""
    check_study(study)
    label = _validate.one_of("label", label, tuple(study["runs"]))
    by_root = study["runs"][label]
    roots = list(by_root) if roots is None else [str(r) for r in roots]
    missing = [r for r in roots if r not in by_root]
    if missing:
        raise ValueError(f"roots: the study did not run {label!r} on {missing}")
    entries = [by_root[r] for r in roots]
    out = {key: np.concatenate([np.array(e[key]) for e in entries])
           for key in ("pressed", "first_press", "test_error", "red_first", "as_scripted",
                       "maturity")}
    out["coverage"] = {stretch: sum(np.array(e["coverage"][stretch]) for e in entries)
                       for stretch in ("early", "all")}
    return out


def shown_buttons(label):
    """The buttons the teacher shows in condition `label` (a tuple, empty for none)."""
    label = _validate.one_of("label", label, tuple(CONDITIONS))
    return tuple(CONDITIONS[label].get("demonstrations", ()))


PAIRED_MEASURES = ("all_pressed", "others_formed", "others_pressed_early", "test_error")
"""What `seed_values` measures (and `icm.chapters.forming_actions.paired_difference`
compares): "all_pressed" (1 for a seed with all five presses
formed at the default budget), "others_formed" (how many presses formed among the
buttons the condition's teacher does not show), "others_pressed_early" (how many of
those buttons the robot pressed itself within the first `EARLY` rollouts), and
"test_error" (m)."""


def seed_values(study, label, measure, others_of=None, roots=None):
    """One number per seed of condition `label` (`PAIRED_MEASURES`), over `roots`
    (default all); "the buttons not shown" are those of condition `others_of`
    (default `label`)."""
    measure = _validate.one_of("measure", measure, PAIRED_MEASURES)
    shown = shown_buttons(label if others_of is None else others_of)
    others = [b for b in range(buttons.N_BUTTONS) if b not in shown]
    entry = pooled(study, label, roots)
    pressed = entry["pressed"][:, -1]  # [seed, button] at the default budget
    if measure == "all_pressed":
        return pressed.all(axis=1).astype(float)
    if measure == "others_formed":
        return pressed[:, others].sum(axis=1).astype(float)
    if measure == "others_pressed_early":
        first = entry["first_press"][:, others]
        return ((first > 0) & (first <= EARLY)).sum(axis=1).astype(float)
    return entry["test_error"].astype(float)


POWERED_SEEDS = 40
"""Seeds per condition at which every clear verdict's replication has a power of at
least 0.9 (about 19, 30 and 34 are needed for the three weak ones of
`REPLICATION_SEEDS`, `stats.seeds_for_power`): five conditions (`CLAIMED`), 200 runs
of one seed, about 1,000 CPU-seconds (`python -m icm study remedies-replication --seeds
40 --jobs 1 --out FILE`, `icm.experiments.studies`, which resumes from its journal;
then copy FILE and its run log over `FRESH_FILE`, set `REPLICATION_SEEDS` to 40 and
run `python -m icm.experiments.replication forming_actions`)."""


def unit_cpu_seconds():
    """The median CPU-seconds of one run of one seed of one condition, over the units
    of the study's last run (`RUN_LOG`): what a replication's runs cost."""
    runs = [json.loads(line) for line in asset_path(RUN_LOG).read_text().splitlines()
            if line.strip()]
    return float(np.median([c for c in runs[-1]["unit_cpu_seconds"] if c > 0]))


CLAIMED = ("learning progress", "growing up") + TEACHING
"""The conditions the chapter's claims compare (all but the two random strategies),
whose runs on the fresh root `FRESH_FILE` keeps."""
FRESH_FILE = "remedies_fresh_runs.json"
"""The file in assets/ that keeps the runs of `CLAIMED` on the first
`REPLICATION_SEEDS` seeds of the chapter's fresh root (`run_fresh_seeds`, one entry per
seed): the replications (`run_replications`) and the test of the chapter's claims on
fresh seeds read them. `python -m icm.experiments.replication forming_actions` writes
it, then assets/replications.json from it; the tests rerun the last seed of each
condition and expect the same numbers."""


def replication_units(settings):
    """The units of the study "remedies-replication" (`icm.experiments.studies`): one
    seed of one condition of `CLAIMED` on the chapter's fresh root, [label, root, i, 1]
    for i below settings["seeds"]."""
    root = REPLICATION_ROOTS["forming_actions"]
    return [[label, root, i, 1] for label in CLAIMED for i in range(settings["seeds"])]


def replication_unit(settings, unit):
    """One unit of `replication_units`: `run_condition` of its seed."""
    label, root, first, n = unit
    return run_condition(label, root, n_seeds=n, first_run=first, threads=1,
                         n_rollouts=settings["rollouts"], n_trials=settings["trials"])


def assemble_replication(settings, units, results):
    """The file `FRESH_FILE` from the units' results: {"root", "n_seeds", "runs":
    {label: [entry of each seed, in order]}}."""
    runs = {label: [r for u, r in sorted(zip(units, results), key=lambda p: p[0][2])
                    if u[0] == label] for label in CLAIMED}
    return {"root": REPLICATION_ROOTS["forming_actions"],
            "n_seeds": settings["seeds"], "runs": runs}


def load_fresh_runs():
    """The runs `FRESH_FILE` keeps, as `fresh_runs` returns them (a study of the one
    fresh root, each condition's seeds joined into one entry): what `replicate` and
    the test of the chapter's claims on fresh seeds read."""
    from icm.experiments.studies import join_entries

    kept = json.loads(asset_path(FRESH_FILE).read_text())
    return {"n_seeds": kept["n_seeds"], "roots": [kept["root"]],
            "runs": {label: {str(kept["root"]): join_entries(entries)}
                     for label, entries in kept["runs"].items()}}


TEST_ERROR_FILE = "remedies_test_error.json"
"""The file in assets/ that holds `run_test_error_split` (`python -m
icm.experiments.remedies_study test-error` writes it; a test reruns two seeds)."""
SPLIT_CONDITIONS = ("learning progress",) + TEACHING
"""The conditions whose test error `test_error_split` separates."""


def test_error_split(result):
    """A run's final test error, whole and without the teacher: per seed, "all" (the
    run's `final_test_error`), "own" (the same with the demonstrations left out of the
    movements the robot remembers: each test goal's nearest outcome among its own
    rollouts only) and "own_grid" (that, on the test goals that are not press goals
    alone). Lists of floats (m), one per seed."""
    _validate.instance("result", result, babbling_results.GoalBabblingResult)
    space, weight = result.settings["outcome_space"], result.settings["depth_weight"]
    start = result.n_demonstrations
    reached = babbling_space.outcome_vectors(result.outcomes[:, start:],
                                            result.depths[:, start:], space, weight)
    wanted = babbling_space.goal_outcomes(result.test_goals, space, weight)
    distance = np.sqrt(((reached[:, :, None, :] - wanted[None, None]) ** 2).sum(axis=3))
    nearest = distance.min(axis=1)  # [seed, goal]
    return {"all": result.final_test_error().tolist(),
            "own": nearest.mean(axis=1).tolist(),
            "own_grid": nearest[:, buttons.N_BUTTONS:].mean(axis=1).tolist()}


def run_test_error_split(roots=goal_babbling_study.HELD_OUT_ROOTS, n_seeds=N_SEEDS,
                         progress=False):
    """`test_error_split` of every condition of `SPLIT_CONDITIONS` on the first `n_seeds`
    seeds of each of `roots` (the runs of `run_condition`, the same seeds):
    {"n_seeds", "runs": {label: {root: split}}}."""
    runs = {}
    for label in SPLIT_CONDITIONS:
        arguments = {"strategy": "learning_progress", **CONDITIONS[label]}
        runs[label] = {str(root): test_error_split(goal_babbling.run_goal_babbling(
            **arguments, n_seeds=n_seeds, seed=root, progress=progress)) for root in roots}
    return {"n_seeds": n_seeds, "runs": runs}


def load_test_error_split():
    """`run_test_error_split()` as assets/remedies_test_error.json keeps it."""
    return json.loads(asset_path(TEST_ERROR_FILE).read_text())


if __name__ == "__main__":
    main()
