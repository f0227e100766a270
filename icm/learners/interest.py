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

import dataclasses
import math
import operator

import numpy as np

from icm import _validate
from icm._settings import Names, Setting, Slider
from icm.learners._common import check_state

READINGS = ("progress", "literal")
"""How the slope d of the error history becomes interest:
"progress": max(-d, 0), errors going down are interesting (learning progress);
"literal": max(d, 0), the paper's printed "d_t if d_t > 0", errors going up."""
SIGNAL_CLASSES = {}
"""The registry of interest signals: {name: class}, filled by `interest_signal`. A
signal is one class (an `InterestSignal`) and its entry here: `make_interest`, the
batched `InterestTable`, the settings' choices and the CLI all read this registry."""
SIGNALS = Names(lambda: tuple(SIGNAL_CLASSES))
"""The interest signals, by name, in the order they were registered (a live view of
`SIGNAL_CLASSES`)."""
NEW_TASK_MEANS = ("known", "witnessed")
"""Which tasks the mean behind a new task's share averages (see `NEW_TASK_MEAN`)."""
SHORT_HISTORIES = ("slope", "zero")
"""The interest of a task witnessed 2 to k-1 times (see `SHORT_HISTORY`)."""

WINDOW = Setting(
    default=5, label="errors in the learning-progress slope (k)", kind="integer", low=2,
    high=100, paper=5,
    source='section 3.1: "the first derivative of the last 5 elements of H_t" and "In '
           'our implementation, k was fixed at 5"',
    slider=Slider(live=(2, 20, 1), grid=(3, 5, 7, 9, 11)))
"""k, the errors in the least-squares slope (and in the prediction-error signal's mean)."""
NEW_TASK_FACTOR = Setting(
    default=0.5, label="share of the mean interest a new task gets", kind="real", low=0.0,
    high=1.0, paper=0.5,
    source='section 3.1: "The interest for new tasks (witnessed only one time) is fixed '
           'at 50% of the average interest for other tasks"; the same section also says '
           '"If H_t contains 0 or one element, i_t is zero", which is a factor of 0',
    slider=Slider(live=(0.0, 1.0, 0.05), grid=(0.0, 0.25, 0.5, 0.75, 1.0)))
"""The share of the mean interest of the other tasks that a task seen once gets."""
READING = Setting(
    default="progress", label="reading of the interest formula", kind="choice",
    choices=READINGS,
    source='section 3.1 calls the interest the derivative of the error history and prints '
           '"d_t if d_t > 0, 0 otherwise", errors going up; learning progress, the drive '
           'the paper builds on, is errors going down. The book takes "progress" and shows '
           'both',
    swept=READINGS)
"""How the slope becomes interest (`READINGS`)."""
SIGNAL = Setting(
    default="learning_progress", label="interest signal", kind="choice", choices=SIGNALS,
    paper="learning_progress", per_row=False,
    source="section 3.1: the interest of a task is the derivative of its error history")
"""Which interest signal (`SIGNALS`); the chapter "Which curiosity?" compares them."""
NEW_TASK_MEAN = Setting(
    default="known", label="tasks averaged for a new task's share", kind="choice",
    choices=NEW_TASK_MEANS,
    source='"50% of the average interest for other tasks" does not say which: the book '
           'averages the tasks witnessed at least twice ("known", whose interest is '
           'defined); "witnessed" averages every other task witnessed, one seen once '
           'counting 0')
"""Which tasks the mean behind a new task's share averages (`NEW_TASK_MEANS`)."""
SHORT_HISTORY = Setting(
    default="slope", label="interest of a task seen fewer than k times", kind="choice",
    choices=SHORT_HISTORIES,
    source="the paper defines the interest from the last k errors and for a task seen "
           "once or never, not for one seen 2 to k-1 times: the book takes the slope of "
           'all its errors ("slope"); "zero" gives it no interest until it has k')
