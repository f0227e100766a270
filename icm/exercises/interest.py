"""Checks of the interest exercises: the least-squares slope, the paper's interest of a
task (the slope of its last k errors, the progress reading, the two rules for a task
seen once), and a curiosity signal of the student's own design, each then run in the
goal-oriented learner beside the library's ("your interest, your Figure 5")."""

import math
import operator
import zlib

import numpy as np

from icm import _validate
from icm.exercises import _core, _own
from icm.exercises._core import Case
from icm.exercises._own import Forbidden
from icm.exercises._runs import EXERCISE_SEEDS, EXERCISE_TRIALS, run_goal_oriented_with
from icm.envs.buttons import NOISY_BUTTON
from icm.experiments.results import percent
from icm.learners.interest import (DEFAULT_NEW_TASK_FACTOR, DEFAULT_WINDOW, slope_weights,
                                   least_squares_slope)

SLOPE_PARAMETERS = ("values",)
INTEREST_PARAMETERS = ("history", "others", "window", "new_task_factor")
SIGNAL_PARAMETERS = ("history",)
INTEREST_FORBIDDEN = Forbidden(("icm.learners.interest",))
"""What a slope, an interest or a curiosity signal must not call: the library's
interest module (the slope, the four signals, their batched table)."""


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


def public_signal_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    coin = np.random.default_rng(3).integers(0, 2, 20).astype(float).tolist()
    return [
        Case("empty history: a task never witnessed", ([],),
             "a task never witnessed must still get a number (often 0, or a bonus for "
             "novelty): do not index history[-1] before checking it is not empty."),
        Case("one element", ([1.0],), "a single error: no slope yet; return a finite number >= 0."),
        Case("two elements, the error went down", ([1.0, 0.0],),
             "return a finite number >= 0."),
        Case("errors going up", ([0.0, 0.2, 0.4, 0.6, 0.8, 1.0],),
             "interest must not be negative: the actor picks the largest, and a "
             "negative value would make a task worse than one never seen. Clip at 0."),
        Case("ties: flat errors", ([0.5] * 6,),
             "return a finite number >= 0 (a slope of flat errors can come out as -1e-17: "
             "clip at 0)."),
        Case("errors going down", ([1.0, 0.8, 0.6, 0.4, 0.2, 0.0],),
             "return a finite number >= 0."),
        Case("a coin flip: errors 0 or 1 at random (the noisy button)", (coin,),
             "return a finite number >= 0 on any history."),
        Case("a long history", ([0.9 ** k for k in range(60)],),
             "return a finite number >= 0."),
    ]


def _signal_contract(history):
    """What every interest signal must give: a finite number >= 0."""
    return "a finite number >= 0"


def _meets_contract(expected, given):
    return _validate.is_real(given) and math.isfinite(float(given)) and float(given) >= 0.0


CONSTANT = "the same interest for every history"
"""The name of the check's last case: a signal must not be a constant."""


