"""The actor-critic of the paper (section 3.2, Figures 3 and 4), with an extrinsic or
an intrinsic reward."""

import math

import numpy as np

from icm import _exact, _streams, _validate
from icm.learners._common import check_keys, check_state, check_values, read_observation
from icm.learners import action_selection
from icm.learners.action_selection import (epsilon_greedy, epsilon_greedy_rows, softmax,
                                           softmax_unchecked)  # noqa: F401 (softmax: its API)
from icm._settings import Settings, Slider, setting, setting_from, settings_class
from icm.learners import predictors as _predictors
from icm.learners.predictors import NearestNeighbourPredictor, NearestNeighbourTable

ACTION_SELECTIONS = ("softmax", "epsilon_greedy")
"""How the actor picks a press from its preferences. The paper's Figure 4 (the
intrinsic learner) uses a softmax; its section 3.2 gives the extrinsic learner "an
epsilon-greedy algorithm so that the agent explores". The default is the softmax for
both; the chapter compares the two on the extrinsic learner."""
REWARDS = ("intrinsic", "extrinsic")
"""Where the reward comes from: the predictor's errors (Figure 3b) or the environment
(Figure 3a)."""
VARIANTS = {
    "standard": ("standard", "error"),
    "printed_td": ("printed", "error"),
    "printed_reward": ("standard", "correct"),
    "printed": ("printed", "correct"),
}
"""The four readings of the paper's formulas, as (TD form, intrinsic reward on):

TD form "standard": r + gamma * V(s') - V(s), the usual TD error.
TD form "printed": r + gamma * (V(s) - V(s')), equation 2 as printed.
reward on "error": the intrinsic reward is 1 when the prediction is wrong (the text:
"the interest of the agent is maximal in situations where it makes mistakes").
reward on "correct": 1 when the prediction is right (the formula as printed).

"standard" (the default) is the standard reading of both; "printed" takes both
formulas as printed; the other two change one at a time. With an extrinsic reward
only the TD form matters."""
_RATE = dict(kind="real", low=0.0, high=1.0, low_open=True,
             slider=Slider(live=(0.05, 1.0, 0.05), grid=(0.1, 0.3, 0.5, 0.7, 0.9)))


@settings_class
class ActorCriticSettings(Settings):
    """The actor-critic's settings (section 3.2, Figures 3 and 4). Each is a
    `icm._settings.Setting`: see `ActorCriticSettings.specs()` for its range, the
    paper's value and where it comes from. Values may be one per batch row (arrays) in
    `ActorCriticBatch`."""

    temperature: float = setting(
        default=0.2, label="softmax temperature", kind="real", low=0.0, low_open=True,
        source="Figure 4's actor picks by softmax and the paper gives no temperature. With "
               "rewards of 0 or 1 and the default learning rates, one surprise raises a "
               "preference by 0.5, which makes that button e^(0.5/0.2) = 12 times likelier "
               "than an untried one: the learner repeats what surprised it, as the paper "
               "describes, yet still tries the others",
        slider=Slider(live=(0.05, 2.0, 0.05), grid=(0.1, 0.2, 0.3, 0.4, 0.5)),
        others=(0.1, 1.0))
    lr_actor: float = setting(
        default=0.5, label="the actor's learning rate (lrA)",
        source="Figure 4 names lrA and gives no value: the book takes 0.5",
        others=(0.1, 0.9), **_RATE)
    lr_critic: float = setting(
        default=0.5, label="the critic's learning rate (lrC)",
        source="Figure 4 names lrC and gives no value: the book takes 0.5",
        others=(0.1, 0.9), **_RATE)
    gamma: float = setting(
        default=0.5, label="discount (gamma)", kind="real", low=0.0, high=1.0,
        source="equation 2's gamma has no value in the paper: the book takes 0.5, a short "
               "horizon, since no press changes what the next one does (the console shuts "
               "the boxes before every press)",
        others=(0.0, 0.9))
    reward: str = setting(
        default="intrinsic", label="where the reward comes from", kind="choice",
        choices=REWARDS, paper="intrinsic", per_row=False,
        source="Figure 3b and Figure 4: the reward is internal, from the predictor; 3a is "
               "the extrinsic learner")
    variant: str = setting(
        default="standard", label="reading of the TD error and reward formulas",
        kind="choice", choices=tuple(VARIANTS),
        source="equation 2 and Figure 4's reward, as printed, contradict the text; the "
               "book takes the standard readings and shows all four (`VARIANTS`)",
        swept=("standard", "printed_td"))
    action_selection: str = setting(
        default="softmax", label="how the actor picks a press", kind="choice",
        choices=ACTION_SELECTIONS, paper="softmax", per_row=False,
        source='Figure 4 (the intrinsic learner) uses a softmax; section 3.2 gives the '
               'extrinsic learner "an epsilon-Greedy algorithm"')
    epsilon: float = setting(
        default=0.1, label="probability of a random press with epsilon-greedy selection",
        kind="real", low=0.0, high=1.0,
        source="section 3.2 names an epsilon-greedy rule and gives no epsilon: the book "
               "takes 0.1")
    action_weight: float = setting_from(_predictors.ACTION_WEIGHT)
    tie: str = setting_from(_predictors.TIE)