"""The interest of a task witnessed 2 to k-1 times (`SHORT_HISTORIES`)."""
_MEAN_WINDOW = dataclasses.replace(WINDOW, low=1, name="window")
"""The window of the signals that average errors (one error is a mean)."""
DEFAULT_WINDOW = WINDOW.default
DEFAULT_NEW_TASK_FACTOR = NEW_TASK_FACTOR.default


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
    return float((x * (y - y.mean())).sum() / (x * x).sum())  # not @: see icm._exact


def slope_weights(n):
    """Weights w with slope = w @ y for n equally spaced values (w sums to 0)."""
    x = np.arange(n) - (n - 1) / 2.0
    return tuple((x / (x * x).sum()).tolist())


def interest_signal(cls):
    """Registers `cls` (an `InterestSignal` with a `NAME`) in `SIGNAL_CLASSES`."""
    if not (isinstance(cls, type) and issubclass(cls, InterestSignal)):
        raise _validate.ArgumentTypeError(f"an interest signal must be a subclass of "
                                          f"InterestSignal, got {_validate.show(cls)}")
    _validate.text("NAME", cls.NAME)
    SIGNAL_CLASSES[cls.NAME] = cls
    return cls


class InterestSignal:
    """The base of the interest signals: per-task error histories for one agent, and
    the signal's batched form for `InterestTable`.

    A signal subclasses this, sets `NAME` (its registry key) and `SETTINGS` (the
    names of the settings its constructor takes: among window, new_task_factor,
    reading, new_task_mean, short_history), implements `record(task, error)` and
    `interest(task)` for one agent, and `table_values(table, rows)` (and, if it keeps
    state as errors come, `table_record`) for many; then `@interest_signal` registers
    it. `COLOUR`, `LINESTYLE`, `MARKER` say how the figures draw it;
    `KERNEL_FORMULA`, `ONE_ERROR_REWARD` and `LEARNS_VALUES` how it rewards the
    Q-learner. CONTRIBUTING shows an example.
    """

    NAME = None
    SETTINGS = ()
    COLOUR = "#000000"
    """Its colour in the figures (`icm.figures.curiosity.SIGNAL_COLOURS`)."""
    LINESTYLE, MARKER = "-", "x"
    """Its line style and marker in the figures, so that no two differ by colour alone."""
    KERNEL_FORMULA = None
    """The formula by which the rods' compiled loop computes it as a reward, one of
    `icm.experiments._rods_kernel.FORMULAS` ("error", "slope", "novelty", "none"), or
    None: the loop does not, and runs refuse it there by name (it still runs on the
    per-agent classes). A formula the loop does not have is refused by name too."""
    ONE_ERROR_REWARD = False
    """Whether, as a reward (`icm.learners.q_learning`), it reads the move's error alone
    (a window of 1: the paper's reward is the error itself), not the pair's last
    `window` errors."""
    LEARNS_VALUES = True
    """Whether a Q-learner rewarded by it learns values (the walk at random does not:
    every move stays a tie)."""
    WINDOW_SETTING = _MEAN_WINDOW
    """The setting that checks `window` in `InterestTable` (a mean needs one error, a
    slope two)."""

    def __init__(self):
        self._history = {}

    @staticmethod
    def table_record(table, flat, history, count, rows):
        """Called by `InterestTable.record` after it appended errors: `flat` are the
        (row, key) entries recorded, `history` their new last errors [entries, kmax],
        `count` their new counts, `rows` the rows (None: every row, in order). The
        default keeps nothing more."""

    @staticmethod
    def table_values(table, rows):
        """The interest of every key of `rows` of `table` (an `InterestTable`), [rows,
        n_keys], computed as the one-agent class computes it."""
        raise NotImplementedError

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


