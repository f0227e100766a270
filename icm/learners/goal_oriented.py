"""The goal-oriented architecture of the paper (section 3.1, Figure 2).

Predictor, interest module and actor are separate and replaceable. For each action
the actor (1) looks at the observation, (2) asks the predictor what the action would
do, (3) hands that effect, as a task, to the interest module, and (4) gets back how
interesting the task is; it then picks an action epsilon-greedily on interest.
"""

import math


from icm import _validate
from icm.learners._common import check_keys, check_values, read_observation
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
      ValueError: for n_actions < 1, epsilon outside [0, 1], a predictor or interest
        module without the methods above, keys that are not entry names, or a bad
        seed.
    """

    def __init__(self, n_actions, predictor=None, interest=None, epsilon=DEFAULT_EPSILON,
                 context_keys=("lights",), goal_key="boxes", goal_at_rest=None, seed=None):
        self.n_actions = _validate.integer_at_least("n_actions", n_actions, 1)
        self.epsilon = _validate.in_closed_interval("epsilon", epsilon, 0.0, 1.0)
        self.predictor = NearestNeighbourPredictor() if predictor is None else predictor
        self.interest = LearningProgressInterest() if interest is None else interest
        for name, part, methods in (("predictor", self.predictor, ("predict", "update")),
                                    ("interest", self.interest, ("record", "interest"))):
            if not all(callable(getattr(part, m, None)) for m in methods):
                raise _validate.ArgumentTypeError(
                    f"{name} must have the methods {' and '.join(methods)}, got "
                    f"{_validate.show(part)}")
        self.context_keys = check_keys("context_keys", context_keys)
        self.goal_key = _validate.text("goal_key", goal_key)
        self.goal_at_rest = None if goal_at_rest is None else check_values(
            "goal_at_rest", goal_at_rest)
        self._random = _validate.generator("seed", seed)

    def context(self, observation):
        """The predictor's context for an observation: its context entries as a tuple."""
        return read_observation("observation", observation, self.context_keys)

    def goal_state(self, observation, name="observation"):
        """The goal state of an observation (its `goal_key` entry) as a tuple."""
        return read_observation(name, observation, (self.goal_key,))

    def _rest(self, observation):
        if self.goal_at_rest is None:
            self.goal_at_rest = (0,) * len(self.goal_state(observation))
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

        Raises:
          ValueError: for an observation without the agent's entries, or an action
            that is not an integer in 0..n_actions-1.
        """
        action = _validate.integer("action", action, 0, self.n_actions - 1)
        context, rest = self.context(observation), self._rest(observation)
        observed = self.goal_state(next_observation, "next_observation")
        predicted = self.predictor.predict(context, action, default=rest)
        error = math.dist(predicted, observed)
        task = (rest, observed)
        self.interest.record(task, error)
        self.predictor.update(context, action, observed)
        return task, error
