"""The machinery the checks share: cases, running a student's function on them against
the reference, and a report that teaches (which case, its input, the expected and the
given result, a hint), never the reference's code."""

import copy
import dataclasses
import html
import inspect
import math
import numbers
import warnings

import numpy as np

from icm import _validate
from icm.exercises._own import call_own

PASSED, FAILED, NOT_IMPLEMENTED = "passed", "failed", "not implemented yet"
"""The three outcomes of a check."""
SHOW_LIMIT = 240
"""Characters of an input or a result shown in a report before it is cut."""


@dataclasses.dataclass(frozen=True)
class Case:
    """One case a check tries: a name a student can read, the arguments given to the
    function (positionally, in the order of the exercise's signature) and a hint to
    show if the student's answer differs from the reference's here.

    Attributes:
      name: what the case is about, e.g. "one element: a task seen once".
      args: the arguments, a tuple.
      hint: what to look at when this case fails.
      about: for a check that judges several quantities (e.g. the reward and Q), the
        one `hint` is about; when another is the first one wrong, the report gives
        that quantity's hint instead. None for a check of one result.
    """

    name: str
    args: tuple
    hint: str
    about: str = None


@dataclasses.dataclass
class CheckResult:
    """What a check found. True (in an `if`) only when every case passed.

    Attributes:
      exercise: the exercise's name, as the report shows it.
      status: `PASSED`, `FAILED` or `NOT_IMPLEMENTED`.
      cases: the names of the cases tried, in order.
      case: the case that failed (None if none did).
      arguments: the failed case's arguments, as the report shows them.
      expected: the reference's result on that case.
      given: the student's result (or the error it raised).
      hint: what to look at.
      notes: lines the report adds after the verdict (e.g. what an experiment run with
        the student's piece measured).
      figure: a figure the check drew (e.g. the paper's experiment with the student's
        piece beside the reference), or None.
      borrowed: an `icm.exercises._own.Borrowed` when the student's function called
        what the exercise forbids (the library's answer, a reference), else None.
    """

    exercise: str
    status: str
    cases: list
    case: Case = None
    arguments: str = ""
    expected: object = None
    given: object = None
    hint: str = ""
    notes: list = dataclasses.field(default_factory=list)
    figure: object = None
    borrowed: object = None

    @property
    def passed(self):
        """Whether every case passed."""
        return self.status == PASSED

    def __bool__(self):
        return self.passed

    def headline(self):
        """The verdict in one line."""
        if self.status == PASSED:
            return f"{self.exercise}: all {len(self.cases)} cases passed."
        if self.status == NOT_IMPLEMENTED:
            return (f"{self.exercise}: not implemented yet. Replace the line `raise "
                    f"NotImplementedError` with your code, run that cell, then run this "
                    f"check again.")
        return (f"{self.exercise}: case {self.cases.index(self.case.name) + 1} of "
                f"{len(self.cases)}, \"{self.case.name}\", failed.")

    def details(self):
        """(label, text) pairs of the report under the headline."""
        if self.status == FAILED:
            return [("input", self.arguments), ("expected", show(self.expected)),
                    ("given", show(self.given)), ("hint", self.hint)]
        if self.status == PASSED:
            return [("cases", "; ".join(self.cases))]
        return []

    def __repr__(self):
        lines = [self.headline()]
        lines += [f"  {label}: {text}" for label, text in self.details()]
        lines += self.notes
        return "\n".join(lines)

    def _repr_html_(self):
        kind = {PASSED: "passed", FAILED: "failed", NOT_IMPLEMENTED: "todo"}[self.status]
        mark = {PASSED: "\u2713", FAILED: "\u2717", NOT_IMPLEMENTED: "\u2026"}[self.status]
        parts = [f'<div class="icm-check icm-check-{kind}" role="status">',
                 f'<p><strong><span aria-hidden="true">{mark}</span> '
                 f'{html.escape(self.headline())}</strong></p>']
        if self.details():
            parts.append("<dl>")
            for label, text in self.details():
                parts.append(f"<dt>{html.escape(label)}</dt><dd><code>{html.escape(text)}"
                             f"</code></dd>" if label in ("input", "expected", "given")
                             else f"<dt>{html.escape(label)}</dt><dd>{html.escape(text)}</dd>")
            parts.append("</dl>")
        parts += [f"<p>{html.escape(note)}</p>" for note in self.notes]
        if self.figure is not None:
            parts.append(_figure_html(self.figure))
        parts.append("</div>")
        return "\n".join(parts)