def signal_verdict(signal, cases):
    """What any interest signal must be, on `cases` (one history each): a finite number
    >= 0 on every history, the history left unchanged, the same number twice for the
    same history, not the same number for every history, computed without calling
    the library's signals.

    Args:
      signal: the student's function of (history).
      cases: a list of `Case`.

    Returns:
      A `CheckResult`.
    """
    result = _core.run_cases("your curiosity signal", "signal", signal, SIGNAL_PARAMETERS,
                             cases, _signal_contract, compare=_meets_contract,
                             forbidden=INTEREST_FORBIDDEN)
    if not result.passed:
        return result
    names = result.cases + [CONSTANT]
    values = []
    for case in cases:
        history = list(case.args[0])
        first, borrowed = _own.call_own(signal, (history,), INTEREST_FORBIDDEN)
        if history != list(case.args[0]):
            return _core.CheckResult(
                "your curiosity signal", _core.FAILED, names, case,
                _core.show_arguments(SIGNAL_PARAMETERS, case.args),
                "the history unchanged", history,
                "your signal changed the history it was given (append, pop, sort in "
                "place?): the learner keeps that list; work on a copy.")
        try:
            second, borrowed = _own.call_own(signal, (list(case.args[0]),),
                                             INTEREST_FORBIDDEN)
            same = _core.close(float(first), float(second))
        except Exception as error:
            second, same = error, False
        if not same:
            return _core.CheckResult(
                "your curiosity signal", _core.FAILED, names, case,
                _core.show_arguments(SIGNAL_PARAMETERS, case.args), first, second,
                "your signal gave two different numbers for the same history: an interest "
                "must depend on the history only (no random numbers, no state kept "
                "between calls).")
        values.append(float(first))
    if all(_core.close(values[0], value) for value in values):
        case = Case(CONSTANT, ("every history above",), "")
        return _core.CheckResult(
            "your curiosity signal", _core.FAILED, names, case, "history=every history above",
            "different interests for histories that differ",
            f"{_core.show(values[0])} for every history",
            "A constant interest makes every task exactly as interesting as every other: "
            "the learner then presses at random, and there is no curiosity left. Make your "
            "signal depend on the history (its errors, their trend, how many there are).")
    return _core.CheckResult("your curiosity signal", _core.PASSED, names)


