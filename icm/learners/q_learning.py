"""Tabular one-step Q-learning (paper section 3.3, equation 3), paid by a predictor's
errors: the learner of the rod-toppling experiment (section 4.2, Figure 7).

The intrinsic reward is the paper's, the predictor's error, or one of the other
interest signals of `icm.learners.interest`, computed per (state, action) pair from
the same errors (`REWARDS`)."""


import numpy as np

from icm import _validate
from icm._settings import Names, Settings, Slider, setting, setting_from, settings_class
from icm.learners import interest as _interest
from icm.learners import predictors as _predictors
from icm.learners import action_selection
from icm.learners.action_selection import epsilon_greedy
from icm.learners.interest import DEFAULT_WINDOW, SIGNAL_CLASSES, SIGNALS, make_interest
from icm.learners.predictors import LinearPredictor

REWARDS = Names(lambda: ("prediction_error",) + tuple(s for s in SIGNALS
                                                      if s != "prediction_error"))
"""The intrinsic rewards, by name: the interest signals of `icm.learners.interest`,
each kept per (state, action) pair and fed the predictor's error on every move:

- "prediction_error" (the paper's, default): the error itself, ``r = sum_i abs(o_i - p_i)``;
- "learning_progress": how fast the pair's errors fall, max(0, -slope) of its last
  `window` errors (a least-squares slope; 0 until the pair was tried twice);
- "novelty": 1 / sqrt(1 + n), n the times the pair was tried, this move included;
- "random": no reward and no learning of Q: every move is a tie, so the hand walks at
  random (the baseline); the predictor still learns."""
_RATE_SLIDER = Slider(live=(0.05, 1.0, 0.05), grid=(0.1, 0.3, 0.5, 0.7, 0.9))


@settings_class
class QLearnerSettings(Settings):
    """The curious Q-learner's settings (section 3.3, equation 3; section 4.2). Each is
    a `icm._settings.Setting`: see `QLearnerSettings.specs()` for its range, the
    paper's value and where it comes from. Values may be one per batch row (arrays),
    as the compiled loop of `icm.experiments.run_rod_toppling` takes them."""

    epsilon: float = setting(
        default=0.1, label="probability of a random move (epsilon)", kind="real", low=0.0,
        high=1.0,
        source="section 3.3's Q-learner is epsilon-greedy, with no epsilon given: the "
               "book takes 0.1",
        slider=Slider(live=(0.0, 1.0, 0.05), grid=(0.0, 0.1, 0.2, 0.3, 0.4)),
        swept=(0.0, 0.05, 0.1, 0.3))
    alpha: float = setting(
        default=0.5, label="Q-learning step size (alpha)", kind="real", low=0.0, high=1.0,
        low_open=True, slider=_RATE_SLIDER,
        source="equation 3's alpha has no value in the paper: the book takes 0.5, a large "
               "step, since a pair's reward fades as the predictor learns it (0.8 of what "
               "it was, each time) and the values must follow a moving target",
        others=(0.1, 0.9))
    gamma: float = setting(
        default=0.9, label="discount (gamma)", kind="real", low=0.0, high=1.0,
        slider=Slider(live=(0.0, 1.0, 0.05), grid=(0.1, 0.3, 0.5, 0.7, 0.9)),
        source="equation 3's gamma has no value in the paper: the book takes 0.9; a rod "
               "is 3 to 6 moves from the start cell, and 0.9^5 = 0.59, so a surprise "
               "several moves away still pulls the hand",
        others=(0.5, 0.99))
    initial_q: float = setting(
        default=0.1, label="value of a move never tried (initial Q)", kind="real",
        low=0.0, high=1e6,
        source="the paper does not say how Q starts. The book takes 0.1, mildly "
               "optimistic: a move never tried is worth as much as a topple still "
               "predicted with an error of 0.1, so the robot gets bored of a rod once its "
               "errors there have fallen to about that level; with 0 the smallest leftover "
               "error would keep it at the first rod it found",
        swept=(0.0, 0.01, 0.1, 0.2, 1.0))
    predictor_lr: float = setting_from(_predictors.LINEAR_LR)
    reward: str = setting(
        default="prediction_error", label="intrinsic reward", kind="choice",
        choices=REWARDS, paper="prediction_error", per_row=False,
        source="section 4.2: the Q-learner's reward is the predictor's error; the chapter "
               '"Which curiosity?" compares the others')
    window: int = setting_from(_interest.WINDOW, slider=None)


DEFAULT_ALPHA = QLearnerSettings.spec("alpha").default
DEFAULT_GAMMA = QLearnerSettings.spec("gamma").default
DEFAULT_EPSILON = QLearnerSettings.spec("epsilon").default
DEFAULT_INITIAL_Q = QLearnerSettings.spec("initial_q").default


