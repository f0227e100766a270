"""The paper's experiments run with a student's piece in place of the library's: the
goal-oriented learner on the tabular button console, one agent per seed, with any
interest module (`GoalOrientedAgent` takes one)."""

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.experiments import goal_oriented as go_experiment
from icm.experiments._seeding import run_seeds
from icm.learners.goal_oriented import DEFAULT_EPSILON, GoalOrientedAgent
from icm.learners.predictors import NearestNeighbourPredictor
from icm.stats import first_from_which

EXERCISE_SEEDS = 20
"""Seeds of the runs a check makes with a student's piece: enough for a mean curve
with a visible band, few enough for a run of a few seconds."""
EXERCISE_TRIALS = 60
"""Trials of those runs (the chapter's Figure 5 has 60)."""


def run_goal_oriented_with(make_interest, n_seeds=EXERCISE_SEEDS, n_trials=EXERCISE_TRIALS,
                           noisy_button=False, seed=0):
    """`icm.experiments.run_goal_oriented` with another interest module: each seed is a
    `GoalOrientedAgent` built with `make_interest()`, on a `ButtonConsole`, seeded as
    `run_goal_oriented` seeds its rows (with the library's `LearningProgressInterest`
    it gives the same numbers; a test checks it).

    Args:
      make_interest: a function of no arguments returning a new interest module (with
        `record(task, error)` and `interest(task)`).
      n_seeds: runs (>= 1).
      n_trials: trials per run (>= 1).
      noisy_button: add the noisy button (action 5).
      seed: the root seed, an integer >= 0.

    Returns:
      A `GoalOrientedResult` (its `action_interest` is left at zero).
    """
    _validate.function("make_interest", make_interest, allow_none=False)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    noisy_button = _validate.boolean("noisy_button", noisy_button)
    seed = _validate.seed("seed", seed)
    red = buttons.DEFAULT_RED_BUTTON
    presses = buttons.DEFAULT_PRESSES_PER_TRIAL
    n_actions = buttons.n_actions(noisy_button)
    layouts = buttons.layouts(red)
    queries = [(tuple(layout.tolist()), b) for layout in layouts for b in range(buttons.N_BUTTONS)]
    truth = np.array([buttons.press_outcome(np.array(c), b) for c, b in queries])
    interest = np.zeros((n_seeds, n_trials, 2))
    error = np.zeros((n_seeds, n_trials, 2))
    practice = np.zeros((n_seeds, n_trials, 2), dtype=np.int64)
    pressed = np.zeros((n_seeds, n_trials, n_actions))
    for run, (env_seed, agent_seed) in enumerate(run_seeds(seed, n_seeds, 2)):
        env = buttons.ButtonConsole(red, presses, noisy_button=noisy_button, seed=env_seed)
        agent = GoalOrientedAgent(n_actions, NearestNeighbourPredictor(), make_interest(),
                                  DEFAULT_EPSILON, seed=agent_seed)
        for trial in range(n_trials):
            step = env.reset()
            while not step.last():
                action = agent.select_action(step.observation)
                next_step = env.step(action)
                agent.learn(step.observation, action, next_step.observation)
                practice[run, trial] += next_step.observation["boxes"]
                pressed[run, trial, action] += 1
                step = next_step
            for i, task in enumerate(go_experiment.TASKS):
                interest[run, trial, i] = agent.interest.interest(go_experiment.TASK_KEYS[task])
            predicted = np.array([agent.predictor.predict(c, b, default=(0, 0))
                                  for c, b in queries])
            error[run, trial] = np.abs(predicted - truth).mean(axis=0)
    mastery = first_from_which(np.moveaxis(error, 1, 2) == 0)
    mastery = np.where(mastery >= 0, mastery + 1, -1)
    settings = dict(n_seeds=n_seeds, n_trials=n_trials, presses_per_trial=presses,
                    noisy_button=noisy_button, seed=seed, interest="yours")
    return go_experiment.GoalOrientedResult(settings, interest, error, mastery, practice,
                                            pressed / presses,
                                            np.zeros((n_seeds, n_trials, n_actions)))
