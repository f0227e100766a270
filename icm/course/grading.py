"""The tests of the assignments: what otter-grader runs, in the student's notebook, for
each implement exercise (`icm.course.assign` writes their cells).

- `public_test(label, function)`: the exercise's check on its public cases, the ones
  the book shows, with the check's report (the case, the input, the expected and the
  given result, a hint) as the failure message. The student's notebook holds it
  (`grader.check`).
- `hidden_test(label, function, seed, test)`: the same check on cases of the same
  shapes drawn from `seed`, which only the grading material holds; the failure
  message names the case's shape and gives the hint, never the input or the
  expected result.

An answer that calls what the exercise forbids (the library's implementation of it,
a reference; `icm.exercises._own`) fails every test of the exercise, public and
hidden: each test first asks whether the function called it on the public cases or
on cases of the hidden shapes drawn afresh (so that a table of the public cases that
calls the library on the others is caught too). Every test runs under a time limit
(`icm.exercises.registry.Exercise.timeout`).
"""

import contextlib
import secrets
import signal
import threading

import numpy as np

from icm.exercises import _own
from icm.exercises._core import NOT_IMPLEMENTED, PASSED, show
from icm.exercises.registry import EXERCISES

_SEEN = {}
"""{(label, id(function)): `_Seen`}: what the tests of an exercise found so far about
one function (they run one after the other in the student's kernel)."""


class _Seen:
    """What the tests of one exercise found about one function."""

    def __init__(self, function):
        self.function = function
        self.public = None      # (CheckResult or None, what stopped it or None)
        self.borrowed = False   # False: not looked for yet; then a Borrowed or None
        self.stopped = None     # the first time limit or uncaught error, if any


class _Timeout(BaseException):
    """A test ran past its time limit (a BaseException, so that the student's `except
    Exception` does not swallow it)."""


@_own.allow  # runs inside the student's function, which the checks watch
def _expired(signum, frame):
    raise _Timeout()