@interest_signal
class LearningProgressInterest(InterestSignal):
    """Interest of each task as learning progress over its last `window` errors.

    For a task t with error history H_t (most recent last):
      - never witnessed: interest 0;
      - witnessed once (a new task): `new_task_factor` times the mean interest of the
        other tasks (with `new_task_mean="known"`, those witnessed at least twice; with
        "witnessed", every other task witnessed, one seen once counting 0), 0 if there
        are none;
      - otherwise: d = least-squares slope of the last `window` errors (with
        `short_history="slope"`, of all of them while there are fewer; with "zero",
        interest 0 until there are `window`), and interest max(-d, 0) (reading
        "progress") or max(d, 0) (reading "literal", the paper's printed formula).

    The paper says both "if H_t contains 0 or one element, i_t is zero" and "the
    interest for new tasks is fixed at 50% of the average interest for other tasks";
    `new_task_factor=0` is the first reading, the default 0.5 the second. Where the
    paper is silent (which tasks the mean averages, a task seen 2 to k-1 times) the
    defaults are the book's choices, stated in `NEW_TASK_MEAN` and `SHORT_HISTORY`.

    Tasks are hashable keys that can be sorted among themselves (numbers, strings, or
    tuples of them), added as they are first recorded (the paper's goal space
    "constructed dynamically as new tasks are observed"). The mean over the known
    tasks adds their interests in the tasks' sorted order, so that it does not depend
    on the order in which the tasks were met.

    Args:
      window: k, the number of most recent errors in the slope (`WINDOW`).
      new_task_factor: share of the mean interest of the other tasks that a task
        witnessed once receives (`NEW_TASK_FACTOR`).
      reading: "progress" (default) or "literal"; see `READINGS`.
      new_task_mean: "known" (default) or "witnessed"; see `NEW_TASK_MEAN`.
      short_history: "slope" (default) or "zero"; see `SHORT_HISTORY`.

    Raises:
      ValueError: for any argument outside what its `Setting` allows.
    """

    NAME = "learning_progress"
    COLOUR, LINESTYLE, MARKER = "#1b9e77", "-", "o"
    KERNEL_FORMULA = "slope"
    SETTINGS = ("window", "new_task_factor", "reading", "new_task_mean", "short_history")
    WINDOW_SETTING = WINDOW

    def __init__(self, window=WINDOW.default, new_task_factor=NEW_TASK_FACTOR.default,
                 reading=READING.default, new_task_mean=NEW_TASK_MEAN.default,
                 short_history=SHORT_HISTORY.default):
        super().__init__()
        self.window = WINDOW.check(window, "window")
        self.new_task_factor = NEW_TASK_FACTOR.check(new_task_factor, "new_task_factor")
        self.reading = READING.check(reading, "reading")
        self.new_task_mean = NEW_TASK_MEAN.check(new_task_mean, "new_task_mean")
        self.short_history = SHORT_HISTORY.check(short_history, "short_history")
        self._sign = -1.0 if self.reading == "progress" else 1.0
        self._weights = {n: slope_weights(n) for n in range(2, self.window + 1)}
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
        if self.short_history == "zero" and len(history) < self.window:
            return 0.0
        recent = history[-self.window:]
        slope = sum(map(operator.mul, self._weights[len(recent)], recent))
        return max(0.0, self._sign * slope)

    def _update_new_task_interests(self):
        interests = dict(self._known)
        total = sum(self._known[task] for task in sorted(self._known))
        count = len(self._known) if self.new_task_mean == "known" else len(self._history) - 1
        for task, history in self._history.items():
            if len(history) == 1:  # a new task: never in self._known
                interests[task] = self.new_task_factor * (total / count if count else 0.0)
        self._interest = interests

    def interest(self, task):
        """The current interest of `task` (0.0 for a task never witnessed)."""
        return self._interest.get(check_state("task", task), 0.0)

    @staticmethod
    def table_record(table, flat, history, count, rows):
        """Keeps each recorded task's learning progress, from its second error on."""
        every = rows is None
        window = table.window if every else table.window[rows]
        n = np.minimum(count, window)
        weights = table._weights_of_one_window.take(n, axis=0) \
            if table._one_window is not None else table.weights[window, n]
        slope = weights[:, 0] * history[:, 0]
        for i in range(1, table.kmax):  # in order, as the one-agent sum adds them
            slope = slope + weights[:, i] * history[:, i]
        if table._zero_short is not None:  # no interest before `window` errors
            zero = table._zero_short if every else table._zero_short[rows]
            slope = np.where(zero & (count < window), 0.0, slope)
        # With one error (n = 1) the weights are 0: the interest stays 0, unused.
        table._flat_known[flat] = np.maximum(0.0, (table.sign if every else table.sign[rows])
                                             * slope)

    @staticmethod
    def table_values(table, rows):
        """The known tasks' progress, and a new task's share of their mean."""
        count = table.count[rows]
        # A task's learning progress is kept from its second error on; before, it is 0.
        known, interest = count >= 2, table.known[rows]
        total, n_known = interest[:, 0], known[:, 0].astype(np.int64)
        for i in range(1, table.n_keys):  # in the tasks' order, as the one-agent sum
            total = total + interest[:, i]
            n_known = n_known + known[:, i]
        if table._witnessed_mean is not None:  # every other task witnessed, not the known
            others = (count >= 1).sum(axis=1) - 1
            n_known = np.where(table._witnessed_mean[rows], others, n_known)
        new = table.factor[rows] * (total / np.maximum(n_known, 1))  # 0 if none is known
        return interest + (count == 1) * new[:, None]  # a task seen once: the new share