def _figure_html(figure):
    """A figure as an inline PNG image, as wide as the text column at most."""
    import base64
    import io

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=100, bbox_inches="tight")
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    alt = html.escape(getattr(figure, "icm_alt", "") or "the check's figure")
    return (f'<img src="data:image/png;base64,{data}" alt="{alt}" '
            f'style="max-width: 100%; height: auto;">')


def show(value, limit=SHOW_LIMIT):
    """A short text of a value for a report: numbers to 6 significant digits, arrays
    and sequences as lists, an error as its type and message, a string as it is.

    Args:
      value: what to show.
      limit: the most characters shown (longer texts are cut, ending in "...").

    Returns:
      The text.
    """
    if isinstance(value, BaseException):
        text = f"{type(value).__name__}: {value}"
    elif isinstance(value, str):  # a description, not a result
        text = value
    else:
        text = repr(_plain(value))
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _plain(value):
    """`value` with numpy numbers and arrays as Python numbers and lists, floats rounded
    to 6 significant digits, for showing."""
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        number = float(value)
        return float(f"{number:.6g}") if math.isfinite(number) else number
    if isinstance(value, tuple):
        return tuple(_plain(v) for v in value)
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {_plain(k): _plain(v) for k, v in value.items()}
    return value


def show_arguments(names, args):
    """The arguments of a case as `name=value, ...`.

    Args:
      names: the exercise's argument names, in order.
      args: the case's arguments.

    Returns:
      The text.
    """
    return ", ".join(f"{name}={show(value, 120)}" for name, value in zip(names, args))


def check_function(name, function, parameters):
    """Returns `function` if it is callable with the exercise's arguments, given
    positionally in the order of `parameters`; else raises a clear error.

    Args:
      name: the check's name for the argument, for the message.
      function: what the student passed.
      parameters: the exercise's argument names, in order.

    Raises:
      ArgumentTypeError (a TypeError and a ValueError): if `function` is not a function
        or cannot take those arguments.
    """
    if not callable(function) or isinstance(function, type):
        raise _validate.ArgumentTypeError(
            f"{name} must be a function taking ({', '.join(parameters)}), got "
            f"{_validate.show(function)} of type {type(function).__name__}: pass the "
            f"function itself, without calling it (no parentheses)")
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):  # a builtin without a signature: try it as it is
        return function
    try:
        signature.bind(*parameters)
    except TypeError:
        raise _validate.ArgumentTypeError(
            f"{name} must take the arguments ({', '.join(parameters)}), in this order; "
            f"yours takes {signature}") from None
    return function


def close(expected, given, tolerance=1e-9):
    """Whether `given` equals `expected`, numbers to a relative `tolerance` (and 1e-12
    absolute), sequences and dicts entry by entry, True and False only as booleans.

    Args:
      expected: the reference's result.
      given: the student's result.
      tolerance: the relative tolerance on numbers.

    Returns:
      True or False.
    """
    if isinstance(expected, dict):
        return isinstance(given, dict) and set(given) == set(expected) and all(
            close(expected[k], given[k], tolerance) for k in expected)
    if isinstance(expected, (list, tuple, np.ndarray)):
        if isinstance(given, (str, bytes, dict)) or not hasattr(given, "__len__"):
            return False
        given_list = list(np.asarray(given).tolist()) if isinstance(given, np.ndarray) \
            else list(given)
        expected_list = list(np.asarray(expected).tolist()) \
            if isinstance(expected, np.ndarray) else list(expected)
        return len(given_list) == len(expected_list) and all(
            close(e, g, tolerance) for e, g in zip(expected_list, given_list))
    if isinstance(expected, (bool, np.bool_)):
        return isinstance(given, (bool, np.bool_)) and bool(given) == bool(expected)
    if _validate.is_real(expected):
        if not _validate.is_real(given):
            return False
        e, g = float(expected), float(given)
        if math.isnan(e) or math.isnan(g):
            return math.isnan(e) and math.isnan(g)
        return math.isclose(e, g, rel_tol=tolerance, abs_tol=1e-12)
    return expected == given


