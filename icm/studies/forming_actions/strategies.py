"""The study "goal-babbling": the longer runs of the first half of the chapter "Forming
actions", every variant of the goal-babbling learner at the default budget on root
seeds that no test uses, kept in assets/goal_babbling_study.json because they take
minutes, not seconds. One seed of one variant is a unit (`run_variant`, the arm's run of
`arms.run_arm`); `python -m icm study goal-babbling` writes the file on every core or
on a Dask cluster (about 15 minutes of CPU); `load_study` reads it, and `summary`,
`pool`, `tuning` and `failure_counts` read what the chapter quotes from it; a test
reruns the first seeds of some of it (the first k seeds of a root seed are the same in
any larger run) and expects the same numbers.
"""

import json

import numpy as np

from icm import _validate
from icm.experiments import formed_actions, goal_babbling
from icm.store import asset_path
from icm.studies.forming_actions.arms import (ARMS, FORMED_TRIALS, HELD_OUT_ROOTS,
                                              ROLLOUTS, SEEDING, TUNING_ROOTS,
                                              assemble_roots, budgets_of, run_arm,
                                              unit_seconds)
from icm.studies.registry import Study, register

STUDY_FILE = "goal_babbling_study.json"
"""The file in assets/ that holds the study."""
VARIANTS = {label: ARMS[label] for label in (
    "learning progress", "where the finger stopped only", "depth weight 1",
    "depth weight 3", "LWLR inverse model", "competence progress", "splitting regions",
    "return home simulated", "random goal babbling", "random motor babbling")}
"""The variants compared, by label: `run_goal_babbling` arguments that differ from
its defaults (the first is the default learner: learning progress over fixed
regions, the paper's interest, the nearest-neighbour inverse model, the caps' depths
in the outcome)."""
HELD_OUT_VARIANTS = ("learning progress", "random goal babbling")
"""The variants checked on the held-out root seeds: the default and its baseline."""
N_SEEDS = 10
"""Seeds per root seed."""
LOOP_VARIANTS = ("learning progress", "random goal babbling")
"""The variants whose formed presses the goal-oriented learner also runs on
(`run_formed_actions`, seeded with the root seed)."""


def run_variant(label, root, n_seeds=N_SEEDS, progress=False, first_run=0, threads=None,
                n_rollouts=goal_babbling.DEFAULT_N_ROLLOUTS,
                n_trials=formed_actions.DEFAULT_TRIALS):
    """Runs one variant on seeds first_run to first_run + n_seeds - 1 of one root seed
    and returns its entry of the study (`arms.run_arm`): {"pressed": [seed][budget]
    [button] (0 or 1, budgets `BUDGETS`), "failures": [seed][button] (codes of
    `formed_actions.PRESS_FAILURES` at the default budget), "test_error": [seed]
    (final, in the run's outcome space), and for `LOOP_VARIANTS` "red_first" [seed] (0
    or 1) and "as_scripted" [seed] (share of the learner's presses with the scripted
    effect)}. The arguments are `run_arm`'s; `label` a key of `VARIANTS`."""
    label = _validate.one_of("label", label, tuple(VARIANTS))
    measures = ("pressed", "failures", "test_error") + \
        (("loop",) if label in LOOP_VARIANTS else ())
    return run_arm(label, root, measures, n_seeds, progress, first_run, threads, n_rollouts,
                   n_trials)


def plan():
    """{variant: the root seeds it runs on}: every variant on `TUNING_ROOTS`, and
    `HELD_OUT_VARIANTS` on `HELD_OUT_ROOTS` too."""
    return {label: TUNING_ROOTS + (HELD_OUT_ROOTS if label in HELD_OUT_VARIANTS else ())
            for label in VARIANTS}


def _check(settings):
    n_roots = len(TUNING_ROOTS)
    if settings["seeds"] % n_roots:
        raise ValueError(f"seeds must be a multiple of the {n_roots} tuning root seeds "
                         f"{list(TUNING_ROOTS)}, got {settings['seeds']}")
    return settings


def units(settings):
    """The study's units: [variant, root, i, 1], seed i of each root of each variant
    (`plan`), settings["seeds"] // 2 seeds per root."""
    per_root = settings["seeds"] // len(TUNING_ROOTS)
    return [[label, root, i, 1] for label, roots in plan().items()
            for root in roots for i in range(per_root)]


