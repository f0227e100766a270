"""The longer goal-babbling runs the chapter "Forming actions" shows: every variant of
the learner at the default budget on root seeds that no test uses, kept in
assets/goal_babbling_study.json because they take minutes, not seconds.

`run_variant` runs one variant on seeds of one root seed with `run_goal_babbling`
(and `run_formed_actions`); `python -m icm study goal-babbling`
(`icm.experiments.studies`) writes the file on every core or on a Dask cluster, one
seed of one variant a unit (`python -m icm.experiments.goal_babbling_study` with the
defaults; about 15 minutes of CPU); `load_study` reads it; a test reruns the first
seeds of some of it (the first k seeds of a root seed are the same in any larger run)
and expects the same numbers.
"""

import json
import numpy as np

from icm import _validate
from icm.store import ASSETS, asset_path
from icm.experiments import formed_actions, goal_babbling


STUDY_FILE = "goal_babbling_study.json"
"""The file in assets/ that holds the study."""
VARIANTS = {
    "learning progress": {},
    "where the finger stopped only": {"outcome_space": "point"},
    "depth weight 1": {"depth_weight": 1.0},
    "depth weight 3": {"depth_weight": 3.0},
    "LWLR inverse model": {"inverse_model": "lwlr"},
    "competence progress": {"measure": "competence_progress"},
    "splitting regions": {"regions": "splitting"},
    "return home simulated": {"retract": True},
    "random goal babbling": {"strategy": "random_goal"},
    "random motor babbling": {"strategy": "random_motor"},
}
"""The variants compared, by label: `run_goal_babbling` arguments that differ from
its defaults (the first is the default learner: learning progress over fixed
regions, the paper's interest, the nearest-neighbour inverse model, the caps' depths
in the outcome)."""
TUNING_ROOTS = (100, 200)
"""Root seeds on which every variant runs (the choices of the chapter were made on
them)."""
HELD_OUT_ROOTS = (300, 400)
"""Root seeds on which `HELD_OUT_VARIANTS` run again, after every choice was made."""
HELD_OUT_VARIANTS = ("learning progress", "random goal babbling")
"""The variants checked on the held-out root seeds: the default and its baseline."""
N_SEEDS = 10
"""Seeds per root seed."""
BUDGETS = (100, 200, 300, 400, 500, 600, 700, 800, 900, 1000)
"""Rollouts after which the presses formed so far are tested (`presses_formed`)."""
LOOP_VARIANTS = ("learning progress", "random goal babbling")
"""The variants whose formed presses the goal-oriented learner also runs on
(`run_formed_actions`, seeded with the root seed)."""


def _check_budgets():
    if BUDGETS[-1] != goal_babbling.DEFAULT_N_ROLLOUTS:
        raise ValueError(f"BUDGETS must end at the default budget "
                         f"({goal_babbling.DEFAULT_N_ROLLOUTS}), got {BUDGETS[-1]}")


def budgets_of(n_rollouts):
    """The budgets at which a run of `n_rollouts` rollouts tests its presses: those of
    `BUDGETS` below it, and `n_rollouts` (`BUDGETS` at the default budget)."""
    n_rollouts = _validate.integer_at_least("n_rollouts", n_rollouts, 1)
    return tuple(b for b in BUDGETS if b < n_rollouts) + (n_rollouts,)


