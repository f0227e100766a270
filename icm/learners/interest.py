"""Interest measures: how interesting a task is, from the history of prediction errors.

The paper's interest module (section 3.1): per task t a history H_t of prediction
errors; the interest is the slope of a least-squares line through the last k errors,
learning progress. Three other signals share its interface (`record(task, error)`,
`interest(task)`), for comparing curiosities on the same tasks:

- `LearningProgressInterest`, the paper's: errors going down are interesting;
- `PredictionErrorInterest`: the errors themselves, what is still mispredicted;
- `NoveltyInterest`: count-based, 1 / sqrt(1 + times witnessed);
- `RandomInterest`: no interest at all, so the actor's ties make it press at random.

Each is a small class for one agent; `InterestTable` is the same four signals for many
agents at once (a leading row axis), as the batched learners use them. A test shows
the two give identical numbers.
"""

import math
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
SIGNALS = ("learning_progress", "prediction_error", "novelty", "random")
"""The interest signals, by name (see `make_interest`)."""


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


class _ErrorHistories:
    """Per-task error histories, shared by the signals."""

    def __init__(self):
        self._history = {}

    @property
    def tasks(self):
        """The tasks witnessed so far, in the order they were first witnessed."""
        return list(self._history)

    def history(self, task):
        """A copy of the error history H_t of `task` (empty if never witnessed)."""
        return list(self._history.get(check_state("task", task), ()))

    def _append(self, task, error):
        task = check_state("task", task)
        error = _validate.non_negative("error", error)
        history = self._history.setdefault(task, [])
        history.append(error)
        return task, history


class LearningProgressInterest(_ErrorHistories):
    """Interest of each task as learning progress over its last `window` errors.

    For a task t with error history H_t (most recent last):
      - never witnessed: interest 0;
      - witnessed once (a new task): `new_task_factor` times the mean interest of the
        other known tasks (those witnessed at least twice), 0 if there are none;
      - otherwise: d = least-squares slope of the last `window` errors (of all of
        them while there are fewer), and interest max(-d, 0) (reading "progress") or
        max(d, 0) (reading "literal", the paper's printed formula).

    The paper says both "if H_t contains 0 or one element, i_t is zero" and "the
    interest for new tasks is fixed at 50% of the average interest for other tasks";
    `new_task_factor=0` is the first reading, the default 0.5 the second.

    Tasks are hashable keys that can be sorted among themselves (numbers, strings, or
    tuples of them), added as they are first recorded (the paper's goal space
    "constructed dynamically as new tasks are observed"). The mean over the known
    tasks adds their interests in the tasks' sorted order, so that it does not depend
    on the order in which the tasks were met.

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
        super().__init__()
        self.window = _validate.integer_at_least("window", window, 2)
        self.new_task_factor = _validate.in_closed_interval(
            "new_task_factor", new_task_factor, 0.0, 1.0)
        self.reading = _validate.one_of("reading", reading, READINGS)
        self._sign = -1.0 if reading == "progress" else 1.0
        self._weights = {n: _slope_weights(n) for n in range(2, self.window + 1)}
        self._known = {}  # interest of tasks witnessed at least twice
        self._interest = {}

    def record(self, task, error):
        """Appends the prediction error made when `task` was witnessed.

        Raises:
          ValueError: for an unhashable task, or an error that is not a finite
            number >= 0.
        """
        task, history = self._append(task, error)
        if len(history) >= 2:
            self._known[task] = self._known_interest(history)
        self._update_new_task_interests()

    def _known_interest(self, history):
        recent = history[-self.window:]
        slope = sum(map(operator.mul, self._weights[len(recent)], recent))
        return max(0.0, self._sign * slope)

    def _update_new_task_interests(self):
        interests = dict(self._known)
        total = sum(self._known[task] for task in sorted(self._known))
        count = len(self._known)
        for task, history in self._history.items():
            if len(history) == 1:  # a new task: never in self._known
                interests[task] = self.new_task_factor * (total / count if count else 0.0)
        self._interest = interests

    def interest(self, task):
        """The current interest of `task` (0.0 for a task never witnessed)."""
        return self._interest.get(check_state("task", task), 0.0)


class PredictionErrorInterest(_ErrorHistories):
    """Interest of each task as its recent prediction error: the mean of its last
    `window` errors (0 for a task never witnessed). What is still mispredicted is
    interesting, whether or not it can be learned.

    Args:
      window: errors in the mean (integer >= 1).
    """

    def __init__(self, window=DEFAULT_WINDOW):
        super().__init__()
        self.window = _validate.integer_at_least("window", window, 1)

    def record(self, task, error):
        """Appends the prediction error made when `task` was witnessed."""
        self._append(task, error)

    def interest(self, task):
        """The mean of the last `window` errors of `task` (0.0 if never witnessed)."""
        recent = self._history.get(check_state("task", task), ())[-self.window:]
        return sum(recent) / len(recent) if recent else 0.0


class NoveltyInterest(_ErrorHistories):
    """Count-based novelty: interest 1 / sqrt(1 + n) for a task witnessed n times (1
    for a task never witnessed), whatever the errors."""

    def record(self, task, error):
        """Counts one more witnessing of `task` (the error is kept in its history)."""
        self._append(task, error)

    def interest(self, task):
        """1 / sqrt(1 + times `task` was witnessed)."""
        n = len(self._history.get(check_state("task", task), ()))
        return 1.0 / math.sqrt(1.0 + n)


class RandomInterest(_ErrorHistories):
    """The baseline: every task has interest 0, so every action ties and the actor's
    random tie-breaking presses uniformly at random."""

    def record(self, task, error):
        """Keeps the error in the task's history; the interest stays 0."""
        self._append(task, error)

    def interest(self, task):
        """0.0, whatever the task."""
        check_state("task", task)
        return 0.0


