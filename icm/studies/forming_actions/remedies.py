"""The studies "remedies" and "remedies-replication": the longer runs of "Growing up, and
being shown", the second half of the chapter "Forming actions": the paper's two
remedies for exploration that takes too long, maturational constraints and a teacher,
against the three strategies, all on the same seeds and budget, kept in
assets/remedies_study.json because they take minutes (`python -m icm study remedies`,
about an hour and a quarter of CPU); and the conditions its claims compare, on the
chapter's fresh root, for the replications (assets/remedies_fresh_runs.json, `python
-m icm study remedies-replication`). One seed of one condition is a unit
(`run_condition`, the arm's run of `arms.run_arm`). `load_study`, `pooled`,
`seed_values`, `study_times` and `load_fresh_runs` read what the chapter quotes; the
split of the teacher's test error (`run_test_error_split`, assets/remedies_test_error.json)
is read by `load_test_error_split`.
"""

import json

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.experiments import babbling_results, babbling_space, formed_actions, goal_babbling
from icm.experiments.seeding import REPLICATION_ROOTS
from icm.store import asset_path
from icm.studies.forming_actions.arms import (ARMS, EARLY, FORMED_TRIALS, HELD_OUT_ROOTS,
                                              ROLLOUTS, SEEDING, TUNING_ROOTS,
                                              assemble_roots, budgets_of, join_entries,
                                              run_arm, unit_seconds)
from icm.studies.registry import Study, register

STUDY_FILE = "remedies_study.json"
"""The file in assets/ that holds the study."""
CONDITIONS = {label: ARMS[label] for label in (
    "random motor babbling", "random goal babbling", "learning progress", "growing up",
    "shown button 2", "shown buttons 0 and 4", "shown all five")}
"""The conditions compared, by label (`arms.ARMS`: the `run_goal_babbling` arguments
that differ from its defaults)."""
ROOTS = TUNING_ROOTS + HELD_OUT_ROOTS
"""Root seeds on which every condition runs (the maturation's settings were chosen on
the tuning roots, the first two)."""
N_SEEDS = 20
"""Seeds per root seed (80 per condition). The first 10 of each root were computed
first, in one process; the next 10 on the sweep engine, one seed a unit; seed i of a
root is the same either way."""
TEACHING = ("shown button 2", "shown buttons 0 and 4", "shown all five")
"""The conditions with a teacher, fewest buttons shown first."""
REACH_MOVEMENTS = 1000
"""Random movements per share of the joint range in the study's `touch_shares`."""
REACH_SEED = 0
"""Their seed."""
MEASURES = ("pressed", "first_press", "test_error", "loop", "maturity", "coverage")
"""What a condition's entry keeps (`arms.run_arm`)."""


def run_reach(n_movements=REACH_MOVEMENTS):
    """How often random movements touch the console for each reachable range of
    `babbling_space.RANGE_SHARES` (`babbling_space.touch_shares` with `n_movements`
    movements per share, `REACH_MOVEMENTS` in the study, seed `REACH_SEED`): the
    study's "reach"."""
    return babbling_space.touch_shares(babbling_space.RANGE_SHARES, n_movements, REACH_SEED)


def run_condition(label, root, n_seeds=N_SEEDS, progress=False, first_run=0, threads=None,
                  n_rollouts=goal_babbling.DEFAULT_N_ROLLOUTS,
                  n_trials=formed_actions.DEFAULT_TRIALS):
    """Runs one condition on seeds first_run to first_run + n_seeds - 1 of one root seed
    and returns its entry of the study (`arms.run_arm` with `MEASURES`): "pressed"
    [seed][budget][button] (0 or 1, budgets `BUDGETS`), "first_press" [seed][button]
    (`GoalBabblingResult.first_presses`, -1 for never), "test_error" [seed] (final),
    "red_first" [seed] (0 or 1) and "as_scripted" [seed] (the goal-oriented learner on
    the formed presses, seeded with the root seed), "maturity" [seed][budget] (the
    maturational clock at the budgets), and "coverage" {"early": ..., "all": ...}
    (`arms.coverage_counts` over the first `EARLY` rollouts and over all, summed over
    the seeds). The arguments are `run_arm`'s; `label` a key of `CONDITIONS`."""
    label = _validate.one_of("label", label, tuple(CONDITIONS))
    return run_arm(label, root, MEASURES, n_seeds, progress, first_run, threads, n_rollouts,
                   n_trials)


