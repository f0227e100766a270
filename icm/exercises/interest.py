"""Checks of the interest exercises: the least-squares slope and the paper's interest of
a task (the slope of its last k errors, the progress reading, the two rules for a task
seen once), each then run in the goal-oriented learner beside the library's ("your
interest, your Figure 5"). A curiosity signal of the student's own design is checked
in `icm.exercises.curiosity_signal`."""

import operator

import numpy as np

from icm import _validate
from icm.exercises import _core
from icm.exercises._core import Case
from icm.exercises._own import Forbidden
from icm.exercises._runs import EXERCISE_SEEDS, EXERCISE_TRIALS, run_goal_oriented_with
from icm.chapters.words import percent
from icm.learners.interest import (DEFAULT_NEW_TASK_FACTOR, DEFAULT_WINDOW, slope_weights,
                                   least_squares_slope)

SLOPE_PARAMETERS = ("values",)
INTEREST_PARAMETERS = ("history", "others", "window", "new_task_factor")
INTEREST_FORBIDDEN = Forbidden(("icm.learners.interest",))
"""What a slope, an interest or a curiosity signal (`icm.exercises.curiosity_signal`)
must not call: the library's interest module (the slope, the four signals, their
batched table)."""


def public_slope_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    rng = np.random.default_rng(20)
    cases = [
        Case("two values", ([1.0, 0.0],),
             "through two points the line passes through both: its slope is the second "
             "minus the first, negative when the values go down (x = 0, 1, ...: the "
             "oldest value first)."),
        Case("a line going up: y = 0.5 + 0.1 x, 5 values", ([0.5, 0.6, 0.7, 0.8, 0.9],),
             "the values are (0, y0), (1, y1), ...: x is the position, y the value, and "
             "the slope is positive when the values go up."),
        Case("the same line, 9 values: the slope does not depend on the length",
             ([0.5 + 0.1 * x for x in range(9)],),
             "the slope of a line is the same whatever the number of points: divide by "
             "the spread of x, sum((x - mean x)^2), not by the number of values."),
        Case("ties: every value the same", ([0.3, 0.3, 0.3, 0.3],),
             "flat values have slope 0."),
        Case("values going down", ([1.0, 0.8, 0.6, 0.4],),
             "values going down give a negative slope: x is the position (0, 1, 2, ...), "
             "y the value."),
        Case("not on a line", ([0.0, 1.0, 0.0, 1.0, 0.0, 1.0],),
             "fit every point, not only the first and the last: lambda_1 = sum((x - mean "
             "x)(y - mean y)) / sum((x - mean x)^2)."),
        Case("not on a line, going down", ([1.0, 0.8, 0.7, 0.2, 0.1],),
             "fit every point with least squares, x = 0, 1, 2, ..."),
    ]
    for i in range(6):
        values = rng.random(int(rng.integers(2, 11))).round(3).tolist()
        cases.append(Case(f"random values {i + 1}", (values,),
                          "fit every point with least squares, x = 0, 1, 2, ..."))
    return cases


def check_least_squares_slope(least_squares_slope_function, cases=None):
    """Checks a student's least-squares slope: `f(values)` returns the slope lambda_1 of
    the line lambda_0 + lambda_1 * x fitted by least squares to (0, values[0]), (1,
    values[1]), ... (2 values or more).

    Args:
      least_squares_slope_function: the student's function of (values).
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult` (displayed as a report; true if every case passed).

    Raises:
      ArgumentTypeError: if the argument is not a function of one argument.
    """
    cases = public_slope_cases() if cases is None else cases
    return _core.run_cases("least_squares_slope", "least_squares_slope_function",
                           least_squares_slope_function, SLOPE_PARAMETERS, cases,
                           least_squares_slope, returns="a number",
                           forbidden=INTEREST_FORBIDDEN)


