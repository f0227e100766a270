"""Argument checks shared by the whole package.

Every check raises an error that names the argument, shows the value it got and says
what is allowed:

- a value of the wrong *type* (a string for a number, a float for a count, a bool for
  an action) raises `ArgumentTypeError`, which is a `TypeError` and also a
  `ValueError`, so that ``except ValueError`` still catches every bad argument;
- a value of the right type outside what is allowed raises `ValueError`.

Numpy scalars and 0-d arrays count as the numbers they hold; bools never count as
numbers.
"""

import math
import numbers
import os

import numpy as np

MAX_SEED = 2**63 - 1
"""The largest integer seed: seeds are kept in int64 arrays and settings."""


class ArgumentTypeError(TypeError, ValueError):
    """An argument of the wrong type. A `TypeError`, and a `ValueError` too, so that
    code catching ValueError for bad arguments catches this one as well."""


def show(value, limit=80):
    """A short repr of `value` for an error message (long arrays are cut)."""
    if isinstance(value, np.ndarray):
        text = np.array2string(value, threshold=8, edgeitems=2, separator=", ")
        text = f"array({text}, dtype={value.dtype})"
    else:
        try:
            text = repr(value)
        except Exception:  # a repr that fails must not hide the real error
            text = f"<{type(value).__name__}>"
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _type_error(name, allowed, value):
    return ArgumentTypeError(f"{name} must be {allowed}, got {show(value)} "
                             f"of type {type(value).__name__}")


def _value_error(name, allowed, value):
    return ValueError(f"{name} must be {allowed}, got {show(value)}")


def scalar(value):
    """`value` itself, or the number held by a 0-d numpy array."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value[()]
    return value


def is_integer(value):
    """True for Python and numpy integers (and 0-d integer arrays), never for bools."""
    value = scalar(value)
    return isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_))


def is_real(value):
    """True for Python and numpy real numbers (and 0-d arrays of them), never bools."""
    value = scalar(value)
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def integer(name, value, low=None, high=None):
    """Returns `value` as an int if it is an integer with low <= value <= high (either
    bound may be None: unbounded)."""
    if low is not None and high is not None:
        allowed = f"an integer in {low}..{high}"
    elif low is not None:
        allowed = f"an integer >= {low}"
    elif high is not None:
        allowed = f"an integer <= {high}"
    else:
        allowed = "an integer"
    if not is_integer(value):
        raise _type_error(name, allowed, value)
    number = int(scalar(value))
    if (low is not None and number < low) or (high is not None and number > high):
        raise _value_error(name, allowed, value)
    return number


def integer_at_least(name, value, minimum):
    """Returns `value` as an int if it is an integer >= minimum."""
    return integer(name, value, low=minimum)


def integer_in_range(name, value, low, high):
    """Returns `value` as an int if it is an integer with low <= value <= high."""
    return integer(name, value, low, high)


def n_jobs(value):
    """Returns `value` as an int if it is a count of joblib's jobs: an integer >= 1, or
    -1 for one job per core."""
    allowed = "an integer >= 1, or -1 for one job per core"
    if not is_integer(value):
        raise _type_error("n_jobs", allowed, value)
    number = int(scalar(value))
    if number < 1 and number != -1:
        raise _value_error("n_jobs", allowed, value)
    return number


def real(name, value, low=-math.inf, high=math.inf, low_open=False, high_open=False,
         allowed=None):
    """Returns `value` as a float if it is a finite real number within the bounds.

    Args:
      name: the argument's name, for the message.
      value: what was given.
      low, high: the bounds (infinite: unbounded on that side).
      low_open, high_open: whether a bound itself is excluded.
      allowed: the message's description of what is allowed (default: built from
        the bounds).
    """
    if allowed is None:
        if math.isinf(low) and math.isinf(high):
            allowed = "a finite number"
        elif math.isinf(high):
            allowed = f"a finite number {'>' if low_open else '>='} {low:g}"
        elif math.isinf(low):
            allowed = f"a number {'<' if high_open else '<='} {high:g}"
        else:
            allowed = (f"a number in {'(' if low_open else '['}{low:g}, "
                       f"{high:g}{')' if high_open else ']'}")
    if not is_real(value):
        raise _type_error(name, allowed, value)
    number = float(scalar(value))
    if not math.isfinite(number):
        raise _value_error(name, allowed, value)
    if number < low or number > high or (low_open and number == low) or \
            (high_open and number == high):
        raise _value_error(name, allowed, value)
    return number


def in_closed_interval(name, value, low, high):
    """Returns `value` as a float if low <= value <= high."""
    return real(name, value, low, high)


def learning_rate(name, value):
    """Returns `value` as a float if 0 < value <= 1."""
    return real(name, value, 0.0, 1.0, low_open=True, allowed="a learning rate in (0, 1]")


def positive(name, value):
    """Returns `value` as a float if it is a finite number > 0."""
    return real(name, value, 0.0, low_open=True)


def non_negative(name, value):
    """Returns `value` as a float if it is a finite number >= 0."""
    return real(name, value, 0.0)


def boolean(name, value):
    """Returns `value` if it is True or False (numpy bools too), else raises."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise _type_error(name, "True or False", value)