class QLearner:
    """Tabular one-step Q-learning with epsilon-greedy moves and an intrinsic reward.

    Equation 3 of the paper (its `max_a Q(s_{t+1}, a_t)` read as the usual
    `max_a Q(s_{t+1}, a)`):

        Q(s_t, a_t) <- Q(s_t, a_t) + alpha * [r_{t+1} + gamma * d * max_a Q(s_{t+1}, a)
                                              - Q(s_t, a_t)],

    where d is the environment's discount: 0 when the move ended the episode (a rod
    toppled: nothing follows), 1 otherwise (a time limit does not end the world).

    The reward (`learn`) is intrinsic: by default (the paper's) the absolute error of
    the predictor's guess of what the move would do, ``r = sum_i abs(o_i - p_i(s, a))``,
    computed before the predictor learns from the move. A move the predictor already
    knows pays nothing; a surprise pays up to 1. `reward` chooses another signal
    computed from the same errors (see `REWARDS`).

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
      reward: the intrinsic reward, one of `REWARDS` (default "prediction_error").
      window: errors in the learning-progress slope (integer >= 2).
      seed: None, an integer >= 0 or a `numpy.random.Generator`.

    Raises:
      ValueError: for any argument outside its range, an unknown reward (the message
        lists the known ones), or a state or action outside the table.
    """

    def __init__(self, n_states, n_actions, predictor=None, alpha=DEFAULT_ALPHA,
                 gamma=DEFAULT_GAMMA, epsilon=DEFAULT_EPSILON, initial_q=DEFAULT_INITIAL_Q,
                 reward="prediction_error", window=DEFAULT_WINDOW, seed=None):
        self.n_states = _validate.integer_at_least("n_states", n_states, 1)
        self.n_actions = _validate.integer_at_least("n_actions", n_actions, 1)
        spec = QLearnerSettings.spec
        self.alpha = spec("alpha").check(alpha)
        self.gamma = spec("gamma").check(gamma)
        self.epsilon = spec("epsilon").check(epsilon)
        self.initial_q = spec("initial_q").check(initial_q)
        self.reward = spec("reward").check(reward)
        self.window = spec("window").check(window)
        # The reward signal, kept per (state, action) pair: the paper's error is the
        # mean of the last one error.
        self._signal = SIGNAL_CLASSES[self.reward]
        self.reward_signal = make_interest(
            self.reward, 1 if self._signal.ONE_ERROR_REWARD else self.window,
            new_task_factor=0.0)
        self.predictor = LinearPredictor(n_actions, 1) if predictor is None else predictor
        if not callable(getattr(self.predictor, "update", None)):
            raise _validate.ArgumentTypeError(f"predictor must have a method update, got "
                                              f"{_validate.show(predictor)}")
        self._random = _validate.generator("seed", seed)
        # Lists of floats: the learner's inner loop reads and writes single entries.
        self._q = [[self.initial_q] * self.n_actions for _ in range(self.n_states)]

    @classmethod
    def from_settings(cls, n_states, n_actions, n_outputs=1, settings=None, seed=None):
        """The Q-learner of `settings` (a `QLearnerSettings` of one value each; default
        the library's), with a `LinearPredictor` of `n_outputs` at its learning rate."""
        settings = QLearnerSettings() if settings is None else _validate.instance(
            "settings", settings, QLearnerSettings)
        values = settings.as_dict()
        predictor = LinearPredictor(n_actions, n_outputs, values.pop("predictor_lr"))
        return cls(n_states, n_actions, predictor, seed=seed, **values)

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
        draws = self._random.random(action_selection.DRAWS_PER_CHOICE)
        return epsilon_greedy(self._q[state], self.epsilon, draws)

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
        """Pays itself its intrinsic reward, teaches the predictor, updates Q.

        Args:
          state: the state the action was taken in.
          action: the action.
          observed: what the action did (the predictor's outcome, e.g. the rods).
          next_state: the state after the action.
          discount: 0 if the action ended the episode, else 1.

        Returns:
          The intrinsic reward: by default the absolute error of the prediction for
          (state, action) before this observation; with another `reward`, that
          signal of the pair after recording this error (see `REWARDS`). The error on
          each of the outcome's entries is kept in `last_errors`.
        """
        state, action = self._check(state, action)
        per_output = getattr(self.predictor, "update_per_output", None)
        if per_output is not None:  # kept: what each output of the move surprised
            self.last_errors = per_output(state, action, observed)
            error = sum(self.last_errors)
        else:
            error = self.predictor.update(state, action, observed)
            self.last_errors = [error]
        self.reward_signal.record((state, action), error)
        reward = self.reward_signal.interest((state, action))
        if self._signal.LEARNS_VALUES:
            self.update(state, action, reward, next_state, discount)
        return reward
