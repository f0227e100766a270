"""Tabular one-step Q-learning (paper section 3.3, equation 3), paid by a predictor's
errors: the learner of the rod-toppling experiment (section 4.2, Figure 7)."""


import numpy as np

from icm import _validate
from icm.learners.predictors import LinearPredictor

DEFAULT_ALPHA = 0.5
"""Q-learning step size (the paper's alpha; its value is not given). The reward of a
pair fades as the predictor learns it (0.8 of what it was, each time), so the values
must follow a moving target: a large step."""
DEFAULT_GAMMA = 0.9
"""Discount (the paper's gamma; its value is not given). A rod is 3 to 6 moves from
the start cell; 0.9^5 = 0.59, so a surprise several moves away still pulls the hand."""
DEFAULT_EPSILON = 0.1
"""Probability of a uniformly random move (the paper's epsilon-greedy rule; its value
is not given)."""
DEFAULT_INITIAL_Q = 0.1
"""Value of every (state, action) before it is tried: mildly optimistic. A move never
tried is worth as much as a topple still predicted with an error of 0.1, the level
the book calls "predicted well". So the robot gets *bored* of a rod once its
errors there have fallen to about that level, and goes looking elsewhere; with 0 the
smallest leftover error would keep it at the first rod it found (the errors shrink by
a factor 0.8 per topple and never reach 0)."""



class QLearner:
    """Tabular one-step Q-learning with epsilon-greedy moves and an intrinsic reward.

    Equation 3 of the paper (its `max_a Q(s_{t+1}, a_t)` read as the usual
    `max_a Q(s_{t+1}, a)`):

        Q(s_t, a_t) <- Q(s_t, a_t) + alpha * [r_{t+1} + gamma * d * max_a Q(s_{t+1}, a)
                                              - Q(s_t, a_t)],

    where d is the environment's discount: 0 when the move ended the episode (a rod
    toppled: nothing follows), 1 otherwise (a time limit does not end the world).

    The reward (`learn`) is intrinsic: the absolute error of the predictor's guess of
    what the move would do, ``r = sum_i abs(o_i - p_i(s, a))``, computed before the predictor
    learns from the move. A move the predictor already knows pays nothing; a surprise
    pays up to 1.

    Actions: with probability epsilon a uniformly random action, otherwise one of the
    actions with the largest Q(s, .), ties broken at random.

    States are integers 0..n_states-1 (the rod experiment numbers the cells
    column + 5 * row).

    Args:
      n_states: number of states (integer >= 1).
      n_actions: number of actions (integer >= 1).
      predictor: has `update(state, action, observed) -> error`; default a
        `LinearPredictor(n_actions, n_outputs=1)` (pass one with the outcome's size).
      alpha: step size in (0, 1].
      gamma: discount in [0, 1].
      epsilon: probability of a random action, in [0, 1].
      initial_q: Q of every pair before it is tried (a finite number >= 0).
      seed: None, an integer >= 0 or a `numpy.random.Generator`.

    Raises:
      ValueError: for any argument outside its range, or a state or action outside
        the table.
    """

    def __init__(self, n_states, n_actions, predictor=None, alpha=DEFAULT_ALPHA,
                 gamma=DEFAULT_GAMMA, epsilon=DEFAULT_EPSILON, initial_q=DEFAULT_INITIAL_Q,
                 seed=None):
        self.n_states = _validate.integer_at_least("n_states", n_states, 1)
        self.n_actions = _validate.integer_at_least("n_actions", n_actions, 1)
        self.alpha = _validate.learning_rate("alpha", alpha)
        self.gamma = _validate.in_closed_interval("gamma", gamma, 0.0, 1.0)
        self.epsilon = _validate.in_closed_interval("epsilon", epsilon, 0.0, 1.0)
        self.initial_q = _validate.non_negative("initial_q", initial_q)
        self.predictor = LinearPredictor(n_actions, 1) if predictor is None else predictor
        if not callable(getattr(self.predictor, "update", None)):
            raise _validate.ArgumentTypeError(f"predictor must have a method update, got "
                                              f"{_validate.show(predictor)}")
        self._random = _validate.generator("seed", seed)
        # Lists of floats: the learner's inner loop reads and writes single entries.
        self._q = [[self.initial_q] * self.n_actions for _ in range(self.n_states)]

    @property
    def q(self):
        """A copy of the Q-table, a float array [n_states, n_actions]."""
        return np.array(self._q)

    def _check(self, state, action=None, name="state"):
        state = _validate.integer(name, state, 0, self.n_states - 1)
        if action is None:
            return state
        return state, _validate.integer("action", action, 0, self.n_actions - 1)

    def greedy_actions(self, state):
        """The actions with the largest Q(state, .), in increasing order."""
        row = self._q[self._check(state)]
        best = max(row)
        return [a for a, value in enumerate(row) if value == best]

    def select_action(self, state):
        """Epsilon-greedy: a random action with probability epsilon, else a greedy one
        (ties broken uniformly at random)."""
        state = self._check(state)
        uniform = self._random.random  # floor(u * n) is uniform on 0..n-1, and cheap
        if self.epsilon > 0 and uniform() < self.epsilon:
            return int(uniform() * self.n_actions)
        row = self._q[state]
        best = max(row)
        candidates = [a for a, value in enumerate(row) if value == best]
        if len(candidates) == 1:
            return candidates[0]
        return candidates[int(uniform() * len(candidates))]

    def update(self, state, action, reward, next_state, discount=1.0):
        """One step of equation 3.

        Args:
          state: s_t.
          action: a_t.
          reward: r_{t+1}, a finite number.
          next_state: s_{t+1} (ignored when discount is 0).
          discount: the environment's discount d in [0, 1]: 0 if the episode ended.

        Returns:
          The TD error r + gamma * d * max_a Q(s', a) - Q(s, a), before the update.
        """
        state, action = self._check(state, action)
        discount = _validate.in_closed_interval("discount", discount, 0.0, 1.0)
        target = _validate.real("reward", reward)
        if discount > 0:
            next_state = self._check(next_state, name="next_state")
            target += self.gamma * discount * max(self._q[next_state])
        td_error = target - self._q[state][action]
        self._q[state][action] += self.alpha * td_error
        return td_error

    def learn(self, state, action, observed, next_state, discount=1.0):
        """Pays itself the predictor's surprise, teaches the predictor, updates Q.

        Args:
          state: the state the action was taken in.
          action: the action.
          observed: what the action did (the predictor's outcome, e.g. the rods).
          next_state: the state after the action.
          discount: 0 if the action ended the episode, else 1.

        Returns:
          The intrinsic reward: the absolute error of the prediction for
          (state, action) before this observation.
        """
        state, action = self._check(state, action)
        reward = self.predictor.update(state, action, observed)
        self.update(state, action, reward, next_state, discount)
        return reward