def _check(settings):
    n_roots = len(ROOTS)
    if settings["seeds"] % n_roots:
        raise ValueError(f"seeds must be a multiple of the {n_roots} root seeds "
                         f"{list(ROOTS)} (the same number of seeds on each), got "
                         f"{settings['seeds']}")
    return settings


def units(settings):
    """The study's units: ["reach"], then [condition, root, i, 1] for each seed of each
    root of each condition (with seeds imported from an earlier file, their block
    first: [condition, root, 0, k])."""
    per_root = settings["seeds"] // len(ROOTS)
    kept = settings.get("imported_seeds", 0)
    out = [["reach"]]
    for label in CONDITIONS:
        for root in ROOTS:
            if kept:
                out.append([label, root, 0, kept])
            out.extend([label, root, i, 1] for i in range(kept, per_root))
    return out


def run_unit(settings, unit):
    """One unit of `units`: `run_reach`, or `run_condition` of its seeds."""
    if unit == ["reach"]:
        return run_reach(settings["reach_movements"])
    label, root, first, n = unit
    return run_condition(label, root, n_seeds=n, first_run=first, threads=1,
                         n_rollouts=settings["rollouts"], n_trials=settings["trials"])


def assemble(settings, units, results):
    """The study's file from its units' results: {"budgets", "n_seeds" (per root seed),
    "n_rollouts", "n_trials", "runs": {condition: {root: entry}}, "reach"}."""
    study = {"budgets": list(budgets_of(settings["rollouts"])),
             "n_seeds": settings["seeds"] // len(ROOTS),
             "n_rollouts": settings["rollouts"], "n_trials": settings["trials"], "runs": {}}
    done = {json.dumps(u): r for u, r in zip(units, results)}
    study["reach"] = done[json.dumps(["reach"])]
    study["runs"] = assemble_roots(units, results, {label: ROOTS for label in CONDITIONS})
    return study


register(Study(
    name="remedies",
    description="growing up and being shown against the three strategies "
                "(icm.studies.forming_actions.remedies; assets/remedies_study.json)",
    seeds=(80, "per condition, spread evenly over the root seeds 100, 200, 300, 400"),
    options={"rollouts": ROLLOUTS, "trials": FORMED_TRIALS,
             "reach_movements": (REACH_MOVEMENTS, 1,
                                 "random movements per range share in 'reach'")},
    units=units, run_unit=run_unit, assemble=assemble, seeding=SEEDING, check=_check,
    unit_seconds=unit_seconds))


def load_study():
    """The study, read from assets/remedies_study.json: {"budgets": [...], "n_seeds": (per
    root seed), "n_rollouts": ..., "reach": `run_reach()`, "runs": {label: {root:
    entry}}} (entries as `run_condition` returns them for all the seeds of a root;
    roots as strings, as JSON keys are), and "produced_by" (`icm.studies.engine`:
    the settings, versions, seeds and units that produced it)."""
    return json.loads(asset_path(STUDY_FILE).read_text())


RUN_LOG = STUDY_FILE + ".runs.jsonl"
"""The file in assets/ that records the runs that wrote the study (one JSON line per
run: backend, workers, wall seconds, every unit's CPU seconds; see
`icm.studies.engine.run_study`)."""


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


def unit_cpu_seconds():
    """The median CPU-seconds of one run of one seed of one condition, over the units
    of the study's last run (`RUN_LOG`): what a replication's runs cost."""
    runs = [json.loads(line) for line in asset_path(RUN_LOG).read_text().splitlines()
            if line.strip()]
    return float(np.median([c for c in runs[-1]["unit_cpu_seconds"] if c > 0]))


