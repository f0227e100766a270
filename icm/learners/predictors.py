"""Predictors: models of what an action does in a context (paper sections 3.1 and 3.3)."""

import math
import operator

import numpy as np

from icm import _validate
from icm._settings import Setting, Slider
from icm.learners._common import check_state, check_values

TIES = ("latest", "earliest")
"""Which of equally near experiences a nearest-neighbour prediction takes (`TIE`)."""
ACTION_WEIGHT = Setting(
    default=10.0, label="the predictor's cost of a different button (action weight)",
    kind="real", low=0.0, low_open=True,
    source='the paper\'s predictor is "a simple nearest neighbour research on past '
           'experiences" (section 3.1) and does not say how it compares them. The book '
           'counts the lights that differ, plus this weight if the button differs: 10, '
           'larger than any difference in lights, so the same button counts first',
    swept=(1.0, 1.5, 2.0, 3.0, 10.0))
"""The cost of a different action, in units of one differing context entry. Two
button layouts differ in two lights, so what changes a learner is whether the weight
is below, at or above 2 (the sweep's grid)."""
TIE = Setting(
    default="latest", label="the experience a tie between nearest neighbours predicts",
    kind="choice", choices=TIES,
    source="the paper does not say which of equally near experiences its nearest "
           'neighbour takes: the book takes the most recent ("latest"); "earliest" '
           "keeps the first")
"""Which of equally near experiences a prediction takes (`TIES`)."""
LINEAR_LR = Setting(
    default=0.2, label="the linear predictor's learning rate", kind="real", low=0.0,
    high=1.0, low_open=True, paper=0.2,
    source='section 4.2: "A linear predictor with a learning rate = 0.2 is used"',
    slider=Slider(live=(0.05, 1.0, 0.05), grid=(0.1, 0.2, 0.3, 0.4, 0.5)))
"""The learning rate of `LinearPredictor` (the paper's value)."""
DEFAULT_ACTION_WEIGHT = ACTION_WEIGHT.default


class NearestNeighbourPredictor:
    """Predicts the effect of an action from the nearest stored experience.

    The paper's prediction module (section 3.1): "a simple nearest neighbour research
    on past experiences, assuming a non-stochastic, markovian property of the
    environment". An experience is (context, action) -> effect.

    Encoding: a context is a tuple of categorical values (for the buttons, the 5
    lights); an action is an integer; an effect is a tuple (for the buttons, the 2 box
    states after the press).

    Distance between (c, a) and (c', a'):
        number of positions where c and c' differ  +  action_weight * [a != a']

    The default `action_weight` (10) is larger than any context distance here, so the
    predictor first looks for the same button and only then for the most similar
    lights: one press of the red button teaches "this button opens red" in every
    layout, while the green button, which moves, must be learned layout by layout.
    With `action_weight=1` every entry of (context, action) counts the same (a plain
    Hamming distance); the same-layout experiences of other buttons are then nearer
    than the red button pressed under another layout, and red too must be learned
    layout by layout. The book's chapter "Goal-oriented interest" shows both.

    Ties: among equally near experiences the most recently stored one wins (`tie`
    "latest", the book's choice) or the first stored ("earliest").
    Empty memory: `predict` returns the `default` it is given (the agent passes the
    boxes as they are, i.e. "no change").

    Predictions are cached per query and updated exactly when an experience is stored,
    so a query costs O(1) and a store O(number of distinct queries seen).

    Args:
      action_weight: cost of a different action, in units of one differing context
        entry (`ACTION_WEIGHT`).
      tie: "latest" (default) or "earliest" (`TIE`).

    Raises:
      ValueError: if action_weight is not a finite number > 0, or tie is unknown.
    """

    def __init__(self, action_weight=ACTION_WEIGHT.default, tie=TIE.default):
        self.action_weight = ACTION_WEIGHT.check(action_weight, "action_weight")
        self.tie = TIE.check(tie, "tie")
        self._nearer = operator.le if self.tie == "latest" else operator.lt
        self._experiences = []
        self._cache = {}

    def __len__(self):
        return len(self._experiences)

    def distance(self, context, action, other_context, other_action):
        """The distance between two (context, action) pairs (see the class docstring)."""
        context = check_values("context", context, allow_text=True)
        other_context = check_values("other_context", other_context, allow_text=True)
        action = _validate.integer("action", action, 0)
        other_action = _validate.integer("other_action", other_action, 0)
        if len(context) != len(other_context):
            raise ValueError(f"contexts must have the same length, got {len(context)} "
                             f"and {len(other_context)}")
        differing = sum(map(operator.ne, context, other_context))
        return differing + (self.action_weight if action != other_action else 0.0)

    def _nearest(self, context, action):
        best_distance, best_effect = float("inf"), None
        for other_context, other_action, effect in self._experiences:
            d = self.distance(context, action, other_context, other_action)
            if self._nearer(d, best_distance):  # "latest": later experiences win ties
                best_distance, best_effect = d, effect
        return best_distance, best_effect

    def predict(self, context, action, default=None):
        """The effect of the nearest stored experience, or `default` if none is stored.

        Args:
          context: a tuple of categorical values (finite numbers or strings).
          action: an integer >= 0.
          default: returned when nothing is stored yet.

        Raises:
          ValueError: for a context that is not a sequence of finite numbers or
            strings, or an action that is not an integer >= 0.
        """
        context = check_values("context", context, allow_text=True)
        action = _validate.integer("action", action, 0)
        if not self._experiences:
            return default
        key = (context, action)
        entry = self._cache.get(key)
        if entry is None:
            entry = list(self._nearest(*key))
            self._cache[key] = entry
        return entry[1]

    def update(self, context, action, effect):
        """Stores the experience (context, action) -> effect.

        Raises:
          ValueError: for a context that is not a sequence of finite numbers or strings
            (or not as long as the stored ones), an action that is not an integer >= 0,
            or an effect that is not a sequence of finite numbers.
        """
        context = check_values("context", context, allow_text=True)
        action = _validate.integer("action", action, 0)
        effect = check_values("effect", effect)
        if self._experiences and len(context) != len(self._experiences[0][0]):
            raise ValueError(f"context must have {len(self._experiences[0][0])} entries "
                             f"like the stored ones, got {len(context)}")
        self._experiences.append((context, action, effect))
        weight, ne, nearer = self.action_weight, operator.ne, self._nearer
        for (query_context, query_action), entry in self._cache.items():
            # self.distance(...), inlined: this loop is the learner's inner loop.
            d = sum(map(ne, query_context, context)) + (weight if query_action != action else 0.0)
            if nearer(d, entry[0]):
                entry[0], entry[1] = d, effect