def make_interest(signal="learning_progress", window=DEFAULT_WINDOW,
                  new_task_factor=DEFAULT_NEW_TASK_FACTOR, reading="progress"):
    """The interest module of a signal, by name (see `SIGNALS`).

    Args:
      signal: "learning_progress" (the paper's, default), "prediction_error",
        "novelty" or "random".
      window: errors in the slope (learning progress, >= 2) or in the mean
        (prediction error).
      new_task_factor, reading: learning progress only (see
        `LearningProgressInterest`).

    Raises:
      ValueError: for an unknown signal (the message lists the known ones) or a bad
        argument of the signal.
    """
    signal = _validate.one_of("interest", signal, SIGNALS)
    if signal == "learning_progress":
        return LearningProgressInterest(window, new_task_factor, reading)
    if signal == "prediction_error":
        return PredictionErrorInterest(window)
    return NoveltyInterest() if signal == "novelty" else RandomInterest()


class InterestTable:
    """An interest signal for many agents at once: rows are agents, keys the tasks (or
    regions) they can witness, numbered 0..n_keys-1.

    Row r gives exactly the numbers `make_interest(signal, ...)` gives for one agent
    witnessing the same tasks with the same errors. Settings may differ per row
    (arrays of one value per row), so that a grid of settings times seeds runs as
    one batch.

    Args:
      n_rows: agents.
      n_keys: tasks (or regions) per agent.
      signal: one of `SIGNALS`.
      window: per row or one for all (see `make_interest`).
      new_task_factor: per row or one for all (learning progress).
      reading: "progress" or "literal", per row or one for all (learning progress).
    """

    def __init__(self, n_rows, n_keys, signal="learning_progress", window=DEFAULT_WINDOW,
                 new_task_factor=DEFAULT_NEW_TASK_FACTOR, reading="progress"):
        self.signal = _validate.one_of("interest", signal, SIGNALS)
        self.n_rows, self.n_keys = n_rows, n_keys
        self.window = np.broadcast_to(np.asarray(window, dtype=np.int64), (n_rows,)).copy()
        self.factor = np.broadcast_to(np.asarray(new_task_factor, dtype=float), (n_rows,))
        readings = np.broadcast_to(np.asarray(reading, dtype=object), (n_rows,))
        self.sign = np.where(readings == "progress", -1.0, 1.0)
        self.kmax = int(self.window.max())
        self.errors = np.zeros((n_rows, n_keys, self.kmax))  # the last kmax, newest last
        self.count = np.zeros((n_rows, n_keys), dtype=np.int64)
        self.known = np.zeros((n_rows, n_keys))  # learning progress, count >= 2
        # weights[k, n, i]: the slope weights of the last n of k errors, at buffer
        # position i (zero before the last n), so that a sum over i is the slope.
        self.weights = np.zeros((self.kmax + 1, self.kmax + 1, self.kmax))
        for n in range(2, self.kmax + 1):
            self.weights[:, n, self.kmax - n:] = _slope_weights(n)
        self._values = None  # the interest of every task, until the next record
        self._one_window = int(self.window[0]) if np.all(self.window == self.window[0]) else None
        if self._one_window is not None:
            self._weights_of_one_window = self.weights[self._one_window]
        self._all = np.arange(n_rows)
        self._flat_errors = self.errors.reshape(n_rows * n_keys, self.kmax)  # views
        self._flat_count = self.count.reshape(-1)
        self._flat_known = self.known.reshape(-1)

    def record(self, rows, keys, errors):
        """Appends `errors[i]` to the history of task `keys[i]` of agent `rows[i]`
        (distinct rows; None: every agent, in order)."""
        self._values = None
        every = rows is None
        flat = (self._all if every else rows) * self.n_keys + keys
        history = np.concatenate((self._flat_errors.take(flat, axis=0)[:, 1:],
                                  np.asarray(errors, dtype=float)[:, None]), axis=1)
        self._flat_errors[flat] = history
        count = self._flat_count.take(flat) + 1
        self._flat_count[flat] = count
        if self.signal == "learning_progress":
            window = self.window if every else self.window[rows]
            n = np.minimum(count, window)
            weights = self._weights_of_one_window.take(n, axis=0) \
                if self._one_window is not None else self.weights[window, n]
            slope = weights[:, 0] * history[:, 0]
            for i in range(1, self.kmax):  # in order, as the one-agent sum adds them
                slope = slope + weights[:, i] * history[:, i]
            # With one error (n = 1) the weights are 0: the interest stays 0, unused.
            self._flat_known[flat] = np.maximum(0.0, (self.sign if every else self.sign[rows])
                                                * slope)

    def values(self, rows=None):
        """The interest of every task of agents `rows` (default all), [rows, n_keys]."""
        if rows is None:
            if self._values is None:
                self._values = self._compute(slice(None))
            return self._values
        return self._compute(rows)

    def _compute(self, rows):
        count = self.count[rows]
        if self.signal == "random":
            return np.zeros(count.shape)
        if self.signal == "novelty":
            return 1.0 / np.sqrt(1.0 + count)
        if self.signal == "prediction_error":
            n = np.minimum(count, self.window[rows][:, None])
            errors = self.errors[rows]
            total = np.zeros(count.shape)
            for i in range(self.kmax):  # the last n, oldest first
                total = total + np.where(i >= self.kmax - n, errors[..., i], 0.0)
            return np.where(n > 0, total / np.maximum(n, 1), 0.0)
        # A task's learning progress is kept from its second error on; before, it is 0.
        known, interest = count >= 2, self.known[rows]
        total, n_known = interest[:, 0], known[:, 0].astype(np.int64)
        for i in range(1, self.n_keys):  # in the tasks' order, as the one-agent sum
            total = total + interest[:, i]
            n_known = n_known + known[:, i]
        new = self.factor[rows] * (total / np.maximum(n_known, 1))  # 0 if none is known
        return interest + (count == 1) * new[:, None]  # a task seen once: the new share