DEFAULT_TEMPERATURE = ActorCriticSettings.spec("temperature").default
DEFAULT_LR_ACTOR = ActorCriticSettings.spec("lr_actor").default
DEFAULT_LR_CRITIC = ActorCriticSettings.spec("lr_critic").default
DEFAULT_GAMMA = ActorCriticSettings.spec("gamma").default
DEFAULT_EPSILON = ActorCriticSettings.spec("epsilon").default


def _check_finite(td_error):
    """Returns `td_error` if it is finite, else raises FloatingPointError."""
    if not math.isfinite(td_error):
        raise FloatingPointError(
            f"the TD error overflowed ({td_error!r}): the critic diverged. The printed TD "
            f"form feeds V(s) back into itself, multiplying it by up to "
            f"1 + lr_critic * gamma at every visit; use the standard form or fewer trials")
    return td_error


class ActorCritic:
    """A tabular actor-critic whose reward is extrinsic or intrinsic (Figures 3, 4).

    The state s is the observation as a tuple (for the buttons: the 5 lights, then the
    2 boxes as they are shown). The actor keeps a preference per (state, action) and
    picks an action by softmax with a `temperature`; the critic keeps a value V(s).
    Both start at 0 and are updated after every action with the TD error (see
    `VARIANTS` for its two forms).

    The reward:
      - "extrinsic" (Figure 3a): the reward the environment pays (for the buttons:
        a `ButtonConsole(rewarded_box=...)`).
      - "intrinsic" (Figure 3b, Figure 4): the predictor guesses what the action will
        do to the `effect_key` entry (for the buttons: the boxes) from the state; the
        internal reward is 1 when that guess is wrong (default) or right (printed),
        else 0. The lights do not change when a button is pressed, so predicting the
        next observation (x2, y2) amounts to predicting the boxes y2.

    The predictor learns from every action in both cases, so the prediction errors
    of an extrinsic learner can be measured too.

    Args:
      n_actions: number of discrete actions (integer >= 1).
      temperature: softmax temperature, a finite number > 0.
      action_selection: "softmax" (default) or "epsilon_greedy"; see
        `ACTION_SELECTIONS`.
      epsilon: probability of a random press with epsilon-greedy selection, in [0, 1].
      lr_actor: actor learning rate (lrA), in (0, 1].
      lr_critic: critic learning rate (lrC), in (0, 1].
      gamma: discount, in [0, 1].
      reward: "intrinsic" or "extrinsic"; see `REWARDS`.
      variant: one of `VARIANTS` ("standard", "printed_td", "printed_reward",
        "printed").
      predictor: has `predict(context, action, default)` and `update(context, action,
        effect)`; default a `NearestNeighbourPredictor()`.
      state_keys: observation entries that make the state, in order.
      effect_key: the observation entry the predictor predicts.
      effect_at_rest: what the predictor predicts before it has stored anything
        (default: zeros the size of the effect, i.e. "no box opens").
      seed: None, an int >= 0, or a `numpy.random.Generator`, for the softmax draws.

    Raises:
      ValueError: for any argument outside its allowed range.
    """

    def __init__(self, n_actions, temperature=DEFAULT_TEMPERATURE, lr_actor=DEFAULT_LR_ACTOR,
                 lr_critic=DEFAULT_LR_CRITIC, gamma=DEFAULT_GAMMA, reward="intrinsic",
                 variant="standard", predictor=None, state_keys=("lights", "boxes"),
                 effect_key="boxes", effect_at_rest=None, action_selection="softmax",
                 epsilon=DEFAULT_EPSILON, seed=None):
        self.n_actions = _validate.integer_at_least("n_actions", n_actions, 1)
        spec = ActorCriticSettings.spec
        self.temperature = spec("temperature").check(temperature)
        self.action_selection = spec("action_selection").check(action_selection)
        self.epsilon = spec("epsilon").check(epsilon)
        self.lr_actor = spec("lr_actor").check(lr_actor)
        self.lr_critic = spec("lr_critic").check(lr_critic)
        self.gamma = spec("gamma").check(gamma)
        self.reward = spec("reward").check(reward)
        self.variant = spec("variant").check(variant)
        self.td_form, self.reward_on = VARIANTS[self.variant]
        self.predictor = NearestNeighbourPredictor() if predictor is None else predictor
        if not all(callable(getattr(self.predictor, m, None)) for m in ("predict", "update")):
            raise _validate.ArgumentTypeError(f"predictor must have the methods predict and "
                                              f"update, got {_validate.show(predictor)}")
        self.state_keys = check_keys("state_keys", state_keys)
        self.effect_key = _validate.text("effect_key", effect_key)
        self.effect_at_rest = None if effect_at_rest is None else check_values(
            "effect_at_rest", effect_at_rest)
        self._random = _validate.generator("seed", seed)
        self.critic = {}  # state -> V(state)
        self.actor = {}  # state -> list of preferences, one per action

    @classmethod
    def from_settings(cls, n_actions, settings=None, seed=None, **arguments):
        """The actor-critic of `settings` (an `ActorCriticSettings` of one value each;
        default the library's), with its nearest-neighbour predictor built from them.
        `arguments` are the constructor's others (state_keys, effect_key, ...)."""
        settings = ActorCriticSettings() if settings is None else _validate.instance(
            "settings", settings, ActorCriticSettings)
        values = settings.as_dict()
        predictor = NearestNeighbourPredictor(values.pop("action_weight"), values.pop("tie"))
        return cls(n_actions, predictor=predictor, seed=seed, **values, **arguments)

    def state(self, observation):
        """The state of an observation: its `state_keys` entries as one flat tuple."""
        return read_observation("observation", observation, self.state_keys)

    def value(self, state):
        """The critic's V(state) (0.0 for a state never updated)."""
        return self.critic.get(check_state("state", state), 0.0)

    def preferences(self, state):
        """A copy of the actor's preferences in `state`, one per action."""
        return list(self.actor.get(check_state("state", state), [0.0] * self.n_actions))

    def policy(self, state):
        """The probability of each action in `state` (a numpy array): the softmax of
        its preferences at the learner's temperature, or with epsilon-greedy selection
        epsilon / n for every action plus (1 - epsilon) shared by the most preferred."""
        if self.action_selection == "epsilon_greedy":
            preferences = np.array(self.preferences(state))
            best = preferences == preferences.max()
            return self.epsilon / self.n_actions + (1 - self.epsilon) * best / best.sum()
        return np.array(self._policy(state))

    def _policy(self, state):
        preferences = self.actor.get(check_state("state", state))
        if preferences is None:
            return [1.0 / self.n_actions] * self.n_actions
        return softmax_unchecked(preferences, self.temperature).tolist()

    def select_action(self, observation):
        """Picks an action in the observation's state: drawn from the softmax policy,
        or, with `action_selection="epsilon_greedy"`, uniformly at random with
        probability epsilon and otherwise one of the most preferred (ties at random).
        Either way it draws `DRAWS_PER_CHOICE` numbers (the softmax uses the first)."""
        draws = self._random.random(action_selection.DRAWS_PER_CHOICE)
        if self.action_selection == "epsilon_greedy":
            return epsilon_greedy(self.preferences(self.state(observation)), self.epsilon,
                                  draws)
        probabilities = self._policy(self.state(observation))
        threshold = draws[0]
        cumulative = 0.0
        for action, probability in enumerate(probabilities):
            cumulative += probability
            if threshold < cumulative:
                return action
        return self.n_actions - 1  # rounding: the cumulative sum fell short of 1

    def effect(self, observation):
        """The `effect_key` entry of an observation (for the buttons, the boxes) as a
        tuple; the first one seen also sets `effect_at_rest` if it was not given."""
        effect = read_observation("observation", observation, (self.effect_key,))
        if self.effect_at_rest is None:
            self.effect_at_rest = (0,) * len(effect)
        return effect

    def predict(self, state, action):
        """The predictor's guess of the effect entry after `action` in `state`; with
        nothing stored yet, `effect_at_rest` (no change: for the buttons, boxes shut)."""
        action = _validate.integer("action", action, 0, self.n_actions - 1)
        return self.predictor.predict(state, action, default=self.effect_at_rest)

    def internal_reward(self, state, action, effect):
        """Figure 4's internal reward for a prediction of `effect` (a tuple).

        Returns:
          With `reward_on` "error": 1.0 if the prediction is wrong, else 0.0; with
          "correct" (as printed): 1.0 if it is right, else 0.0.
        """
        effect = check_values("effect", effect)
        right = tuple(self.predict(state, action)) == effect
        if self.reward_on == "correct":
            return 1.0 if right else 0.0
        return 0.0 if right else 1.0

    def td_error(self, reward, state, next_state, discount=1.0):
        """The TD error of one step, in the variant's form.

        Args:
          reward: r, the reward of the step.
          state: s, the state the action was taken in.
          next_state: s', the state after it.
          discount: the environment's discount (0 at a true end of episode, where
            V(s') is not counted; the button console never ends an episode).

        Returns:
          The TD error, a float.

        Raises:
          ValueError: for a reward that is not a finite number or a discount outside
            [0, 1].
          FloatingPointError: if the TD error is not finite (a diverged critic).
        """
        reward = _validate.real("reward", reward)
        discount = _validate.in_closed_interval("discount", discount, 0.0, 1.0)
        gamma = self.gamma * discount
        if self.td_form == "printed":
            # equation 2 as printed: r + gamma * (V(s) - V(s'))
            td_error = reward + gamma * (self.value(state)
                                         - self.value(next_state))
        else:  # the standard TD error: r + gamma * V(s') - V(s)
            td_error = reward + gamma * self.value(next_state) - self.value(state)
        return _check_finite(td_error)

    def _check_step(self, action, external_reward, discount):
        return (_validate.integer("action", action, 0, self.n_actions - 1),
                _validate.real("external_reward", external_reward),
                _validate.in_closed_interval("discount", discount, 0.0, 1.0))

    def learn(self, observation, action, next_observation, external_reward=0.0,
              discount=1.0):
        """One step of Figure 4, after `action` took `observation` to `next_observation`.

        Args:
          observation: the observation the action was chosen in.
          action: the action taken.
          next_observation: the observation after the action.
          external_reward: the environment's reward (used when `reward` is "extrinsic").
          discount: the environment's discount of the step.

        Returns:
          (reward, td_error): the reward used and the TD error of the step.

        Raises:
          ValueError: for observations without the learner's entries, an action that
            is not an integer in 0..n_actions-1, an external reward that is not a
            finite number, or a discount outside [0, 1].
        """
        action, external_reward, discount = self._check_step(
            action, external_reward, discount)
        state = self.state(observation)
        next_state = read_observation("next_observation", next_observation,
                                      self.state_keys)
        effect = self.effect(next_observation)
        if self.reward == "intrinsic":  # Figure 3b: the agent pays itself
            reward = self.internal_reward(state, action, effect)
        else:  # Figure 3a: the environment pays
            reward = float(external_reward)
        td_error = self.td_error(reward, state, next_state, discount)
        # critic(s) <- critic(s) + lrC * tdError
        self.critic[state] = self.value(state) + self.lr_critic * td_error
        # actor(s, selectedA) <- actor(s, selectedA) + lrA * tdError
        preferences = self.actor.setdefault(state, [0.0] * self.n_actions)
        preferences[action] += self.lr_actor * td_error
        # the predictor remembers what the action did
        self.predictor.update(state, action, effect)
        return reward, td_error