DEFAULT_LINEAR_LR = LINEAR_LR.default
UNTRIED_ERROR = 1.0
"""The error `LinearPredictor.confidence` counts for an action never tried from a
state: nothing is known about it, as if the last prediction had been wholly wrong."""


class LinearPredictor:
    """A table of predicted outcomes per (state, action), each moved a step towards
    what is observed: the paper's "tabular linear predictor" (sections 2.2 and 4.2).

    For the rods, a state is the hand's cell, an action a move, and the outcome one
    number per rod: 0 standing, 1 toppled. Every prediction starts at
    `initial_prediction` (0: "the rods stay up") and after each observation o of
    (s, a) becomes

        p(s, a) <- p(s, a) + lr * (o - p(s, a)),

    so after n observations of the same outcome the remaining error is (1 - lr)^n
    times the first one (with lr = 0.2, 0.8^n: 11 topples bring it below 0.1).

    The *error* of a prediction is its absolute error summed over the outcome's
    entries, ``sum_i abs(o_i - p_i(s, a))``; on the rods only one rod falls at a time, so it
    is the error on that rod, in [0, 1]. `update` returns the error of the prediction
    it corrects: that is the intrinsic reward of the Q-learner.

    The predictor also keeps, for every (state, action), the error of its latest
    prediction there, from which `confidence` (the paper's "state confidence", Figure
    7) is computed.

    States are any hashable values, actions integers 0..n_actions-1.

    Args:
      n_actions: number of actions (integer >= 1).
      n_outputs: entries of an outcome (integer >= 1; the rods: 2).
      lr: learning rate in (0, 1] (paper: 0.2).
      initial_prediction: the prediction before any observation (a number in [0, 1]).

    Raises:
      ValueError: for an argument outside its range, or (in `update`) an outcome of
        the wrong length.
    """

    def __init__(self, n_actions, n_outputs, lr=DEFAULT_LINEAR_LR, initial_prediction=0.0):
        self.n_actions = _validate.integer_at_least("n_actions", n_actions, 1)
        self.n_outputs = _validate.integer_at_least("n_outputs", n_outputs, 1)
        self.lr = LINEAR_LR.check(lr, "lr")
        self.initial_prediction = _validate.in_closed_interval(
            "initial_prediction", initial_prediction, 0.0, 1.0)
        self._predictions = {}  # state -> [action][output], lists of floats
        self._last_errors = {}  # state -> [action] latest error, None if untried

    def _row(self, state):
        row = self._predictions.get(state)
        if row is None:
            row = [[self.initial_prediction] * self.n_outputs for _ in range(self.n_actions)]
            self._predictions[state] = row
            self._last_errors[state] = [None] * self.n_actions
        return row

    def _check_action(self, action):
        return _validate.integer("action", action, 0, self.n_actions - 1)

    def predict(self, state, action):
        """The predicted outcome of `action` in `state`, a float array [n_outputs]."""
        action = self._check_action(action)
        row = self._predictions.get(check_state("state", state))
        if row is None:
            return np.full(self.n_outputs, self.initial_prediction)
        return np.array(row[action])

    def error(self, state, action, observed):
        """The absolute error ``sum_i abs(observed_i - p_i)`` of the current prediction."""
        predicted = self.predict(state, action)
        observed = self._check_outcome(observed)
        return float(sum(abs(o - p) for o, p in zip(observed, predicted)))

    def _check_outcome(self, observed):
        observed = check_values("observed", observed)
        if len(observed) != self.n_outputs:
            raise ValueError(f"observed must have {self.n_outputs} entries, got "
                             f"{len(observed)}: {_validate.show(observed)}")
        return [float(v) for v in observed]

    def update(self, state, action, observed):
        """Moves the prediction of (state, action) towards `observed`.

        Args:
          state: a hashable state.
          action: an integer action.
          observed: the outcome, n_outputs numbers.

        Returns:
          The absolute error of the prediction before the update (the surprise).
        """
        return sum(self.update_per_output(state, action, observed))

    def update_per_output(self, state, action, observed):
        """`update`, returning the absolute error of each entry of the prediction
        before the update (a list of n_outputs floats) instead of their sum."""
        action = self._check_action(action)
        observed = self._check_outcome(observed)
        state = check_state("state", state)
        current = self._predictions.get(state)
        current = current[action] if current is not None else \
            [self.initial_prediction] * self.n_outputs
        differences = [o - p for o, p in zip(observed, current)]
        errors = [abs(d) for d in differences]
        if not math.isfinite(sum(errors)) or not all(
                math.isfinite(p + self.lr * d) for p, d in zip(current, differences)):
            raise ValueError(f"observed must hold numbers whose prediction errors are "
                             f"finite; {_validate.show(observed)} against the prediction "
                             f"{_validate.show(current)} overflows")
        predicted = self._row(state)[action]
        for i, d in enumerate(differences):
            predicted[i] += self.lr * d
        self._last_errors[state][action] = sum(errors)
        return errors

    def last_error(self, state, action):
        """The error of the latest prediction for (state, action); None if never tried."""
        action = self._check_action(action)
        errors = self._last_errors.get(check_state("state", state))
        return None if errors is None else errors[action]

    def confidence(self, state):
        """The *state confidence* of `state`, in [0, 1]: how well the predictor knows
        what every action does there.

        It is 1 minus the mean, over the actions, of the error of the latest
        prediction for (state, action), each error capped at 1; an action never tried
        from the state counts as an error of `UNTRIED_ERROR` (1). A state never
        visited has confidence 0; a state whose every action was tried and predicted
        right the last time has confidence 1. On the rods, a cell from which one move
        topples a rod that was predicted with error e (the other moves known) has
        confidence 1 - e / 4.
        """
        errors = self._last_errors.get(check_state("state", state), [None] * self.n_actions)
        capped = [UNTRIED_ERROR if e is None else min(e, 1.0) for e in errors]
        return 1.0 - sum(capped) / self.n_actions

    def table(self, states):
        """The predictions for every action in each of `states`, a float array
        [len(states), n_actions, n_outputs] (states never updated: the initial
        prediction)."""
        if isinstance(states, (str, bytes)) or not hasattr(states, "__iter__"):
            raise _validate.ArgumentTypeError(f"states must be a list of states, got "
                                              f"{_validate.show(states)}")
        fresh = [[self.initial_prediction] * self.n_outputs] * self.n_actions
        return np.array([self._predictions.get(check_state("states[i]", s), fresh)
                         for s in states], dtype=float).reshape(
            -1, self.n_actions, self.n_outputs)

    def states(self):
        """The states seen so far (by `update`), in the order first seen."""
        return list(self._predictions)