def hidden_signal_cases(rng):
    """Histories of the shapes of the public ones, drawn from `rng`.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    n = int(rng.integers(4, 12))
    rising = np.sort(rng.random(n)).round(3)
    hint = "return a finite number >= 0 on any history."
    return [
        Case("empty history (hidden)", ([],), hint),
        Case("one element (hidden)", (rng.random(1).round(3).tolist(),), hint),
        Case("two elements (hidden)", (rng.random(2).round(3).tolist(),), hint),
        Case("errors going up (hidden)", (rising.tolist(),),
             "interest must not be negative: clip at 0."),
        Case("ties: flat errors (hidden)", ([round(float(rng.random()), 3)] * n,), hint),
        Case("errors going down (hidden)", (rising[::-1].tolist(),), hint),
        Case("a coin flip (hidden)", (rng.integers(0, 2, 3 * n).astype(float).tolist(),), hint),
        Case("a long history (hidden)", ((rng.random() ** np.arange(10 * n)).round(6).tolist(),),
             hint),
    ]


class SignalInterest:
    """An interest module whose interest of a task (or region) is a student's function
    of that key's error history alone, `signal(history)` (an empty history for a key
    never witnessed).

    A value that is not a finite number >= 0 raises `SignalValueError`, with the
    history that gave it: a signal that passed the cases may still break on a
    history the learner makes."""

    def __init__(self, signal):
        self.function = _validate.function("signal", signal, allow_none=False)
        self.histories = {}

    def record(self, task, error):
        """Appends an error to the task's history.

        Args:
          task: the task (or region) witnessed.
          error: the prediction error.
        """
        self.histories.setdefault(task, []).append(float(error))

    def interest(self, task):
        """The student's signal on the task's history.

        Args:
          task: a task (or region).

        Returns:
          Its interest, a float.

        Raises:
          SignalValueError: for a value that is not a finite number >= 0.
        """
        history = list(self.histories.get(task, []))
        value = self.function(list(history))
        if not _meets_contract(None, value):
            raise SignalValueError(history, value)
        return float(value)


class SignalValueError(ValueError):
    """A student's signal gave a value that is not a finite number >= 0 during a run.

    Attributes:
      history: the history it was given.
      value: what it returned.
    """

    def __init__(self, history, value):
        super().__init__(f"the signal gave {_core.show(value)} for the history "
                         f"{_core.show(history)}, not a finite number >= 0")
        self.history, self.value = history, value


NOISE_TRAP = "the noisy button, interest per button"
"""The name of the check's case run in the learner: where interest lives per button (a
region of the motor space), a button whose outcome is a coin toss can trap a signal.
Per task it cannot: the noisy button has no task of its own (the chapter "Which
curiosity?")."""
DRAWN_MARGIN = 0.02
"""How much more of its presses than learning progress (on the same seeds) a signal
may spend on the noisy button, in share of presses: the check refuses a signal whose
whole 95% band of that difference lies above this margin. Learning progress per
region is itself drawn to the noise a little (a noisy window's slope often falls), so
the question is not "drawn at all" but "drawn clearly more than the paper's signal".
Measured on 14 roots of the check's 20 seeds of 60 trials, the low end of the band
was 0.060 to 0.104 for the last error (refused on every root), and -0.074 to -0.015
for slopes written another way (windows of 10 and 5 errors) and -0.071 to -0.044 for
the book's solution (accepted on every root)."""


def _trap_root(cases):
    """The root seed of the noise case's runs: 0 for the check's own cases, else drawn
    from the cases given (a hidden test's runs are on seeds the student never saw)."""
    if cases is None:
        return 0
    return zlib.crc32(repr([case.args for case in cases]).encode())


def noise_trap(signal, n_seeds=EXERCISE_SEEDS, n_trials=EXERCISE_TRIALS, seed=0):
    """Runs the goal-oriented learner with `signal` and with learning progress, both
    with interest per button (region) on the console with the noisy button, on the
    same seeds, and compares the shares of their presses on the noisy button.

    Args:
      signal: the student's function of (history).
      n_seeds: runs (>= 2).
      n_trials: trials per run (>= 1).
      seed: the root seed.

    Returns:
      A dict: "yours" and "progress" (the two `GoalOrientedResult`s), "difference"
      (mean, low, high) of the per-seed difference of the shares (yours minus
      learning progress's, whole runs) and "drawn" (whether its whole band lies above
      `DRAWN_MARGIN`).

    Raises:
      SignalValueError: for a value of the signal that is not a finite number >= 0.
    """
    from icm.experiments import run_goal_oriented
    from icm.stats import bootstrap_band

    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 2)
    yours = run_goal_oriented_with(lambda: SignalInterest(signal), n_seeds, n_trials,
                                   noisy_button=True, seed=seed, interest_per="region")
    progress = run_goal_oriented(n_seeds=n_seeds, n_trials=n_trials, noisy_button=True,
                                 interest_per="region", seed=seed, progress=False)
    shares = [run.button_share[:, :, NOISY_BUTTON].mean(axis=1) for run in (yours, progress)]
    mean, low, high = (float(v[0]) for v in bootstrap_band((shares[0] - shares[1])[:, None]))
    return {"yours": yours, "progress": progress, "difference": (mean, low, high),
            "drawn": low > DRAWN_MARGIN}


