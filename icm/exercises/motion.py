"""Check of the simulated iCub's exercise: the minimum-jerk profile along which every
motion of the arm moves its actuators' targets."""

import numpy as np

from icm.envs.icub import minimum_jerk
from icm.exercises import _core
from icm.exercises._core import Case
from icm.exercises._own import Forbidden

PARAMETERS = ("fraction",)
FORBIDDEN = Forbidden(("icm.envs.icub", "icm.envs.buttons.movements"))
"""What a minimum-jerk profile must not call: the arm's own."""


def reference_minimum_jerk(fraction):
    """The minimum-jerk profile (`icm.envs.icub.minimum_jerk`).

    Args:
      fraction: the share of the motion's time, 0 to 1.

    Returns:
      The share of the way covered, a float.
    """
    return float(minimum_jerk(fraction))


def public_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    derive = "Solve the three conditions at s = 1 for a3, a4 and a5 (those at s = 0 make " \
             "a0 = a1 = a2 = 0): x(1) = 1, x'(1) = 0, x''(1) = 0."
    cases = [
        Case("the start: fraction 0", (0.0,), "At the start nothing has moved: x(0) = 0."),
        Case("the end: fraction 1", (1.0,), "At the end the targets are there: x(1) = 1, so "
             "the coefficients add up to 1. Check your signs."),
        Case("half-way: fraction 0.5", (0.5,), "Half-way in time is half-way in space: the "
             "conditions are the same seen from either end."),
        Case("a quarter of the time", (0.25,), "All six conditions must hold, the "
             "acceleration's too: the cubic 3 s^2 - 2 s^3 starts and stops with no speed, "
             "but its acceleration jumps at both ends. " + derive),
        Case("three quarters of the time", (0.75,), derive),
    ]
    for i, s in enumerate(np.linspace(0.05, 0.95, 7).round(3).tolist()):
        cases.append(Case(f"fraction {s}", (s,), derive))
    return cases


def check_minimum_jerk(minimum_jerk_function, cases=None):
    """Checks a student's minimum-jerk profile, `f(fraction)`: the share of the way
    covered at `fraction` (0 to 1) of the motion's time, the polynomial of degree five
    that goes from 0 to 1 and starts and ends with zero speed and zero acceleration
    (the exercise asks the student to derive it).

    Args:
      minimum_jerk_function: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of one argument.
    """
    cases = public_cases() if cases is None else cases
    return _core.run_cases("minimum_jerk", "minimum_jerk_function", minimum_jerk_function,
                           PARAMETERS, cases, reference_minimum_jerk, returns="a number",
                           forbidden=FORBIDDEN)


def hidden_cases(rng):
    """Fractions drawn from `rng`, the ends and the middle included (the shapes of
    the public cases).

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    cases = [Case("the start (hidden)", (0.0,), "At the start the profile is 0."),
             Case("the end (hidden)", (1.0,), "At the end the profile is 1.")]
    for s in np.sort(rng.uniform(0.01, 0.99, 6)).round(4).tolist():
        cases.append(Case("a fraction of the time (hidden)", (s,), "The polynomial of degree "
                          "five with x(0) = 0, x(1) = 1 and no speed or acceleration at "
                          "either end."))
    return cases