def hamming_distances(contexts):
    """The number of differing entries between every pair of `contexts` (an array
    [n_contexts, entries]), as floats [n_contexts, n_contexts]."""
    contexts = np.asarray(contexts)
    return (contexts[:, None, :] != contexts[None, :, :]).sum(axis=-1).astype(float)


class NearestNeighbourTable:
    """`NearestNeighbourPredictor` for many agents at once, in a finite world.

    The contexts an agent can meet are listed in advance (`contexts`, one row each),
    and so are the effects an action can have (numbered by the caller); a key is a
    (context, action) pair, number context * n_actions + action. For every agent and
    every key the table keeps the distance of the nearest experience stored so far
    and its effect, updated exactly when an experience is stored (`update`), which is
    what the one-agent predictor's cache does: ties go to the latest experience, and
    an empty memory predicts `default_effect`.

    Args:
      n_rows: agents.
      contexts: the contexts, an array [n_contexts, entries].
      n_actions: actions per context.
      action_weight: the cost of a different action, one for all agents or one per
        agent (an array [n_rows]).
      default_effect: the effect predicted before anything is stored.
      tie: "latest" or "earliest" (`TIE`), one for all agents or one per agent.
    """

    def __init__(self, n_rows, contexts, n_actions, action_weight=ACTION_WEIGHT.default,
                 default_effect=0, tie=TIE.default):
        self.n_actions = n_actions
        ties = np.broadcast_to(np.asarray(TIE.check_rows(tie, "tie"), dtype=object), (n_rows,))
        self._earliest = None if np.all(ties == "latest") else ties == "earliest"
        lights = hamming_distances(contexts)
        n_contexts = len(lights)
        context_of = np.repeat(np.arange(n_contexts), n_actions)
        action_of = np.tile(np.arange(n_actions), n_contexts)
        self.context_distance = lights[context_of[:, None], context_of[None, :]]
        self.different_action = (action_of[:, None] != action_of[None, :]).astype(float)
        self.action_weight = np.broadcast_to(np.asarray(
            ACTION_WEIGHT.check_rows(action_weight, "action_weight"), dtype=float), (n_rows,))
        # One weight for every agent: the distances between keys, computed once.
        self.key_distance = None
        if np.all(self.action_weight == self.action_weight[0]):
            self.key_distance = (self.context_distance
                                 + self.action_weight[0] * self.different_action)
        n_keys = n_contexts * n_actions
        self.distance = np.full((n_rows, n_keys), np.inf)
        self.effect = np.full((n_rows, n_keys), default_effect, dtype=np.int64)

    def keys(self, contexts, actions):
        """The key numbers of (context, action) pairs (element-wise)."""
        return np.asarray(contexts) * self.n_actions + np.asarray(actions)

    def predict(self, rows, keys):
        """The predicted effect of `keys[i]` for agent `rows[i]` (any matching shapes)."""
        return self.effect[rows, keys]

    def update(self, rows, keys, effects):
        """Stores the experience keys[i] -> effects[i] for agent rows[i] (distinct
        rows; None: every agent, in order)."""
        weight = self.action_weight if rows is None else self.action_weight[rows]
        if self.key_distance is not None:
            distance = self.key_distance.take(keys, axis=0)
        else:
            distance = (self.context_distance[keys]
                        + weight[:, None] * self.different_action[keys])
        effects = np.asarray(effects)[:, None]
        stored = self.distance if rows is None else self.distance[rows]
        nearer = distance <= stored  # tie "latest": later experiences win ties
        if self._earliest is not None:  # tie "earliest": only strictly nearer ones
            earliest = (self._earliest if rows is None else self._earliest[rows])[:, None]
            nearer &= ~earliest | (distance < stored)
        if rows is None:  # every agent, in place
            np.minimum(self.distance, distance, out=self.distance)
            np.copyto(self.effect, effects, where=nearer)  # the new effect where nearer
            return
        self.distance[rows] = np.where(nearer, distance, self.distance[rows])
        self.effect[rows] = np.where(nearer, effects, self.effect[rows])