def run_variant(label, root, n_seeds=N_SEEDS, progress=False, first_run=0, threads=None,
                n_rollouts=goal_babbling.DEFAULT_N_ROLLOUTS,
                n_trials=formed_actions.DEFAULT_TRIALS):
    """Runs one variant on seeds first_run to first_run + n_seeds - 1 of one root seed
    and returns its entry of the study: a dict of lists, one item per seed (the first k
    seeds of a root seed are the same in any larger run, so a shorter rerun checks
    them, and a study can be run one seed at a time: `icm.experiments.studies`).

    Args:
      label: a key of `VARIANTS`.
      root: the root seed (an integer >= 0).
      n_seeds: seeds (>= 1).
      progress: show progress bars.
      first_run: the index of the first seed of the root seed (>= 0).
      threads: threads stepping the physics (as in `run_goal_babbling`; the results
        do not depend on it).
      n_rollouts: rollouts per seed (the study's is the default; fewer make a quick
        trial run, its presses tested at `budgets_of(n_rollouts)`).
      n_trials: trials of the goal-oriented learner on each seed's formed presses, for
        `LOOP_VARIANTS` (`run_formed_actions`; the study's is the default, fewer make
        a quick trial run).

    Returns:
      {"pressed": [seed][budget][button] (0 or 1, budgets `BUDGETS`), "failures":
      [seed][button] (codes of `formed_actions.PRESS_FAILURES` at the default
      budget), "test_error": [seed] (final, in the run's outcome space), and for
      `LOOP_VARIANTS`
      "red_first" [seed] (0 or 1) and "as_scripted" [seed] (share of the learner's
      presses with the scripted effect)}.
    """
    _check_budgets()
    label = _validate.one_of("label", label, tuple(VARIANTS))
    root = _validate.seed("root", root)
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)  # before the babbling
    arguments = {"strategy": "learning_progress", **VARIANTS[label]}
    result = goal_babbling.run_goal_babbling(**arguments, n_seeds=n_seeds, seed=root,
                                             progress=progress, first_run=first_run,
                                             threads=threads, n_rollouts=n_rollouts)
    pressed = formed_actions.presses_formed(result, budgets_of(n_rollouts))
    entry = {"pressed": np.moveaxis(pressed, 0, 1).astype(int).tolist(),
             "failures": formed_actions.press_failures(result).tolist(),
             "test_error": result.final_test_error().tolist()}
    if label in LOOP_VARIANTS:
        loop = formed_actions.run_formed_actions(result, n_trials=n_trials, seed=root,
                                                progress=progress, first_run=first_run)
        entry["red_first"] = loop.red_first().astype(int).tolist()
        entry["as_scripted"] = loop.as_scripted_per_seed.tolist()
    return entry


def load_study():
    """The study, read from assets/goal_babbling_study.json: {"budgets": [...],
    "n_seeds": (per root seed), "n_rollouts": ..., "runs": {label: {root: entry}}}
    (every variant on `TUNING_ROOTS`, and `HELD_OUT_VARIANTS` on `HELD_OUT_ROOTS`;
    entries as `run_variant` returns them; roots as strings, as JSON keys are)."""
    return json.loads(asset_path(STUDY_FILE).read_text())


def summary(study=None):
    """Per variant and root seed: the share of seeds with all five presses formed at
    the default budget, the mean number formed, the mean final test error and, where
    measured, the share of seeds with red mastered first and the share of presses
    with the scripted effect. A dict {label: {root: {...}}}; "all" pools the roots
    (the tuning roots for every variant; the held-out ones are kept apart)."""
    study = load_study() if study is None else study
    out = {}
    for label, by_root in study["runs"].items():
        out[label] = {}
        groups = dict(by_root)
        tuning = [r for r in by_root if int(r) in TUNING_ROOTS]
        groups["tuning"] = pool([by_root[r] for r in tuning])
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


def pool(entries):
    """Entries of consecutive seed blocks (a variant's roots) joined into one: each
    per-seed list the blocks' lists one after the other."""
    pooled = {}
    for entry in entries:
        for key, values in entry.items():
            pooled.setdefault(key, []).extend(values)
    return pooled


def main():
    """Runs the study on every core and writes assets/goal_babbling_study.json
    (`python -m icm study goal-babbling` does the same with more choices: a Dask
    cluster, fewer seeds, ...). A run stopped half-way continues from its journal."""
    from icm.experiments import studies

    path = ASSETS / STUDY_FILE
    studies.run_study("goal-babbling", path, seeds=N_SEEDS * len(TUNING_ROOTS))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()


def tuning(study, label):
    """Variant `label`'s entries on the tuning root seeds of `study`, pooled (`pool`)."""
    return pool([study["runs"][label][str(root)] for root in TUNING_ROOTS])


def failure_counts(study, label):
    """What became of the press formed for each button, counted over the tuning seeds
    of variant `label`: {name in `formed_actions.PRESS_FAILURES`: count}."""
    label = _validate.one_of("label", label, tuple(study["runs"]))
    codes = np.array(tuning(study, label)["failures"])
    return {name: int((codes == i).sum()) for i, name in
            enumerate(formed_actions.PRESS_FAILURES)}


