"""Predictors: models of what an action does in a context (paper sections 3.1 and 3.3)."""

import operator

from icm import _validate

DEFAULT_ACTION_WEIGHT = 10.0
"""Larger than any distance between two button-console contexts (7 entries), so the
nearest experience is always one with the same action when there is one."""


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

    Ties: among equally near experiences the most recently stored one wins.
    Empty memory: `predict` returns the `default` it is given (the agent passes the
    boxes as they are, i.e. "no change").

    Predictions are cached per query and updated exactly when an experience is stored,
    so a query costs O(1) and a store O(number of distinct queries seen).

    Args:
      action_weight: cost of a different action, in units of one differing context
        entry; a number > 0.

    Raises:
      ValueError: if action_weight is not a finite number > 0.
    """

    def __init__(self, action_weight=DEFAULT_ACTION_WEIGHT):
        self.action_weight = _validate.positive("action_weight", action_weight)
        self._experiences = []
        self._cache = {}

    def __len__(self):
        return len(self._experiences)

    def distance(self, context, action, other_context, other_action):
        """The distance between two (context, action) pairs (see the class docstring)."""
        if len(context) != len(other_context):
            raise ValueError(f"contexts must have the same length, got {len(context)} "
                             f"and {len(other_context)}")
        differing = sum(map(operator.ne, context, other_context))
        return differing + (self.action_weight if action != other_action else 0.0)

    def _nearest(self, context, action):
        best_distance, best_effect = float("inf"), None
        for other_context, other_action, effect in self._experiences:
            d = self.distance(context, action, other_context, other_action)
            if d <= best_distance:  # later experiences win ties
                best_distance, best_effect = d, effect
        return best_distance, best_effect

    def predict(self, context, action, default=None):
        """The effect of the nearest stored experience, or `default` if none is stored.

        Args:
          context: a tuple of categorical values.
          action: an integer.
          default: returned when nothing is stored yet.
        """
        if not self._experiences:
            return default
        key = (tuple(context), action)
        entry = self._cache.get(key)
        if entry is None:
            entry = list(self._nearest(*key))
            self._cache[key] = entry
        return entry[1]

    def update(self, context, action, effect):
        """Stores the experience (context, action) -> effect."""
        context, effect = tuple(context), tuple(effect)
        if self._experiences and len(context) != len(self._experiences[0][0]):
            raise ValueError(f"context must have {len(self._experiences[0][0])} entries "
                             f"like the stored ones, got {len(context)}")
        self._experiences.append((context, action, effect))
        weight, ne = self.action_weight, operator.ne
        for (query_context, query_action), entry in self._cache.items():
            # self.distance(...), inlined: this loop is the learner's inner loop.
            d = sum(map(ne, query_context, context)) + (weight if query_action != action else 0.0)
            if d <= entry[0]:
                entry[0], entry[1] = d, effect
