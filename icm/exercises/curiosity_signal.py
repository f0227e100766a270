"""Check of the exercise "a curiosity of your own" (chapter "Which curiosity?"): a
student's interest signal, `signal(history)`, asked what any interest must be on the
paper's edge cases, then run where noise can trap it (interest per button on the
console with the noisy button) beside learning progress on the same seeds."""

import math
import zlib

import numpy as np

from icm import _validate
from icm.envs.buttons import NOISY_BUTTON
from icm.exercises import _core, _own
from icm.exercises._core import Case
from icm.exercises._runs import EXERCISE_SEEDS, EXERCISE_TRIALS, run_goal_oriented_with
from icm.exercises.interest import INTEREST_FORBIDDEN
from icm.chapters.words import percent

SIGNAL_PARAMETERS = ("history",)


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
    history the learner makes.

    The signal is asked once per distinct history: its answer is kept and given again
    when the same history comes back (a run of the check asks about 28,800 times for
    some 2,700 histories; when grading, each call is a round trip to the student's
    confined process). `signal_verdict` has already required the same answer twice for
    the same history, so this changes no number."""

    def __init__(self, signal):
        self.function = _validate.function("signal", signal, allow_none=False)
        self.histories = {}
        self._answers = {}

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
        key = tuple(history)
        if key not in self._answers:
            value = self.function(list(history))
            if not _meets_contract(None, value):
                raise SignalValueError(history, value)
            self._answers[key] = float(value)
        return self._answers[key]


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
