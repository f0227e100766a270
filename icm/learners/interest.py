"""Interest measures: how interesting a task is, from the history of prediction errors.

The paper's interest module (section 3.1): per task t a history H_t of prediction
errors; the interest is the slope of a least-squares line through the last k errors.
"""

import operator

import numpy as np

from icm import _validate
from icm.learners._common import check_state

DEFAULT_WINDOW = 5
DEFAULT_NEW_TASK_FACTOR = 0.5
READINGS = ("progress", "literal")
"""How the slope d of the error history becomes interest:
"progress": max(-d, 0), errors going down are interesting (learning progress);
"literal": max(d, 0), the paper's printed "d_t if d_t > 0", errors going up."""


def least_squares_slope(values):
    """The slope lambda_1 of the least-squares line lambda_0 + lambda_1 * x through
    (0, values[0]), (1, values[1]), ...

    Raises:
      ValueError: with fewer than 2 values, values that are not a 1-d sequence of
        numbers, or NaN or infinite values.
    """
    y = _validate.finite_array("values", values, ndim=1)
    if len(y) < 2:
        raise ValueError(f"values must hold at least 2 numbers for a slope, got {len(y)}")
    x = np.arange(len(y)) - (len(y) - 1) / 2.0
    return float(x @ (y - y.mean()) / (x @ x))


def _slope_weights(n):
    """Weights w with slope = w @ y for n equally spaced values (w sums to 0)."""
    x = np.arange(n) - (n - 1) / 2.0
    return tuple((x / (x @ x)).tolist())


class LearningProgressInterest:
    """Interest of each task as learning progress over its last `window` errors.

    For a task t with error history H_t (most recent last):
      - never witnessed: interest 0;
      - witnessed once (a new task): `new_task_factor` times the mean interest of the
        other known tasks (those witnessed at least twice), 0 if there are none;
      - otherwise: d = least-squares slope of the last `window` errors (of all of
        them while there are fewer), and interest max(-d, 0) (reading "progress") or
        max(d, 0) (reading "literal", the paper's printed formula).

    Tasks are any hashable keys, added as they are first recorded (the paper's goal
    space "constructed dynamically as new tasks are observed").

    Args:
      window: k, the number of most recent errors in the slope (integer >= 2; paper: 5).
      new_task_factor: share of the mean interest of the other tasks that a task
        witnessed once receives (in [0, 1]; paper: 0.5).
      reading: "progress" (default) or "literal"; see `READINGS`.

    Raises:
      ValueError: for a window < 2, a factor outside [0, 1] or an unknown reading.
    """

    def __init__(self, window=DEFAULT_WINDOW, new_task_factor=DEFAULT_NEW_TASK_FACTOR,
                 reading="progress"):
        self.window = _validate.integer_at_least("window", window, 2)
        self.new_task_factor = _validate.in_closed_interval(
            "new_task_factor", new_task_factor, 0.0, 1.0)
        self.reading = _validate.one_of("reading", reading, READINGS)
        self._sign = -1.0 if reading == "progress" else 1.0
        self._weights = {n: _slope_weights(n) for n in range(2, self.window + 1)}
        self._history = {}
        self._known = {}  # interest of tasks witnessed at least twice
        self._interest = {}

    @property
    def tasks(self):
        """The tasks witnessed so far, in the order they were first witnessed."""
        return list(self._history)

    def history(self, task):
        """A copy of the error history H_t of `task` (empty if never witnessed)."""
        return list(self._history.get(check_state("task", task), ()))

    def record(self, task, error):
        """Appends the prediction error made when `task` was witnessed.

        Raises:
          ValueError: for an unhashable task, or an error that is not a finite
            number >= 0.
        """
        task = check_state("task", task)
        error = _validate.non_negative("error", error)
        history = self._history.setdefault(task, [])
        history.append(error)
        if len(history) >= 2:
            self._known[task] = self._known_interest(history)
        self._update_new_task_interests()

    def _known_interest(self, history):
        recent = history[-self.window:]
        slope = sum(map(operator.mul, self._weights[len(recent)], recent))
        return max(0.0, self._sign * slope)

    def _update_new_task_interests(self):
        interests = dict(self._known)
        total, count = sum(self._known.values()), len(self._known)
        for task, history in self._history.items():
            if len(history) == 1:  # a new task: never in self._known
                interests[task] = self.new_task_factor * (total / count if count else 0.0)
        self._interest = interests

    def interest(self, task):
        """The current interest of `task` (0.0 for a task never witnessed)."""
        return self._interest.get(check_state("task", task), 0.0)