def hidden_slope_cases(rng):
    """Cases of the shapes of the public ones, with values drawn from `rng`.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    a, b = round(float(rng.uniform(-1, 1)), 2), round(float(rng.uniform(-0.3, 0.3)), 3)
    n = int(rng.integers(3, 13))
    line = [round(a + b * x, 6) for x in range(n)]
    cases = [
        Case("two values (hidden)", (rng.random(2).round(3).tolist(),),
             "through two points the slope is the second minus the first."),
        Case("a line (hidden)", (line,), "x is the position, y the value."),
        Case("the same line, another length (hidden)",
             ([round(a + b * x, 6) for x in range(n + int(rng.integers(2, 6)))],),
             "the slope of a line does not depend on the number of points."),
        Case("ties: every value the same (hidden)", ([round(float(rng.random()), 3)] * n,),
             "flat values have slope 0."),
    ]
    for i in range(4):
        values = rng.random(int(rng.integers(2, 14))).round(3).tolist()
        cases.append(Case(f"random values (hidden {i + 1})", (values,),
                          "fit every point with least squares, x = 0, 1, 2, ..."))
    return cases


def reference_task_interest(history, others, window=DEFAULT_WINDOW,
                            new_task_factor=DEFAULT_NEW_TASK_FACTOR):
    """The interest of one task, as `icm.learners.LearningProgressInterest` gives it (a
    test checks they agree).

    Args:
      history: the task's prediction errors, oldest first.
      others: the interests of the other tasks seen at least twice.
      window: k, the errors in the slope.
      new_task_factor: the share of the others' mean a task seen once receives.

    Returns:
      0 for an empty history; for a task seen once, `new_task_factor` times the mean
      of `others` (0 if there are none); else max(0, -slope) of its last `window`
      errors.
    """
    if len(history) == 0:
        return 0.0
    if len(history) == 1:
        return new_task_factor * (sum(others) / len(others)) if others else 0.0
    recent = history[-window:]
    # The slope summed as the library sums it, so that the learner built on this
    # function makes exactly the library's choices (ties between interests included).
    return max(0.0, -sum(map(operator.mul, slope_weights(len(recent)), recent)))


def public_interest_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    rng = np.random.default_rng(5)
    cases = [
        Case("empty history: a task never witnessed", ([], [0.2, 0.1], 5, 0.5),
             "a task never witnessed has interest 0."),
        Case("one element, no other known task", ([0.7], [], 5, 0.5),
             "a task seen once gets new_task_factor times the mean interest of the others "
             "seen at least twice; with none, 0 (no division by zero)."),
        Case("one element: a new task gets half the mean of the others",
             ([1.0], [0.2, 0.1], 5, 0.5),
             "the paper: \"the interest for new tasks (witnessed only one time) is fixed "
             "at 50% of the average interest for other tasks\": new_task_factor * "
             "mean(others)."),
        Case("one element, new_task_factor 0: the paper's other reading",
             ([1.0], [0.2, 0.1], 5, 0.0),
             "with new_task_factor 0 a task seen once has interest 0 (\"if H_t contains "
             "0 or one element, i_t is zero\")."),
        Case("two elements, the error went down", ([1.0, 0.0], [], 5, 0.5),
             "with two errors the slope is their difference; errors going down are "
             "progress: interest max(0, -slope)."),
        Case("fewer than k errors", ([1.0, 0.5, 0.25], [], 5, 0.5),
             "with fewer than `window` errors, fit all of them."),
        Case("errors going up: no interest (the progress reading)",
             ([0.0, 0.5, 1.0], [], 5, 0.5),
             "the progress reading: interest is max(0, -slope), 0 when the errors grow. "
             "Check the sign."),
        Case("ties: the same error every time", ([0.5, 0.5, 0.5, 0.5], [0.3], 5, 0.5),
             "flat errors: slope 0, interest 0."),
        Case("exactly k errors", ([1.0, 0.8, 0.6, 0.4, 0.2], [], 5, 0.5),
             "fit the last `window` errors."),
        Case("more than k errors: only the last k count",
             ([0.0, 0.0, 0.0, 1.0, 0.8, 0.6, 0.4, 0.2], [], 5, 0.5),
             "only the last `window` errors count: history[-window:], not one more or "
             "one fewer."),
        Case("a window of 2", ([1.0, 1.0, 0.6, 0.2], [], 2, 0.5),
             "use the `window` argument, not a fixed 5."),
        Case("a line going down, whatever the window: y = 1 - 0.1 x",
             ([1.0 - 0.1 * x for x in range(9)], [], 7, 0.5),
             "on a line the slope is the same for any window: divide by the spread of x."),
    ]
    for i in range(8):
        history = rng.random(int(rng.integers(0, 12))).round(3).tolist()
        others = rng.random(int(rng.integers(0, 3))).round(3).tolist()
        cases.append(Case(f"random history {i + 1}",
                          (history, others, int(rng.integers(2, 8)),
                           float(rng.choice([0.0, 0.5, 1.0]))),
                          "see the rules: empty 0; one element, the new-task share; else "
                          "max(0, -slope of the last window errors)."))
    return cases


def hidden_interest_cases(rng):
    """Cases of the shapes of the public ones, with values drawn from `rng`.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    def errors(n):
        return rng.random(n).round(3).tolist()

    window = int(rng.integers(2, 9))
    factor = round(float(rng.uniform(0.1, 0.9)), 2)
    others = errors(int(rng.integers(1, 5)))
    falling = sorted(errors(window + int(rng.integers(2, 6))), reverse=True)
    cases = [
        Case("empty history (hidden)", ([], others, window, factor),
             "a task never witnessed has interest 0."),
        Case("one element, no other known task (hidden)", (errors(1), [], window, factor),
             "a task seen once with no other known task: 0."),
        Case("one element: a share of the others' mean (hidden)",
             (errors(1), others, window, factor),
             "a task seen once gets new_task_factor times the mean of `others`."),
        Case("two elements (hidden)", (errors(2), others, window, factor),
             "with two errors the slope is their difference; interest max(0, -slope)."),
        Case("fewer than k errors (hidden)", (errors(max(2, window - 1)), [], window + 1,
                                              factor),
             "with fewer than `window` errors, fit all of them."),
        Case("more than k errors: only the last k count (hidden)",
             (errors(3) + falling, others, window, factor),
             "only the last `window` errors count."),
        Case("errors going up (hidden)", (sorted(errors(window)), [], window, factor),
             "interest is max(0, -slope): 0 when the errors grow."),
    ]
    for i in range(4):
        cases.append(Case(f"random history (hidden {i + 1})",
                          (errors(int(rng.integers(0, 16))), errors(int(rng.integers(0, 4))),
                           int(rng.integers(2, 10)), round(float(rng.uniform(0, 1)), 2)),
                          "empty 0; one element, the new-task share; else max(0, -slope of "
                          "the last window errors)."))
    return cases


