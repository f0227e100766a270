"""The arms of the chapter "Forming actions"'s studies, and the run that measures one:
every arm is the goal-babbling learner with some of `run_goal_babbling`'s settings
changed (`ARMS`: a variant of the learner, or a condition, growing up or being shown),
run on seeds of a root seed and read as its study keeps it (`run_arm`: the presses it
formed at each budget, what became of them, its first presses, its test error, the
paper's learner on the presses it formed, its maturational clock, where its finger
went). The studies register their arms and units in `strategies` and `remedies`.
"""

import numpy as np

from icm import _validate
from icm.experiments import babbling_space, formed_actions, goal_babbling

ARMS = {
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
    "growing up": {"maturation": "joint_range"},
    "shown button 2": {"demonstrations": (2,)},
    "shown buttons 0 and 4": {"demonstrations": (0, 4)},
    "shown all five": {"demonstrations": (0, 1, 2, 3, 4)},
}
"""Every arm the studies run, by label: `run_goal_babbling` arguments that differ from
its defaults (learning progress over fixed regions, the paper's interest, the
nearest-neighbour inverse model, the caps' depths in the outcome, no maturation, no
teacher). One button shown is the middle one, the one the book's runs of the paper's
experiment light red (`buttons.DEFAULT_RED_BUTTON`; the paper does not say which button
is red); two are the end buttons, 0 and 4 (not the two farthest from the resting
fingertip: button 1 is about as far as button 4)."""
TUNING_ROOTS = (100, 200)
"""Root seeds on which every arm runs (the choices of the chapter, the learner's, the
clock's and the teacher's, were made on them). No test uses them."""
HELD_OUT_ROOTS = (300, 400)
"""Root seeds on which the arms run again after every choice was made: the chapter's
verdicts are decided on them."""
BUDGETS = (100, 200, 300, 400, 500, 600, 700, 800, 900, 1000)
"""Rollouts after which the presses formed so far are tested
(`formed_actions.presses_formed`)."""
EARLY = 200
"""Coverage is also counted over the first this many rollouts."""
COVERAGE_CELL = 0.01
"""The side of a coverage map's cells (m), over the goal space's x and y."""
MEASURES = ("pressed", "failures", "first_press", "test_error", "loop", "maturity",
            "coverage")
"""What an arm's entry may keep (`run_arm`), in the order its study's file lists them."""


def _check_budgets():
    if BUDGETS[-1] != goal_babbling.DEFAULT_N_ROLLOUTS:
        raise ValueError(f"BUDGETS must end at the default budget "
                         f"({goal_babbling.DEFAULT_N_ROLLOUTS}), got {BUDGETS[-1]}")


def budgets_of(n_rollouts):
    """The budgets at which a run of `n_rollouts` rollouts tests its presses: those of
    `BUDGETS` below it, and `n_rollouts` (`BUDGETS` at the default budget)."""
    n_rollouts = _validate.integer_at_least("n_rollouts", n_rollouts, 1)
    return tuple(b for b in BUDGETS if b < n_rollouts) + (n_rollouts,)


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


def run_arm(label, root, measures, n_seeds, progress=False, first_run=0, threads=None,
            n_rollouts=goal_babbling.DEFAULT_N_ROLLOUTS,
            n_trials=formed_actions.DEFAULT_TRIALS):
    """Runs arm `label` on seeds first_run to first_run + n_seeds - 1 of one root seed
    and returns its entry of a study: a dict of lists, one item per seed (the first k
    seeds of a root seed are the same in any larger run, so a shorter rerun checks
    them, and a study can be run one seed at a time).

    Args:
      label: a key of `ARMS`.
      root: the root seed (an integer >= 0).
      measures: what the entry keeps, some of `MEASURES` in their order: "pressed"
        [seed][budget][button] (0 or 1, at `budgets_of(n_rollouts)`), "failures"
        [seed][button] (codes of `formed_actions.PRESS_FAILURES`), "first_press"
        [seed][button] (`GoalBabblingResult.first_presses`, -1 for never),
        "test_error" [seed] (final, in the run's outcome space), "loop" ("red_first"
        [seed], 0 or 1, and "as_scripted" [seed]: the paper's goal-oriented learner on
        the presses formed, `run_formed_actions`, seeded with the root seed),
        "maturity" [seed][budget] (the maturational clock at the budgets) and
        "coverage" {"early": ..., "all": ...} (`coverage_counts` over the first
        `EARLY` rollouts and over all, summed over the seeds).
      n_seeds: seeds (>= 1).
      progress: show progress bars.
      first_run: the index of the first seed of the root seed (>= 0).
      threads: threads stepping the physics (as in `run_goal_babbling`; the results
        do not depend on it).
      n_rollouts: rollouts per seed (the studies' is the default; fewer make a quick
        trial run).
      n_trials: trials of the goal-oriented learner on each seed's formed presses (the
        studies' is the default; fewer make a quick trial run).
    """
    _check_budgets()
    label = _validate.one_of("label", label, tuple(ARMS))
    root = _validate.seed("root", root)
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)  # before the babbling
    for measure in measures:
        _validate.one_of("measures[i]", measure, MEASURES)
    arguments = {"strategy": "learning_progress", **ARMS[label]}
    result = goal_babbling.run_goal_babbling(**arguments, n_seeds=n_seeds, seed=root,
                                             progress=progress, first_run=first_run,
                                             threads=threads, n_rollouts=n_rollouts)
    budgets = budgets_of(n_rollouts)
    entry = {}
    for measure in measures:
        if measure == "pressed":
            pressed = formed_actions.presses_formed(result, budgets)  # [budget, seed, button]
            entry["pressed"] = np.moveaxis(pressed, 0, 1).astype(int).tolist()
        elif measure == "failures":
            entry["failures"] = formed_actions.press_failures(result).tolist()
        elif measure == "first_press":
            entry["first_press"] = result.first_presses().tolist()
        elif measure == "test_error":
            entry["test_error"] = result.final_test_error().tolist()
        elif measure == "loop":
            loop = formed_actions.run_formed_actions(result, n_trials=n_trials, seed=root,
                                                     progress=progress, first_run=first_run)
            entry["red_first"] = loop.red_first().astype(int).tolist()
            entry["as_scripted"] = loop.as_scripted_per_seed.tolist()
        elif measure == "maturity":
            entry["maturity"] = result.maturity[:, np.array(budgets) - 1].tolist()
        else:
            entry["coverage"] = {"early": coverage_counts(result, EARLY).tolist(),
                                 "all": coverage_counts(result).tolist()}
    return entry


