"""The learners' runs the live iCub replays: the first trials of the goal-oriented
learner, the first episodes of the Q-learner on the rods, and the presses goal
babbling formed, recorded through the experiments' public loops (see `icm.viewer`)."""

from icm import _validate
from icm.viewer.scenes import buttons_physics, segment

DEFAULT_REPLAY_TRIALS = 10
"""Trials of the goal-oriented learner's run that `live_learner` replays."""
DEFAULT_REPLAY_EPISODES = 30
"""Episodes of the Q-learner's run that `live_rod_learner` replays: for the root seed 0,
they reach the first blue topple (episode 29)."""


def learner_replay(n_trials=DEFAULT_REPLAY_TRIALS, seed=0):
    """The first `n_trials` trials of run 0 of `run_goal_oriented(seed=seed)` (the
    paper's settings, the tabular console), press by press, for the browser to replay.

    The run is the same as `run_goal_oriented(n_seeds=1, n_trials=n_trials,
    seed=seed)`'s, recorded on the way (the tests check it).

    Args:
      n_trials: trials to replay (>= 1).
      seed: the root seed, as in `run_goal_oriented`.

    Returns:
      A dict: "seed" (the integer root seed), "trials", one dict per trial with
      "lights" (5 values: 0 off, 1 red, 2 green), "presses" (buttons), "boxes" (the
      boxes open after each press, [red, green]) and "interest" (interest in the red
      and the green task after the trial).
    """
    from icm.envs import buttons
    from icm.experiments import goal_oriented as experiment

    trials = []

    def record(step):  # a press of run 0: its trial, layout, button and effect
        trial = int(step.episode[0])
        if trial == len(trials):
            trials.append({"layout": int(step.before[0]), "actions": [], "effects": []})
        trials[trial]["actions"].append(int(step.action[0]))
        trials[trial]["effects"].append(int(step.outcome[0]))

    result, = experiment.run_goal_oriented_grid(
        [{}], n_seeds=1, n_trials=n_trials, seed=seed, progress=False, observe=record)
    red = result.settings["red_button"]
    layouts = buttons.layouts(red)
    trials = [{"lights": layouts[trial["layout"]].tolist(),
               "presses": trial["actions"],
               "boxes": [list(buttons.EFFECTS[e]) for e in trial["effects"]],
               "interest": result.interest[0, t].tolist()}
              for t, trial in enumerate(trials)]
    return {"seed": result.settings["seed"], "trials": trials}


def rod_replay(n_episodes=DEFAULT_REPLAY_EPISODES, seed=0):
    """The first `n_episodes` episodes of run 0 of `run_rod_toppling(seed=seed)` (the
    paper's settings, the tabular twin), move by move, for the browser to replay.

    The run is the same as `run_rod_toppling(n_seeds=1, n_episodes=n_episodes,
    seed=seed)`'s, recorded on the way (the tests check it).

    Args:
      n_episodes: episodes to replay (>= 1).
      seed: the root seed, as in `run_rod_toppling`.

    Returns:
      A dict: "seed", "start_cell", and "episodes", one dict per episode with
      "actions" (moves, indices of `icm.envs.rods.ACTIONS`), "cells" (the cell
      before each move), "toppled" ("red", "blue" or None) and "errors" (the
      predictor's absolute errors on each rod summed over the episode: the intrinsic
      reward the robot was paid).
    """
    from icm.envs import rods
    from icm.experiments import rod_toppling as experiment

    recorded = []

    def record(step):  # a move of run 0: its cell, the move, the next cell, the rod toppled
        recorded.append((int(step.before[0]), int(step.action[0]), int(step.after[0]),
                         int(step.outcome[0])))

    result = experiment.run_rod_toppling(n_seeds=1, n_episodes=n_episodes, seed=seed,
                                         progress=False, observe=record)
    seed, start_cell = result.settings["seed"], result.settings["start_cell"]
    episodes, moves = [], iter(recorded)
    for e in range(result.n_episodes):
        taken = [next(moves) for _ in range(int(result.episode_length[0, e]))]
        toppled = int(result.toppled[0, e])
        episodes.append({"cells": [list(rods.number_cell(m[0])) for m in taken],
                         "actions": [m[1] for m in taken],
                         "toppled": rods.ROD_NAMES[toppled] if toppled >= 0 else None,
                         "errors": result.prediction_error[0, e].tolist()})
    return {"seed": seed, "start_cell": list(start_cell), "episodes": episodes}


def formed_presses(babbling, run=0):
    """The presses that goal babbling formed in run `run` of `babbling`, as the
    browser performs them: for each button, the movement `run_goal_babbling` learned
    for it (reach its joint targets, hold, return home: `movements.REACH_TIME`,
    `HOLD_TIME`, `RETRACT_TIME`), in a trial where that button is lit red, as
    `GoalBabblingResult.buttons_pressed` tests it.

    Args:
      babbling: a `GoalBabblingResult` (from `icm.experiments.run_goal_babbling`).
      run: which of its runs (0 .. n_seeds - 1).

    Returns:
      A dict: "run", "strategy", "presses" (one list of segments per button, as in
      `scene_export`), "lights" (the layout of each button's trial) and "pressed"
      (whether Python found that the movement presses its button alone and opens the
      red box).

    Raises:
      ValueError: if `babbling` is not a `GoalBabblingResult` or `run` not one of its
        runs.
    """
    from icm.envs import buttons
    from icm.envs.buttons import movements
    from icm.experiments import babbling_results

    _validate.instance("babbling", babbling, babbling_results.GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    run = _validate.integer("run", run, 0, babbling.n_seeds - 1)
    _, arm, motions = buttons_physics()
    presses = [[segment(arm, q, movements.REACH_TIME),
                segment(arm, q, movements.HOLD_TIME),
                segment(arm, motions.home, movements.RETRACT_TIME)]
               for q in babbling.press_movements[run]]
    lights = [buttons.lights_for(b, buttons.green_candidates(b)[0]).tolist()
              for b in range(buttons.N_BUTTONS)]
    return {"run": run, "strategy": babbling.strategy, "presses": presses, "lights": lights,
            "pressed": [bool(p) for p in babbling.buttons_pressed[run]]}
