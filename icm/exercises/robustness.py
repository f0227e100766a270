"""Check of the robustness exercise: when is the easy task mastered first?"""

import numpy as np

from icm.exercises import _core
from icm.exercises._core import Case
from icm.exercises._own import Forbidden
from icm.stats import comes_first

PARAMETERS = ("red_trial", "green_trial")
FORBIDDEN = Forbidden(("icm.stats", "icm.studies.robustness", "icm.experiments.results"))
"""What "red first" must not call: the library's count of it."""
NEVER = ("-1 means never: a task never mastered comes after any trial, and a seed that "
         "masters neither has not mastered red first.")


def reference_red_first(red_trial, green_trial):
    """Whether red was mastered first, as `icm.stats.comes_first` and the book's "red
    first" count it.

    Args:
      red_trial: the trial red was mastered at (from 1; -1 for never).
      green_trial: the same for green.

    Returns:
      True if red was mastered strictly before green.
    """
    return bool(comes_first(red_trial, green_trial))


def public_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    never = NEVER
    return [
        Case("red at trial 3, green at trial 9", (3, 9), "Red comes first when its trial "
             "number is smaller."),
        Case("green first", (9, 3), "Red does not come first when green's trial is "
             "smaller."),
        Case("ties: both at the same trial", (5, 5), "\"First\" means strictly before: a "
             "tie is not red first."),
        Case("green never mastered, red at trial 12", (12, -1), never),
        Case("red never mastered, green at trial 4", (-1, 4), never),
        Case("neither mastered", (-1, -1), never),
        Case("red at trial 1, green at trial 2", (1, 2), "Red comes first when its trial "
             "number is smaller."),
        Case("red at trial 60, green never", (60, -1), never),
    ]


def check_red_first(red_first, cases=None):
    """Checks a student's rule for "red mastered first", `red_first(red_trial,
    green_trial)`: True when red was mastered strictly before green, the trials counted
    from 1 and -1 meaning never.

    Args:
      red_first: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of two arguments.
    """
    cases = public_cases() if cases is None else cases
    return _core.run_cases("red_first", "red_first", red_first, PARAMETERS, cases,
                           reference_red_first, returns="True or False", forbidden=FORBIDDEN)


def hidden_cases(rng):
    """Trials drawn from `rng`, in the shapes of the public cases.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    a, b = sorted(int(t) for t in rng.choice(np.arange(2, 200), 2, replace=False))
    tie = int(rng.integers(1, 200))
    order = "Red comes first when its trial number is smaller."
    return [
        Case("red first (hidden)", (a, b), order),
        Case("green first (hidden)", (b, a), order),
        Case("ties (hidden)", (tie, tie), "\"First\" means strictly before: a tie is not."),
        Case("green never mastered (hidden)", (b, -1), NEVER),
        Case("red never mastered (hidden)", (-1, a), NEVER),
        Case("neither mastered (hidden)", (-1, -1), NEVER),
        Case("red at trial 1 (hidden)", (1, a), order),
    ]