def join_entries(entries):
    """One entry of a study from entries of consecutive seed blocks: the per-seed lists
    joined in order, the dicts of counts ("coverage") summed cell by cell."""
    out = {}
    for key, value in entries[0].items():
        if isinstance(value, list):
            out[key] = [item for entry in entries for item in entry[key]]
        elif isinstance(value, dict):
            out[key] = {k: _add([entry[key][k] for entry in entries]) for k in value}
        else:
            raise ValueError(f"entries: {key!r} is neither per seed nor counts")
    return out


def _add(grids):
    """The cell-by-cell sum of nested lists of integers of one shape."""
    if isinstance(grids[0], list):
        return [_add(list(cells)) for cells in zip(*grids)]
    return sum(grids)


def assemble_roots(units, results, plan):
    """{label: {root: entry}} from the units [label, root, first, n] and their results,
    the seed blocks of each (label, root) of `plan` ({label: roots}) joined in the
    order of their first seeds (`join_entries`)."""
    runs = {}
    for label, roots in plan.items():
        runs[label] = {}
        for root in roots:
            parts = sorted((u[2], r) for u, r in zip(units, results) if u[:2] == [label, root])
            runs[label][str(root)] = join_entries([r for _, r in parts])
    return runs


SEEDING = ("unit [label, root, first, n]: seeds first..first+n-1 of root seed 'root' "
           "(icm.experiments._seeding.run_seeds: child i of numpy.random.SeedSequence(root)); "
           "the goal-oriented learner on the formed presses uses the same children of the "
           "same root")
"""What seeds the forming-actions studies' units use, in words, as their files keep it
(verbatim, so that a rerun writes the same bytes: `icm.experiments._seeding.run_seeds`
is now `icm.experiments.seeding.run_seeds`, the same function)."""
FORMED_TRIALS = (formed_actions.DEFAULT_TRIALS, 1,
                 "trials of the goal-oriented learner on each seed's formed presses")
"""The option "trials" of the studies of formed presses."""
ROLLOUTS = (goal_babbling.DEFAULT_N_ROLLOUTS, 1, "rollouts per seed")
"""The option "rollouts" of the studies of formed presses."""
ROLLOUT_SECONDS = 0.0075
"""CPU seconds one seed's rollout costs, roughly, its share of the formed presses'
trials included: a seed of 1,000 rollouts took a median of 7.7 CPU-seconds over the
561 units of the 80-seed remedies study (assets/remedies_study.json.runs.jsonl,
2026-12-03), 7.2 over the 240 of the goal-babbling study; one of 100 rollouts 1.1 s
(2026-12-05), hence `SEED_SECONDS` besides."""
SEED_SECONDS = 0.35
"""CPU seconds a seed costs beside its rollouts (setting up its learner and console)."""
REACH_SECONDS = 0.022
"""CPU seconds of the 'reach' unit per random movement of each range share (50 took
1.1 s, 2026-12-05; the 1,000 of the remedies study up to 29 s on shared cores)."""


def unit_seconds(settings, unit):
    """A rough figure of the CPU seconds of one unit of the studies of formed presses
    (`ROLLOUT_SECONDS`, `SEED_SECONDS`, `REACH_SECONDS`): `Study.unit_seconds`."""
    if unit == ["reach"]:
        return REACH_SECONDS * settings["reach_movements"]
    return unit[3] * (SEED_SECONDS + ROLLOUT_SECONDS * settings["rollouts"])