@interest_signal
class PredictionErrorInterest(InterestSignal):
    """Interest of each task as its recent prediction error: the mean of its last
    `window` errors (0 for a task never witnessed). What is still mispredicted is
    interesting, whether or not it can be learned.

    Args:
      window: errors in the mean (integer >= 1).
    """

    NAME = "prediction_error"
    COLOUR, LINESTYLE, MARKER = "#d95f02", "--", "s"
    KERNEL_FORMULA = "error"
    ONE_ERROR_REWARD = True
    SETTINGS = ("window",)

    def __init__(self, window=WINDOW.default):
        super().__init__()
        self.window = _MEAN_WINDOW.check(window, "window")

    def record(self, task, error):
        """Appends the prediction error made when `task` was witnessed."""
        self._append(task, error)

    def interest(self, task):
        """The mean of the last `window` errors of `task` (0.0 if never witnessed)."""
        recent = self._history.get(check_state("task", task), ())[-self.window:]
        return sum(recent) / len(recent) if recent else 0.0

    @staticmethod
    def table_values(table, rows):
        """The mean of each task's last `window` errors."""
        count = table.count[rows]
        n = np.minimum(count, table.window[rows][:, None])
        errors = table.errors[rows]
        total = np.zeros(count.shape)
        for i in range(table.kmax):  # the last n, oldest first
            total = total + np.where(i >= table.kmax - n, errors[..., i], 0.0)
        return np.where(n > 0, total / np.maximum(n, 1), 0.0)


@interest_signal
class NoveltyInterest(InterestSignal):
    """Count-based novelty: interest 1 / sqrt(1 + n) for a task witnessed n times (1
    for a task never witnessed), whatever the errors."""

    def record(self, task, error):
        """Counts one more witnessing of `task` (the error is kept in its history)."""
        self._append(task, error)

    NAME = "novelty"
    COLOUR, LINESTYLE, MARKER = "#7570b3", "-.", "^"
    KERNEL_FORMULA = "novelty"

    def interest(self, task):
        """1 / sqrt(1 + times `task` was witnessed)."""
        n = len(self._history.get(check_state("task", task), ()))
        return 1.0 / math.sqrt(1.0 + n)

    @staticmethod
    def table_values(table, rows):
        """1 / sqrt(1 + count) for every task."""
        return 1.0 / np.sqrt(1.0 + table.count[rows])


@interest_signal
class RandomInterest(InterestSignal):
    """The baseline: every task has interest 0, so every action ties and the actor's
    random tie-breaking presses uniformly at random."""

    def record(self, task, error):
        """Keeps the error in the task's history; the interest stays 0."""
        self._append(task, error)

    NAME = "random"
    COLOUR, LINESTYLE, MARKER = "#7a7a7a", ":", "D"
    KERNEL_FORMULA = "none"
    LEARNS_VALUES = False

    def interest(self, task):
        """0.0, whatever the task."""
        check_state("task", task)
        return 0.0

    @staticmethod
    def table_values(table, rows):
        """0 for every task."""
        return np.zeros(table.count[rows].shape)


