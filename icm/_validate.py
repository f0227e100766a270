"""Argument checks shared by the whole package: each raises a ValueError that names
the argument, shows the value it got, and says what is allowed."""

import numbers

import numpy as np


def _is_real(value):
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _is_integer(value):
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def in_closed_interval(name, value, low, high):
    """Returns `value` as a float if low <= value <= high, else raises ValueError."""
    if not _is_real(value) or not np.isfinite(value) or not low <= value <= high:
        raise ValueError(f"{name} must be a number in [{low}, {high}], got {value!r}")
    return float(value)


def learning_rate(name, value):
    """Returns `value` as a float if 0 < value <= 1, else raises ValueError."""
    if not _is_real(value) or not np.isfinite(value) or not 0 < value <= 1:
        raise ValueError(f"{name} must be a learning rate in (0, 1], got {value!r}")
    return float(value)


def positive(name, value):
    """Returns `value` as a float if it is a finite number > 0, else raises ValueError."""
    if not _is_real(value) or not np.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return float(value)


def non_negative(name, value):
    """Returns `value` as a float if it is a finite number >= 0, else raises ValueError."""
    if not _is_real(value) or not np.isfinite(value) or value < 0:
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return float(value)


def integer_at_least(name, value, minimum):
    """Returns `value` as an int if it is an integer >= minimum, else raises ValueError."""
    if not _is_integer(value) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def integer_in_range(name, value, low, high):
    """Returns `value` as an int if it is an integer with low <= value <= high."""
    if not _is_integer(value) or not low <= value <= high:
        raise ValueError(f"{name} must be an integer in {low}..{high}, got {value!r}")
    return int(value)


def one_of(name, value, allowed):
    """Returns `value` if it is one of `allowed`, else raises ValueError listing them."""
    if value not in allowed:
        listed = ", ".join(repr(a) for a in allowed)
        raise ValueError(f"{name} must be one of {listed}, got {value!r}")
    return value


def seed(name, value):
    """Accepts None or a non-negative integer seed; returns it unchanged."""
    if value is None:
        return None
    if not _is_integer(value) or value < 0:
        raise ValueError(f"{name} must be None or an integer >= 0, got {value!r}")
    return int(value)


def generator(name, value):
    """A `numpy.random.Generator` from None, an integer seed >= 0, or a Generator
    (returned as it is); anything else raises ValueError."""
    if isinstance(value, np.random.Generator):
        return value
    return np.random.default_rng(seed(name, value))