def run_cases(exercise, name, function, parameters, cases, reference, compare=close,
              returns=None, observe=None, quantities=None, forbidden=None):
    """Runs `function` and `reference` on every case and compares their results.

    Both are given fresh copies of each case's arguments, so that a function that
    changes its inputs changes neither the other's nor the next case's. The student's
    function runs first, and the reference only once the student's has returned.

    Args:
      exercise: the exercise's name, for the report.
      name: the check's argument name for the student's function (for errors).
      function: the student's function.
      parameters: the names of the exercise's arguments, in order.
      cases: a list of `Case`.
      reference: the reference: a function of the same arguments.
      compare: compare(expected, given) -> bool.
      returns: a description of what the function must return (e.g. "a number"),
        shown in the hint when it returns something else; None to skip that check.
      observe: observe(arguments, returned) -> what is compared, for functions that
        change their arguments in place (default: what they return).
      quantities: for an `observe` that gives a dict of several quantities, their
        [(key, label, hint)] in the order they are computed: the report names the
        first one that is wrong and gives its hint (the case's own hint when the case
        is `about` it).
      forbidden: an `icm.exercises._own.Forbidden`: what the function must not call
        (its first such call fails the check); None to call it unwatched.

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if `function` is not a function of those arguments.
    """
    function = check_function(name, function, parameters)
    names = [case.name for case in cases]
    for case in cases:
        arguments = copy.deepcopy(case.args)
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")  # the report says what went wrong
                given, borrowed = call_own(function, arguments, forbidden)
        except NotImplementedError:
            return CheckResult(exercise, NOT_IMPLEMENTED, names)
        except Exception as error:  # the student's code failed: say where, and go on
            return CheckResult(exercise, FAILED, names, case,
                               show_arguments(parameters, case.args),
                               _expected(reference, case, observe), error,
                               f"Your function raised {type(error).__name__} on this case. "
                               + _sentence(case.hint))
        if borrowed is not None:
            return CheckResult(exercise, FAILED, names, case,
                               show_arguments(parameters, case.args), "your own code",
                               f"a call to {borrowed.name}", borrowed.hint(exercise),
                               borrowed=borrowed)
        expected = _expected(reference, case, observe)
        hint = _sentence(case.hint)
        if given is None and (observe is not None or expected is not None):
            hint = "Your function returned None: did you forget `return`? " + hint
        elif returns is not None and not _is_kind(expected, given):
            hint = f"Your function must return {returns}. " + hint
        if observe is not None:
            given = observe(arguments, given)
        if not compare(expected, given):
            if quantities:
                hint = _first_wrong(quantities, case, expected, given, hint)
            return CheckResult(exercise, FAILED, names, case,
                               show_arguments(parameters, case.args), expected, given, hint)
    return CheckResult(exercise, PASSED, names)


def _expected(reference, case, observe):
    """The reference's result on a fresh copy of the case's arguments."""
    arguments = copy.deepcopy(case.args)
    expected = reference(*arguments)
    return expected if observe is None else observe(arguments, expected)


def _first_wrong(quantities, case, expected, given, hint):
    """The hint of a failed case of a check that judges several quantities: it names
    the first quantity (in the order they are computed) that differs from the
    reference's, and gives that quantity's hint (the case's, if the case is about
    it)."""
    right = []
    for key, label, quantity_hint in quantities:
        if isinstance(given, dict) and key in given and close(expected[key], given[key]):
            right.append(label)
            continue
        said = f"{_sentence(label)} is wrong"
        said += f" ({' and '.join(right)} right)." if right else "."
        if case.about not in (None, key):
            hint = hint[:len(hint) - len(_sentence(case.hint))] + _sentence(quantity_hint)
        return f"{said} {hint}"
    return hint


def _sentence(text):
    """`text` with its first letter in upper case."""
    return text[:1].upper() + text[1:]


def _is_kind(expected, given):
    """Whether `given` is of the kind of `expected` (a number, a sequence, ...)."""
    if _validate.is_real(expected) and not isinstance(expected, (bool, np.bool_)):
        return _validate.is_real(given)
    if isinstance(expected, (list, tuple, np.ndarray)):
        return isinstance(given, (list, tuple, np.ndarray))
    return True