def run_unit(settings, unit):
    """One unit of `units`: `run_variant` of its seed."""
    label, root, first, n = unit
    return run_variant(label, root, n_seeds=n, first_run=first, threads=1,
                       n_rollouts=settings["rollouts"], n_trials=settings["trials"])


def assemble(settings, units, results):
    """The study's file from its units' results: {"budgets", "n_seeds" (per root seed),
    "n_rollouts", "n_trials", "runs": {variant: {root: entry}}}."""
    return {"budgets": list(budgets_of(settings["rollouts"])),
            "n_seeds": settings["seeds"] // len(TUNING_ROOTS),
            "n_rollouts": settings["rollouts"], "n_trials": settings["trials"],
            "runs": assemble_roots(units, results, plan())}


register(Study(
    name="goal-babbling",
    description="the variants of the goal-babbling learner "
                "(icm.studies.forming_actions.strategies; assets/goal_babbling_study.json)",
    seeds=(20, "per variant and root pair: split over the tuning roots 100 and 200 "
               "(and the held-out roots 300 and 400 for the default and its baseline)"),
    options={"rollouts": ROLLOUTS, "trials": FORMED_TRIALS},
    units=units, run_unit=run_unit, assemble=assemble, seeding=SEEDING, check=_check,
    indent=1, unit_seconds=unit_seconds))


def load_study():
    """The study, read from assets/goal_babbling_study.json: {"budgets": [...],
    "n_seeds": (per root seed), "n_rollouts": ..., "runs": {label: {root: entry}}}
    (every variant on `TUNING_ROOTS`, and `HELD_OUT_VARIANTS` on `HELD_OUT_ROOTS`;
    entries as `run_variant` returns them; roots as strings, as JSON keys are)."""
    return json.loads(asset_path(STUDY_FILE).read_text())


def pool(entries):
    """Entries of consecutive seed blocks (a variant's roots) joined into one: each
    per-seed list the blocks' lists one after the other."""
    pooled = {}
    for entry in entries:
        for key, values in entry.items():
            pooled.setdefault(key, []).extend(values)
    return pooled


def tuning(study, label):
    """Variant `label`'s entries on the tuning root seeds of `study`, pooled (`pool`)."""
    return pool([study["runs"][label][str(root)] for root in TUNING_ROOTS])


def summary(study=None):
    """Per variant and root seed: the share of seeds with all five presses formed at
    the default budget, the mean number formed, the mean final test error and, where
    measured, the share of seeds with red mastered first and the share of presses
    with the scripted effect. A dict {label: {root: {...}}}; "tuning" pools the tuning
    roots, "held_out" the held-out ones (for the variants run there)."""
    study = load_study() if study is None else study
    out = {}
    for label, by_root in study["runs"].items():
        out[label] = {}
        groups = dict(by_root)
        tuned = [r for r in by_root if int(r) in TUNING_ROOTS]
        groups["tuning"] = pool([by_root[r] for r in tuned])
        held = [r for r in by_root if int(r) in HELD_OUT_ROOTS]
        if held:
            groups["held_out"] = pool([by_root[r] for r in held])
        for name, entry in groups.items():
            pressed = np.array(entry["pressed"])[:, -1]  # [seed, button] at the budget
            row = {"n_seeds": len(pressed), "all_pressed_share": float(pressed.all(1).mean()),
                   "buttons_pressed": float(pressed.sum(1).mean()),
                   "test_error": float(np.mean(entry["test_error"]))}
            if "red_first" in entry:  # every seed made the same number of presses
                row["red_first_share"] = float(np.mean(entry["red_first"]))
                row["as_scripted"] = float(np.mean(entry["as_scripted"]))
            out[label][name] = row
    return out


def failure_counts(study, label):
    """What became of the press formed for each button, counted over the tuning seeds
    of variant `label`: {name in `formed_actions.PRESS_FAILURES`: count}."""
    label = _validate.one_of("label", label, tuple(study["runs"]))
    codes = np.array(tuning(study, label)["failures"])
    return {name: int((codes == i).sum()) for i, name in
            enumerate(formed_actions.PRESS_FAILURES)}


def main():
    """Runs the study on every core and writes assets/goal_babbling_study.json
    (`python -m icm study goal-babbling` does the same with more choices: a Dask
    cluster, fewer seeds, ...). A run stopped half-way continues from its journal."""
    from icm.store import ASSETS
    from icm.studies.engine import run_study

    path = ASSETS / STUDY_FILE
    run_study("goal-babbling", path, seeds=N_SEEDS * len(TUNING_ROOTS))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
