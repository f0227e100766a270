"""The goal-oriented architecture of the paper (section 3.1, Figure 2).

Predictor, interest module and actor are separate and replaceable. For each action
the actor (1) looks at the observation, (2) asks the predictor what the action would
do, (3) hands that effect, as a task, to the interest module, and (4) gets back how
interesting the task is; it then picks an action epsilon-greedily on interest.
"""

import math

import numpy as np

from icm import _validate
from icm.learners.interest import LearningProgressInterest
from icm.learners.predictors import NearestNeighbourPredictor

DEFAULT_EPSILON = 0.1


class GoalOrientedAgent:
    """An epsilon-greedy actor on the interest of predicted effects.

    A *task* is a transition of the goal state (for the buttons, the boxes): from the
    goal state at rest (all boxes closed: the console closes them before every press)
    to the goal state after the action. The button experiment thus has three tasks:
    no box -> no box, no box -> red box, no box -> green box.

    Args:
      n_actions: number of discrete actions (integer >= 1).
      predictor: has `predict(context, action, default)` and `update(context, action,
        effect)`; default a `NearestNeighbourPredictor()`.
      interest: has `record(task, error)` and `interest(task)`; default a
        `LearningProgressInterest()`.
      epsilon: probability of a uniformly random action (in [0, 1]).
      context_keys: observation entries that make the context (default the lights).
      goal_key: the observation entry that makes the goal state (default the boxes).
      goal_at_rest: the goal state every action starts from (default all zeros).
      seed: None, an int, or a `numpy.random.Generator`, for epsilon and ties.

    Raises:
      ValueError: for n_actions < 1 or epsilon outside [0, 1].
    """

    def __init__(self, n_actions, predictor=None, interest=None, epsilon=DEFAULT_EPSILON,
                 context_keys=("lights",), goal_key="boxes", goal_at_rest=None, seed=None):
        self.n_actions = _validate.integer_at_least("n_actions", n_actions, 1)
        self.epsilon = _validate.in_closed_interval("epsilon", epsilon, 0.0, 1.0)
        self.predictor = NearestNeighbourPredictor() if predictor is None else predictor
        self.interest = LearningProgressInterest() if interest is None else interest
        self.context_keys = tuple(context_keys)
        self.goal_key = goal_key
        self.goal_at_rest = None if goal_at_rest is None else tuple(goal_at_rest)
        self._random = _validate.generator("seed", seed)

    def context(self, observation):
        """The predictor's context for an observation: its context entries as a tuple."""
        values = []
        for key in self.context_keys:
            values.extend(np.asarray(observation[key]).ravel().tolist())
        return tuple(values)

    def _rest(self, observation):
        if self.goal_at_rest is None:
            self.goal_at_rest = (0,) * np.asarray(observation[self.goal_key]).size
        return self.goal_at_rest

    def predicted_effects(self, observation):
        """The predicted goal state after each action, as a list of tuples."""
        context, rest = self.context(observation), self._rest(observation)
        return [self.predictor.predict(context, a, default=rest)
                for a in range(self.n_actions)]

    def action_interests(self, observation):
        """Interest of the task each action is predicted to achieve (steps 2-4 of Fig. 2)."""
        rest = self._rest(observation)
        return [self.interest.interest((rest, effect))
                for effect in self.predicted_effects(observation)]

    def select_action(self, observation):
        """Epsilon-greedy on interest; ties between the most interesting are random."""
        if self.epsilon > 0 and self._random.random() < self.epsilon:
            return int(self._random.integers(self.n_actions))
        values = self.action_interests(observation)
        best = max(values)
        candidates = [a for a, v in enumerate(values) if v == best]
        if len(candidates) == 1:
            return candidates[0]
        return candidates[int(self._random.integers(len(candidates)))]

    def learn(self, observation, action, next_observation):
        """Scores the prediction of `action` against what happened, and remembers it.

        Args:
          observation: the observation the action was chosen from.
          action: the action taken.
          next_observation: the observation after the action.

        Returns:
          (task, error): the task witnessed and the Euclidean prediction error.
        """
        context, rest = self.context(observation), self._rest(observation)
        predicted = self.predictor.predict(context, action, default=rest)
        observed = tuple(np.asarray(next_observation[self.goal_key]).ravel().tolist())
        error = math.dist(predicted, observed)
        task = (rest, observed)
        self.interest.record(task, error)
        self.predictor.update(context, action, observed)
        return task, error