def check_study(study):
    """`study` if it is a study dict (as `load_study` returns it), else raises an
    `ArgumentTypeError`."""
    if not isinstance(study, dict) or not {"runs", "budgets", "n_seeds"} <= set(study):
        raise _validate.ArgumentTypeError(f"study must be a study dict (from icm.studies."
                                          f"forming_actions.remedies.load_study), got "
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
"""What `seed_values` measures (and `icm.chapters.forming_actions.remedies.paired_difference`
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


CLAIMED = ("learning progress", "growing up") + TEACHING
"""The conditions the chapter's claims compare (all but the two random strategies),
whose runs on the fresh root `FRESH_FILE` keeps."""
FRESH_FILE = "remedies_fresh_runs.json"
"""The file in assets/ that keeps the runs of `CLAIMED` on the first `POWERED_SEEDS`
seeds of the chapter's fresh root (the study "remedies-replication", one entry per
seed): the replications (`icm.chapters.forming_actions.family.run_replications`) and
the test of the chapter's claims on fresh seeds read them; the tests rerun the last
seed of each condition and expect the same numbers."""
POWERED_SEEDS = 40
"""Seeds per condition at which every clear verdict's replication has a power of at
least 0.9 (about 19, 30 and 34 are needed for the three weakest verdicts at 8 seeds,
`stats.seeds_for_power`; see `icm.chapters.forming_actions.family.REPLICATION_SEEDS`):
five conditions (`CLAIMED`), 200 runs of one seed, about 1,000 CPU-seconds (`python -m
icm study remedies-replication --seeds 40 --jobs 1 --out FILE`, which resumes from its
journal; then copy FILE and its run log over `FRESH_FILE` and run `python -m
icm.chapters.replicate forming_actions`)."""


def replication_units(settings):
    """The units of the study "remedies-replication": one seed of one condition of
    `CLAIMED` on the chapter's fresh root, [label, root, i, 1] for i below
    settings["seeds"]."""
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


register(Study(
    name="remedies-replication",
    description="the conditions the chapter 'Forming actions' claims about, on its fresh "
                "root 9001, one seed a unit (icm.studies.forming_actions.remedies."
                "FRESH_FILE; assets/remedies_fresh_runs.json)",
    seeds=(POWERED_SEEDS, "per condition, on the fresh root 9001"),
    options={"rollouts": ROLLOUTS, "trials": FORMED_TRIALS},
    units=replication_units, run_unit=replication_unit, assemble=assemble_replication,
    seeding=SEEDING, unit_seconds=unit_seconds))


def load_fresh_runs():
    """The runs `FRESH_FILE` keeps, as `icm.chapters.forming_actions.family.fresh_runs`
    returns them (a study of the one fresh root, each condition's seeds joined into one
    entry): what the replications and the test of the chapter's claims on fresh seeds
    read."""
    kept = json.loads(asset_path(FRESH_FILE).read_text())
    return {"n_seeds": kept["n_seeds"], "roots": [kept["root"]],
            "runs": {label: {str(kept["root"]): join_entries(entries)}
                     for label, entries in kept["runs"].items()}}


TEST_ERROR_FILE = "remedies_test_error.json"
"""The file in assets/ that holds `run_test_error_split` (`python -m
icm.studies.forming_actions.remedies` writes it; a test reruns two seeds)."""

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


def run_test_error_split(roots=HELD_OUT_ROOTS, n_seeds=N_SEEDS, progress=False):
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


def main():
    """`python -m icm.studies.forming_actions.remedies`: runs `run_test_error_split` and
    writes assets/remedies_test_error.json."""
    from icm.store import ASSETS, write_text

    path = ASSETS / TEST_ERROR_FILE
    write_text(path, json.dumps(run_test_error_split(progress=True)) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