def make_interest(signal=SIGNAL.default, window=WINDOW.default,
                  new_task_factor=NEW_TASK_FACTOR.default, reading=READING.default,
                  new_task_mean=NEW_TASK_MEAN.default, short_history=SHORT_HISTORY.default):
    """The interest module of a signal, by name (see `SIGNALS`).

    Args:
      signal: "learning_progress" (the paper's, default), "prediction_error",
        "novelty" or "random".
      window: errors in the slope (learning progress, >= 2) or in the mean
        (prediction error).
      new_task_factor, reading, new_task_mean, short_history: learning progress only
        (see `LearningProgressInterest`).

    Raises:
      ValueError: for an unknown signal (the message lists the known ones) or a bad
        argument of the signal.
    """
    cls = SIGNAL_CLASSES[SIGNAL.check(signal, "interest")]
    given = dict(window=window, new_task_factor=new_task_factor, reading=reading,
                 new_task_mean=new_task_mean, short_history=short_history)
    return cls(**{name: given[name] for name in cls.SETTINGS})


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
      new_task_factor, reading, new_task_mean, short_history: per row or one for all
        (learning progress; see `LearningProgressInterest`).

    Raises:
      ValueError: for a value its `Setting` refuses, or one array per setting that does
        not hold one value per row.
    """

    def __init__(self, n_rows, n_keys, signal=SIGNAL.default, window=WINDOW.default,
                 new_task_factor=NEW_TASK_FACTOR.default, reading=READING.default,
                 new_task_mean=NEW_TASK_MEAN.default, short_history=SHORT_HISTORY.default):
        self.signal = SIGNAL.check(signal, "interest")
        self._signal = SIGNAL_CLASSES[self.signal]
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.n_keys = _validate.integer_at_least("n_keys", n_keys, 1)

        def rows(spec, value, name, dtype):
            checked = spec.check_rows(value, name)
            if np.ndim(checked) == 1 and len(checked) != n_rows:
                raise ValueError(f"{name} must be one value or one per row ({n_rows}), "
                                 f"got {len(checked)} values")
            return np.broadcast_to(np.asarray(checked, dtype=dtype), (n_rows,))

        # Learning progress needs two errors for a slope; a mean needs one.
        window_spec = self._signal.WINDOW_SETTING
        self.window = rows(window_spec, window, "window", np.int64).copy()
        self.factor = rows(NEW_TASK_FACTOR, new_task_factor, "new_task_factor", float)
        readings = rows(READING, reading, "reading", object)
        self.sign = np.where(readings == "progress", -1.0, 1.0)
        means = rows(NEW_TASK_MEAN, new_task_mean, "new_task_mean", object)
        self._witnessed_mean = None if np.all(means == "known") else means == "witnessed"
        histories = rows(SHORT_HISTORY, short_history, "short_history", object)
        self._zero_short = None if np.all(histories == "slope") else histories == "zero"
        self.kmax = int(self.window.max())
        self.errors = np.zeros((n_rows, n_keys, self.kmax))  # the last kmax, newest last
        self.count = np.zeros((n_rows, n_keys), dtype=np.int64)
        self.known = np.zeros((n_rows, n_keys))  # learning progress, count >= 2
        # weights[k, n, i]: the slope weights of the last n of k errors, at buffer
        # position i (zero before the last n), so that a sum over i is the slope.
        self.weights = np.zeros((self.kmax + 1, self.kmax + 1, self.kmax))
        for n in range(2, self.kmax + 1):
            self.weights[:, n, self.kmax - n:] = slope_weights(n)
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
        self._signal.table_record(self, flat, history, count, rows)

    def values(self, rows=None):
        """The interest of every task of agents `rows` (default all), [rows, n_keys]."""
        if rows is None:
            if self._values is None:
                self._values = self._compute(slice(None))
            return self._values
        return self._compute(rows)

    def _compute(self, rows):
        return self._signal.table_values(self, rows)