def check_curiosity_signal(signal, experiment=True, n_seeds=EXERCISE_SEEDS,
                           n_trials=EXERCISE_TRIALS, cases=None):
    """Checks a curiosity signal of the student's own design, `signal(history)`, the
    interest of a task from its error history. There is no single right answer, so
    the check asks two things:

    1. what any interest must be, on the paper's edge cases: a finite number >= 0 on
       every history, without changing the history, the same twice, not a constant;
    2. the question of the exercise, in the one place where noise can trap a signal:
       with interest per button (a region of the motor space) on the console with the
       noisy button (`NOISE_TRAP`), the signal must not spend more of its presses on
       the noisy button than learning progress does on the same seeds, beyond a margin
       (`noise_trap`, `DRAWN_MARGIN`). A signal that pays for errors themselves (the
       last error, their mean) fails here.

    With `experiment`, a passing signal's runs are drawn beside learning progress's
    and prediction error's (the share of presses on the noisy button, trial after
    trial).

    Args:
      signal: the student's function of (history).
      experiment: whether to draw the runs and report what they measured.
      n_seeds, n_trials: the size of the runs with the noisy button.
      cases: the histories to try, a list of `Case` (default: the check's own, the
        ones the book shows; the grader passes its hidden ones, and the runs then
        take their root seed from them).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: for an argument that is not a function of one argument, or a
        bad `experiment`.
    """
    experiment = _validate.boolean("experiment", experiment)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 2)
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    root = _trap_root(cases)
    cases = public_signal_cases() if cases is None else cases
    result = signal_verdict(signal, cases)
    if not result.passed:
        return result
    names = result.cases + [NOISE_TRAP]
    trap_case = Case(NOISE_TRAP, (), "")
    shown = (f"your signal and learning progress, each with interest per button, on the "
             f"console with the noisy button: {n_seeds} seeds of {n_trials} trials")
    try:
        trap = noise_trap(signal, n_seeds, n_trials, root)
    except SignalValueError as error:
        return _core.CheckResult(
            "your curiosity signal", _core.FAILED, names, trap_case, shown,
            "a finite number >= 0 on every history the learner makes", error.value,
            f"on the history {_core.show(error.history)} your signal gave "
            f"{_core.show(error.value)}: it must give a finite number >= 0 on any "
            f"history, whatever its length or values.")
    except Exception as error:  # the student's code raised during the run
        return _core.CheckResult(
            "your curiosity signal", _core.FAILED, names, trap_case, shown,
            "a number for every history the learner makes", error,
            "your signal raised an error on a history the learner made during the run "
            "(not one of the cases above): make it work on any list of errors.")
    share = lambda run: float(run.button_share[:, :, NOISY_BUTTON].mean())
    mean, low, high = trap["difference"]
    yours, progress = share(trap["yours"]), share(trap["progress"])
    if trap["drawn"]:
        return _core.CheckResult(
            "your curiosity signal", _core.FAILED, names, trap_case, shown,
            f"no larger share of presses on the noisy button than learning progress's "
            f"{percent(progress)}, beyond a margin of {DRAWN_MARGIN:.0%} (the low end of "
            f"the band of the difference)",
            f"{percent(yours)} of the presses, {mean:+.1%} per seed on average "
            f"({low:+.1%} to {high:+.1%})",
            "your signal is drawn to the noise: per button, the noisy button's "
            "errors never stop (a coin toss cannot be learned), so a signal that pays "
            "for errors, or for their size, keeps paying that button. Ask whether the "
            "errors are going down, not whether they are large.")
    result = _core.CheckResult("your curiosity signal", _core.PASSED, names)
    if experiment:
        from icm.experiments import run_goal_oriented
        from icm.figures.curiosity import noisy_share_curves

        error = run_goal_oriented(n_seeds=n_seeds, n_trials=n_trials, noisy_button=True,
                                  interest="prediction_error", interest_per="region",
                                  seed=root, progress=False)
        result.figure = noisy_share_curves({"your signal": trap["yours"],
                                            "learning_progress": trap["progress"],
                                            "prediction_error": error},
                                           title="interest per button, with the noisy button")
        result.figure.icm_alt = ("The share of each trial's presses on the noisy button, "
                                 "with interest per button: your signal beside learning "
                                 "progress and prediction error")
        result.notes.append(
            f"With interest per button and the noisy button, {n_seeds} seeds of {n_trials} "
            f"trials: your signal spent {percent(yours)} of its presses on the noisy "
            f"button and mastered green in {percent(_mastered(trap['yours']))} of the "
            f"seeds; learning progress {percent(progress)} and "
            f"{percent(_mastered(trap['progress']))}; prediction error "
            f"{percent(share(error))} and {percent(_mastered(error))}. A press at random "
            f"would spend {1 / 6:.0%} there.")
    return result


def _mastered(run):
    """The share of a run's seeds that master the green task."""
    return float(np.mean(run.mastery_trial[:, 1] >= 1))