def text(name, value):
    """Returns `value` if it is a string."""
    if not isinstance(value, str):
        raise _type_error(name, "a string", value)
    return value


def one_of(name, value, allowed):
    """Returns `value` if it is one of `allowed` (compared with ==), else raises
    ValueError listing them (ArgumentTypeError if `value` is of another type than all
    of them, e.g. a list where names are expected)."""
    listed = ", ".join(repr(a) for a in allowed)
    value = scalar(value)
    try:
        hash(value)
    except TypeError:
        raise _type_error(name, f"one of {listed}", value) from None
    for option in allowed:
        if option is None:
            if value is None:
                return None
        elif _same_kind(option, value) and option == value:
            return option
    if not any(_same_kind(option, value) for option in allowed if option is not None):
        raise _type_error(name, f"one of {listed}", value)
    raise _value_error(name, f"one of {listed}", value)


def _same_kind(option, value):
    """Whether `value` is of the kind of `option`: both strings, both numbers (bools
    apart), or the same type."""
    if isinstance(option, str):
        return isinstance(value, str)
    if isinstance(option, bool) or isinstance(value, (bool, np.bool_)):
        return isinstance(option, bool) and isinstance(value, (bool, np.bool_))
    if is_real(option):
        return is_real(value)
    return type(option) is type(value)


def seed(name, value):
    """Returns a root seed as given: None, or an integer in 0..MAX_SEED."""
    if value is None:
        return None
    return integer(name, value, 0, MAX_SEED)


def generator(name, value):
    """A `numpy.random.Generator` from None (fresh entropy), an integer seed in
    0..MAX_SEED, or a Generator (returned as it is); anything else raises."""
    if isinstance(value, np.random.Generator):
        return value
    if value is not None and not is_integer(value):
        raise _type_error(name, f"None, an integer in 0..{MAX_SEED} or a "
                                "numpy.random.Generator", value)
    return np.random.default_rng(seed(name, value))


def root_seed(name, value):
    """The integer root seed of an experiment from None (fresh entropy, drawn here so
    that the run records which seed it used), an integer in 0..MAX_SEED, or a
    `numpy.random.Generator` (one integer is drawn from it)."""
    if value is None or isinstance(value, np.random.Generator):
        rng = generator(name, value)
        return int(rng.integers(MAX_SEED, endpoint=True))
    if not is_integer(value):
        raise _type_error(name, f"None, an integer in 0..{MAX_SEED} or a "
                                "numpy.random.Generator", value)
    return seed(name, value)


def instance(name, value, cls, description=None):
    """Returns `value` if it is an instance of `cls` (a class or a tuple of them)."""
    if not isinstance(value, cls):
        if description is None:
            classes = cls if isinstance(cls, tuple) else (cls,)
            description = " or ".join(f"a {c.__name__}" for c in classes)
        raise _type_error(name, description, value)
    return value


def function(name, value, allow_none=True):
    """Returns `value` if it is callable (or None, when allowed)."""
    if value is None and allow_none:
        return None
    if not callable(value):
        raise _type_error(name, "a function" + (" or None" if allow_none else ""), value)
    return value


def finite_array(name, value, shape=None, ndim=None):
    """`value` as a float array, checked to be finite and of the given shape (None
    entries in `shape` match any length) or number of dimensions.

    Only real numbers are accepted: bools, text (even "1.5"), complex numbers and
    other objects raise `ArgumentTypeError`, never a silent conversion."""
    if isinstance(value, (str, bytes)):
        raise _type_error(name, "an array of real numbers", value)
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):  # ragged nested sequences
        raise _type_error(name, "an array of real numbers", value) from None
    if raw.dtype.kind not in "iuf" and not (
            raw.dtype.kind == "O" and all(is_real(v) for v in raw.ravel())):
        raise _type_error(name, "an array of real numbers", value)
    array = raw.astype(float)
    if shape is not None:
        wanted = "(" + ", ".join("any" if s is None else str(s) for s in shape) + ")"
        if array.ndim != len(shape) or any(s is not None and s != n
                                           for s, n in zip(shape, array.shape)):
            raise ValueError(f"{name} must have shape {wanted}, got shape {array.shape}: "
                             f"{show(value)}")
    if ndim is not None and array.ndim != ndim:
        raise ValueError(f"{name} must have {ndim} dimension(s), got {array.ndim}: "
                         f"{show(value)}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must hold finite numbers only (no NaN or infinity), "
                         f"got {show(value)}")
    return array