class FunctionInterest:
    """An interest module (`record(task, error)`, `interest(task)`) whose interest is a
    student's function of a task's error history, `task_interest(history, others,
    window, new_task_factor)` (the exercise's signature), `others` being the interests
    of the other tasks seen at least twice.

    Args:
      task_interest: the function.
      window: k.
      new_task_factor: the share of the mean for a task seen once.
    """

    def __init__(self, task_interest, window=DEFAULT_WINDOW,
                 new_task_factor=DEFAULT_NEW_TASK_FACTOR):
        self.function = _validate.function("task_interest", task_interest, allow_none=False)
        self.window = _validate.integer_at_least("window", window, 2)
        self.new_task_factor = _validate.in_closed_interval("new_task_factor",
                                                            new_task_factor, 0.0, 1.0)
        self.histories = {}
        self._values = {}

    def record(self, task, error):
        """Appends an error to the task's history.

        Args:
          task: the task witnessed.
          error: the prediction error.
        """
        self.histories.setdefault(task, []).append(float(error))
        self._values = {}

    def interest(self, task):
        """The student's function on the task's history.

        Args:
          task: a task.

        Returns:
          Its interest (0 if never witnessed).
        """
        if not self._values:
            known = {t: float(self.function(list(h), [], self.window, self.new_task_factor))
                     for t, h in self.histories.items() if len(h) >= 2}
            values = dict(known)
            for t, h in self.histories.items():
                if len(h) == 1:
                    others = [known[o] for o in sorted(known)]
                    values[t] = float(self.function(list(h), others, self.window,
                                                    self.new_task_factor))
            self._values = values
        return self._values.get(task, 0.0)


def check_task_interest(task_interest, experiment=True, n_seeds=EXERCISE_SEEDS,
                        n_trials=EXERCISE_TRIALS, cases=None):
    """Checks a student's interest of a task, `task_interest(history, others, window,
    new_task_factor)`: 0 for an empty history; for a task seen once,
    new_task_factor times the mean of `others` (0 if `others` is empty); otherwise
    max(0, -slope) of the least-squares line through the last `window` errors.

    If every case passes and `experiment` is true, it runs the goal-oriented learner
    with the student's interest and with the library's, on the same seeds, and draws
    the two Figure 5s side by side.

    Args:
      task_interest: the student's function.
      experiment: whether to run the experiment after the cases pass.
      n_seeds, n_trials: the experiment's size.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: for an argument that is not a function of (history, others,
        window, new_task_factor), or a bad `experiment`.
    """
    experiment = _validate.boolean("experiment", experiment)
    cases = public_interest_cases() if cases is None else cases
    result = _core.run_cases("task_interest", "task_interest", task_interest,
                             INTEREST_PARAMETERS, cases, reference_task_interest,
                             returns="a number", forbidden=INTEREST_FORBIDDEN)
    if result.passed and experiment:
        from icm.experiments import run_goal_oriented
        from icm.figures import figure5_grid

        yours = run_goal_oriented_with(lambda: FunctionInterest(task_interest),
                                       n_seeds, n_trials)
        library = run_goal_oriented(n_seeds=n_seeds, n_trials=n_trials, seed=0,
                                    progress=False)
        result.figure = figure5_grid({"your interest": yours,
                                      "the library's LearningProgressInterest": library})
        result.figure.icm_alt = ("Figure 5 with your interest beside the library's: mean "
                                 "interest in the red and green tasks against trial")
        result.notes.append(
            f"Your Figure 5, {n_seeds} seeds of {n_trials} trials: red mastered first in "
            f"{percent(yours.red_first_fraction())} of the seeds (the library's interest, the "
            f"same seeds: {percent(library.red_first_fraction())}).")
    return result