@contextlib.contextmanager
def _time_limit(seconds):
    """Raises `_Timeout` in the block after `seconds`, then every second after that
    (a student's loop that catches it once is stopped the next time). Only in the
    main thread, where signals are delivered; elsewhere the grading process's own
    limit applies."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    previous = signal.signal(signal.SIGALRM, _expired)
    signal.setitimer(signal.ITIMER_REAL, seconds, 1.0)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _run(exercise, call):
    """`call()` under the exercise's time limit: (its result, None), or (None, the
    text of what stopped it: the time limit or an exception the checks do not catch,
    such as SystemExit)."""
    try:
        with _time_limit(exercise.timeout):
            return call(), None
    except _Timeout:
        return None, (f"it took more than {exercise.timeout:g} s (the time limit of each "
                      f"test): look for a loop that never ends")
    except KeyboardInterrupt:  # the grader interrupted a cell that ran too long
        return None, ("it was interrupted: the cell ran past the grader's time limit of a "
                      "cell; look for a loop that never ends")
    except BaseException as error:  # SystemExit from the student's code
        return None, f"your function raised {type(error).__name__} ({show(error, 120)})"


def _exercise(label, function):
    exercise = EXERCISES.get(label)
    if exercise is None:
        raise AssertionError(f"no implement exercise is labelled {label!r}")
    if function is None:
        raise AssertionError(f"`{exercise.function}` is not defined: run the cell that "
                             f"defines it (its name must stay `{exercise.function}`).")
    if not callable(function):
        raise AssertionError(f"`{exercise.function}` must be a function, not a "
                             f"{type(function).__name__}.")
    return exercise


def _seen(exercise, function):
    key = (exercise.label, id(function))
    if key not in _SEEN or _SEEN[key].function is not function:
        _SEEN[key] = _Seen(function)
    return _SEEN[key]


def _checked(exercise, function, seen, call):
    """`call()` under the time limit, remembering the first time it was stopped: after
    that, the function is not run again (each test would wait for the limit)."""
    if seen.stopped:
        return None, f"{seen.stopped} (on an earlier test; not run again)"
    result, stopped = _run(exercise, call)
    if stopped:
        seen.stopped = stopped
    return result, stopped


def _public(exercise, function, seen):
    if seen.public is None:
        seen.public = _checked(exercise, function, seen, lambda: exercise.public(function))
    return seen.public


def _borrowed(exercise, function, seen):
    """What the function called that it must not, on every public case and on cases
    of every hidden shape drawn from a fresh seed (so that an answer that is right on
    the cases it was shown and calls the library on the others is caught), or None."""
    if seen.borrowed is False:
        result, _ = _public(exercise, function, seen)
        found = result.borrowed if result is not None else None
        if found is None and not seen.stopped:
            rng = np.random.default_rng(secrets.randbits(64))
            scanned, _ = _checked(exercise, function, seen,
                                  lambda: exercise.borrowed(function, rng) or False)
            found = scanned or None
        seen.borrowed = found
    return seen.borrowed


def _not_own(exercise, borrowed):
    return AssertionError(f"0 points for this exercise: {borrowed.hint(exercise.label)}")


def public_test(label, function):
    """The public test of an implement exercise: its check on the public cases.

    Args:
      label: the exercise's label, e.g. "ex-press-outcome".
      function: the student's function (None if the notebook does not define it).

    Raises:
      AssertionError: with the check's report, when a case fails, the function is
        missing, it calls what the exercise forbids, or it takes too long.
    """
    exercise = _exercise(label, function)
    seen = _seen(exercise, function)
    result, stopped = _public(exercise, function, seen)
    if stopped:
        raise AssertionError(f"{exercise.label}: {stopped}.")
    borrowed = _borrowed(exercise, function, seen)
    if borrowed is not None:
        raise _not_own(exercise, borrowed)
    if result.status == NOT_IMPLEMENTED:
        raise AssertionError(result.headline())
    if not result.passed:
        raise AssertionError(repr(result))


def hidden_test(label, function, seed, test):
    """One hidden test of an implement exercise: its check on cases of the public
    cases' shapes drawn from `seed`.

    Args:
      label: the exercise's label.
      function: the student's function (None if the notebook does not define it).
      seed: the grading seed (only the grading material holds it).
      test: which hidden test, from 0.

    Raises:
      AssertionError: naming the case's shape and giving its hint (never its input or
        expected result), when a case fails; or when the function is missing, calls
        what the exercise forbids, or takes too long.
    """
    exercise = _exercise(label, function)
    seen = _seen(exercise, function)
    borrowed = _borrowed(exercise, function, seen)
    if borrowed is not None:
        raise _not_own(exercise, borrowed)
    result, stopped = _checked(exercise, function, seen,
                               lambda: exercise.hidden(function, seed, test))
    where = f"hidden test {test + 1} of {len(exercise.hidden_points)}"
    if stopped:
        raise AssertionError(f"{exercise.label}, {where}: {stopped}.")
    if result.borrowed is not None:
        raise _not_own(exercise, result.borrowed)
    if result.status != PASSED:
        raise AssertionError(f"{exercise.label}, {where}: {case_message(result, hidden=True)}")


def case_message(result, hidden):
    """What a student is told of a check that did not pass: for a public case, the
    check's report (the case, its input, the expected and the given result, a hint);
    for a hidden case, its kind and hint, never its input or expected result.

    Args:
      result: the `CheckResult` (failed, or not implemented).
      hidden: whether the case is hidden.

    Returns:
      The text.
    """
    if result.status == NOT_IMPLEMENTED:
        return "not implemented yet (your function raises NotImplementedError)."
    if not hidden:
        return repr(result)
    what = (f"your function raised {type(result.given).__name__}"
            if isinstance(result.given, BaseException) else "your result differs")
    hint = result.hint
    if isinstance(result.given, BaseException):  # the check's prefix, said above
        hint = hint.split(" on this case. ", 1)[-1]
    return (f"a case like \"{result.case.name}\" failed ({what}; its values are not "
            f"shown). Hint: {hint}")
