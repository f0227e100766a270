"""The paper's experiments run with a student's piece in place of the library's: the
goal-oriented learner on the tabular button console, one agent per seed, with any
interest module (`GoalOrientedAgent` takes one)."""

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.experiments import goal_oriented as go_experiment
from icm.experiments.seeding import run_seeds
from icm.learners.goal_oriented import DEFAULT_EPSILON, INTEREST_PER, GoalOrientedAgent
from icm.learners.predictors import NearestNeighbourPredictor

EXERCISE_SEEDS = 20
"""Seeds of the runs a check makes with a student's piece: enough for a mean curve
with a visible band, few enough for a run of a few seconds."""
EXERCISE_TRIALS = go_experiment.CHAPTER_TRIALS
"""Trials of those runs: the chapter's (its Figure 5's)."""


class _AgentsAsRows:
    """Per-agent learners (`GoalOrientedAgent`, one per row) seen as the batched learner
    `icm.experiments.goal_oriented.play` drives: each row's agent chooses, learns and is
    read through its own methods, in row order, so that its numbers are its own."""

    def __init__(self, agents, red_button, n_actions, interest_per="task"):
        self.agents, self.n_actions = agents, n_actions
        self.lights = [tuple(layout.tolist()) for layout in buttons.layouts(red_button)]
        self.effects = np.array(buttons.EFFECTS)
        self.interest_per = interest_per
        self.interest, self.predictor = self, self  # values() and effect, as the batch's
        rest = go_experiment.TASK_KEYS["nothing"][0]
        self._tasks = [(rest, effect) for effect in buttons.EFFECTS]
        self._rest = rest

    def _observation(self, layout):
        return {"lights": np.array(self.lights[layout]), "boxes": np.array(self._rest)}

    def select_actions(self, layouts):
        return np.array([agent.select_action(self._observation(layout))
                         for agent, layout in zip(self.agents, layouts.tolist())])

    def learn(self, layouts, actions, effects):
        for agent, layout, action, effect in zip(self.agents, layouts.tolist(),
                                                 actions.tolist(), effects.tolist()):
            after = {"lights": np.array(self.lights[layout]),
                     "boxes": np.array(buttons.EFFECTS[effect])}
            agent.learn(self._observation(layout), action, after)

    def values(self):
        """[row, effect]: each agent's interest in the task of each effect; per region,
        [row, action]: its interest in each button's region."""
        keys = self._tasks if self.interest_per == "task" else range(self.n_actions)
        return np.array([[agent.interest.interest(key) for key in keys]
                         for agent in self.agents])

    @property
    def effect(self):
        """[row, layout * n_actions + action]: the effect each agent predicts."""
        return np.array([[buttons.EFFECTS.index(tuple(int(v) for v in agent.predictor.predict(
            lights, action, default=self._rest)))
            for lights in self.lights for action in range(self.n_actions)]
            for agent in self.agents])


def run_goal_oriented_with(make_interest, n_seeds=EXERCISE_SEEDS, n_trials=EXERCISE_TRIALS,
                           noisy_button=False, seed=0, interest_per="task"):
    """`icm.experiments.run_goal_oriented` with another interest module: each seed is a
    `GoalOrientedAgent` built with `make_interest()`, on a row of a
    `ButtonConsoleBatch`, seeded as `run_goal_oriented` seeds its rows and played by its
    loop (`icm.experiments.goal_oriented.play`); with the library's
    `LearningProgressInterest` it gives the same numbers (a test checks it).

    Args:
      make_interest: a function of no arguments returning a new interest module (with
        `record(task, error)` and `interest(task)`).
      n_seeds: runs (>= 1).
      n_trials: trials per run (>= 1).
      noisy_button: add the noisy button (action 5).
      seed: the root seed, an integer >= 0.
      interest_per: where interest lives, "task" (the paper's) or "region" (each
        button its own region; see `icm.learners.goal_oriented.INTEREST_PER`).

    Returns:
      A `GoalOrientedResult`.
    """
    _validate.function("make_interest", make_interest, allow_none=False)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    noisy_button = _validate.boolean("noisy_button", noisy_button)
    seed = _validate.seed("seed", seed)
    interest_per = _validate.one_of("interest_per", interest_per, INTEREST_PER)
    red = buttons.DEFAULT_RED_BUTTON
    presses = buttons.DEFAULT_PRESSES_PER_TRIAL
    n_actions = buttons.n_actions(noisy_button)
    seeds = run_seeds(seed, n_seeds, 2)
    env = buttons.ButtonConsoleBatch([env_seed for env_seed, _ in seeds], red, noisy_button)
    agents = _AgentsAsRows([GoalOrientedAgent(n_actions, NearestNeighbourPredictor(),
                                              make_interest(), DEFAULT_EPSILON,
                                              interest_per, seed=agent_seed)
                            for _, agent_seed in seeds], red, n_actions, interest_per)
    settings = dict(n_seeds=n_seeds, n_trials=n_trials, presses_per_trial=presses,
                    noisy_button=noisy_button, seed=seed, interest="yours",
                    interest_per=interest_per)
    return go_experiment.play(env, agents, n_trials, presses, settings=settings)