def integer_array(name, value, ndim=None):
    """`value` as an int64 array of integers (Python or numpy integers; bools, floats,
    even whole ones, and text are refused as the wrong type), of `ndim` dimensions
    if given."""
    if isinstance(value, (str, bytes)):
        raise _type_error(name, "an array of integers", value)
    array = np.asarray(value)
    if array.dtype.kind not in "iu":
        raise _type_error(name, "an array of integers", value)
    if not isinstance(value, np.ndarray) and any(  # numpy turns [True, 10] into [1, 10]
            isinstance(v, (bool, np.bool_)) for v in np.asarray(value, dtype=object).ravel()):
        raise _type_error(name, "an array of integers", value)
    if ndim is not None and array.ndim != ndim:
        raise ValueError(f"{name} must have {ndim} dimension(s), got {array.ndim}: "
                         f"{show(value)}")
    return array.astype(np.int64)


def integer_values(name, value, allowed="an integer or an array of integers"):
    """`value`, an integer or an array of them, as an int64 array (0-d for one integer):
    Python or numpy integers only. Bools (also inside a list, where numpy would turn
    them into 0 and 1), floats (even whole ones), text and other objects raise
    `ArgumentTypeError`, whose message says `allowed`."""
    if isinstance(value, (str, bytes)):
        raise _type_error(name, allowed, value)
    try:
        array = np.asarray(value)
    except (TypeError, ValueError):  # ragged nested sequences
        raise _type_error(name, allowed, value) from None
    if array.dtype.kind not in "iu":
        raise _type_error(name, allowed, value)
    if not isinstance(value, np.ndarray) and array.ndim > 0 and any(
            isinstance(v, (bool, np.bool_)) for v in np.asarray(value, dtype=object).ravel()):
        raise _type_error(name, allowed, value)
    return array.astype(np.int64)


def event_numbers(name, value):
    """`value` as an int64 array (0-d for one number) of event numbers: the trial or
    episode at which something happened, counted from 1, or -1 where it never did.
    Integers only (`integer_values`); empty input, 0 and negatives other than -1 raise
    ValueError, the message showing the first value refused."""
    allowed = "event numbers: integers from 1 (a trial or an episode), or -1 for never"
    array = integer_values(name, value, allowed)
    if array.size == 0:
        raise ValueError(f"{name} must hold at least one event number, got none: "
                         f"{show(value)}")
    refused = array[(array < 1) & (array != -1)]
    if refused.size:
        raise ValueError(f"{name} must hold {allowed}, got {int(refused.flat[0])} in "
                         f"{show(value)}")
    return array


def broadcastable(name, value, other_name, other):
    """Raises ValueError, naming both, if the arrays `value` and `other` (of the
    arguments `name` and `other_name`) have shapes that do not broadcast together."""
    try:
        np.broadcast_shapes(np.shape(value), np.shape(other))
    except ValueError:
        raise ValueError(f"{name} and {other_name} must have shapes that broadcast "
                         f"together (element-wise), got {np.shape(value)} and "
                         f"{np.shape(other)}") from None


def finite_results(name, value, *results):
    """Raises ValueError, naming `name` and showing `value`, if any of `results` (sums,
    means or spreads computed from `value`) is not finite: numbers near the largest
    float (about 1e308; 1e154 for squares) overflow, and a band or a p-value of
    infinities means nothing."""
    if not all(np.all(np.isfinite(result)) for result in results):
        raise ValueError(f"{name} must be small enough for their sums and squares to stay "
                         f"finite (NaN and infinity have no meaning here), got {show(value)}")


def available_memory():
    """Bytes of memory this machine can still give (Linux: MemAvailable)."""
    try:
        with open("/proc/meminfo") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_AVPHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        return 8 * 1024**3


def _bytes(n):
    for unit in ("bytes", "KB", "MB", "GB", "TB", "PB"):
        if n < 1000 or unit == "PB":
            return f"{n:.0f} {unit}" if unit == "bytes" else f"{n:.1f} {unit}"
        n /= 1000
    return f"{n} bytes"


def fits_in_memory(what, nbytes):
    """Raises ValueError if `nbytes` (what `what` needs) is more than the machine's
    available memory, saying how much it would need."""
    available = available_memory()
    if nbytes > available:
        raise ValueError(f"{what} would need about {_bytes(nbytes)} of memory, more than "
                         f"the {_bytes(available)} available on this machine: ask for "
                         f"fewer seeds or a shorter run")