class ActorCriticBatch:
    """The actor-critic for many agents (rows) at once, in a finite world: states and
    effects are indices into tables listed in advance.

    Row k makes exactly the choices and updates of an `ActorCritic` seeded like it (a
    test checks it): the same softmax (numpy's exp, summed in order), the same
    `DRAWS_PER_CHOICE` numbers per choice, the same TD error and updates, and
    `NearestNeighbourTable` for its predictor. Settings may differ per row, which lets
    a grid of settings times seeds run as one batch.

    Args:
      seeds: one seed per row.
      states: the states' features, an array [n_states, entries] (for the buttons:
        the 5 lights and the 2 boxes); the predictor compares states by them.
      effects: the effects (goal states) an action can lead to, [n_effects, entries];
        effect 0 is the one predicted before anything is stored.
      n_actions: actions per state.
      settings: an `ActorCriticSettings` (default the library's); its per-row
        settings may hold one value per row (arrays).
      **values: settings given one by one instead, checked like a new
        `ActorCriticSettings`.

    Raises:
      ValueError: for a setting its `icm._settings.Setting` refuses, or settings given
        both ways.
    """

    def __init__(self, seeds, states, effects, n_actions, settings=None, **values):
        self.streams = _streams.Streams(seeds)
        n = len(self.streams)
        if settings is None:
            settings = ActorCriticSettings.from_arguments(values, "ActorCriticBatch")
        elif values:
            raise ValueError(f"give the settings either as settings or one by one, got "
                             f"both (settings and {', '.join(values)})")
        self.settings = _validate.instance("settings", settings, ActorCriticSettings)
        self.temperature = settings.per_row("temperature", n)
        self.lr_actor = settings.per_row("lr_actor", n)
        self.lr_critic = settings.per_row("lr_critic", n)
        self.gamma = settings.per_row("gamma", n)
        self.epsilon = settings.per_row("epsilon", n)
        self.intrinsic = settings.per_row("reward", n) == "intrinsic"
        variants = settings.per_row("variant", n)
        self.printed_td = np.array([VARIANTS[v][0] == "printed" for v in variants])
        self.reward_if_right = np.array([VARIANTS[v][1] == "correct" for v in variants])
        self.action_selection = settings.action_selection
        self.n_actions = n_actions
        self.rows = np.arange(n)
        self.critic = np.zeros((n, len(states)))
        self.actor = np.zeros((n, len(states), n_actions))
        self.predictor = NearestNeighbourTable(n, states, n_actions,
                                               settings.per_row("action_weight", n),
                                               tie=settings.per_row("tie", n))
        # Shortcuts of `learn` that give the same numbers: each row's offset in the
        # flattened tables, and whether every row has the same reward and TD error.
        self._state_offset = self.rows * len(states)
        self._key_offset = self.rows * self.predictor.effect.shape[1]
        self._all_intrinsic = bool(np.all(self.intrinsic))
        self._one_td = bool(np.all(self.printed_td == self.printed_td[0]))

    def policy(self, states):
        """Each row's probability of each action in its state, [rows, actions]."""
        return self.policy_of(self.actor[self.rows, states])

    def policy_of(self, preferences):
        """The policy for preferences [rows, ..., actions]: their softmax at each row's
        temperature, or their epsilon-greedy probabilities."""
        per_row = lambda values: values.reshape((-1,) + (1,) * (preferences.ndim - 1))
        if self.action_selection == "epsilon_greedy":
            best = preferences == preferences.max(axis=-1, keepdims=True)
            greedy = per_row(1 - self.epsilon) * best / best.sum(axis=-1, keepdims=True)
            return per_row(self.epsilon / self.n_actions) + greedy
        top = preferences[..., 0]
        for a in range(1, self.n_actions):
            top = np.maximum(top, preferences[..., a])
        with np.errstate(over="ignore"):  # a difference of -inf gives exp 0.0
            weights = _exact.exp((preferences - top[..., None]) / per_row(self.temperature))
        total = weights[..., 0]
        for a in range(1, self.n_actions):  # in order, as the one-agent sum
            total = total + weights[..., a]
        if not np.isfinite(np.add.reduce(total, axis=None)):
            raise FloatingPointError("preferences must be finite: an actor diverged")
        return weights / total[..., None]

    def select_actions(self, states):
        """One action per row, in its state (`states`, [rows])."""
        draws = self.streams.draw(k=action_selection.DRAWS_PER_CHOICE)
        preferences = self.actor.reshape(-1, self.n_actions).take(
            self.rows * self.actor.shape[1] + states, axis=0)
        if self.action_selection == "epsilon_greedy":
            return epsilon_greedy_rows(preferences, self.epsilon, draws)
        # The first action whose cumulative probability exceeds the draw: as many
        # actions as have a cumulative probability at or below it (n - 1 if all do).
        policy, threshold = self.policy_of(preferences), draws[:, 0]
        cumulative = policy[:, 0]
        action = (cumulative <= threshold).astype(np.int64)
        for a in range(1, self.n_actions - 1):
            cumulative = cumulative + policy[:, a]
            action += cumulative <= threshold
        return action

    def predict(self, states, actions):
        """The predicted effect of `actions` in `states`, per row (any matching shapes
        of states and actions, rows along the first axis)."""
        keys = self.predictor.keys(states, actions)
        rows = self.rows.reshape((-1,) + (1,) * (np.ndim(keys) - 1))
        return self.predictor.predict(rows, keys)

    def learn(self, states, actions, next_states, effects, external_reward, discount):
        """One step of Figure 4 in every row; returns (rewards, td errors) [rows].

        Raises:
          FloatingPointError: if a TD error is not finite (a diverged critic).
        """
        keys = self.predictor.keys(states, actions)
        right = self.predictor.effect.reshape(-1).take(self._key_offset + keys) == effects
        internal = (right == self.reward_if_right).astype(float)  # 1 when paid
        reward = internal if self._all_intrinsic else \
            np.where(self.intrinsic, internal, external_reward)
        gamma = self.gamma * discount
        here, there = self._state_offset + states, self._state_offset + next_states
        critic = self.critic.reshape(-1)
        value, next_value = critic.take(here), critic.take(there)
        if self._one_td:  # every row the same TD error (computed as in the np.where)
            td_error = reward + gamma * (value - next_value) if self.printed_td[0] \
                else reward + gamma * next_value - value
        else:
            td_error = np.where(self.printed_td, reward + gamma * (value - next_value),
                                reward + gamma * next_value - value)
        if not np.isfinite(np.add.reduce(td_error)) and not np.all(np.isfinite(td_error)):
            _check_finite(float(td_error[~np.isfinite(td_error)][0]))
        # critic(s) <- critic(s) + lrC * tdError; actor(s, a) <- actor(s, a) + lrA * tdError
        critic[here] = value + self.lr_critic * td_error
        actor = self.actor.reshape(-1)
        chosen = here * self.n_actions + actions
        actor[chosen] = actor.take(chosen) + self.lr_actor * td_error
        self.predictor.update(None, keys, effects)
        return reward, td_error
