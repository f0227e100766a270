"""Checks shared by the learners: contexts, states and observations."""

import collections.abc
import math

import numpy as np

from icm import _validate


def check_values(name, values, allow_text=False):
    """`values` as a tuple: a sequence (tuple, list or 1-d array) of finite numbers
    (or strings, if `allow_text`); NaN and infinity are refused, since NaN never
    equals itself and would make every comparison of contexts fail."""
    allowed = "a sequence of finite numbers" + (" or strings" if allow_text else "")
    if isinstance(values, np.ndarray):
        if values.ndim != 1:
            raise ValueError(f"{name} must be {allowed} (1-d), got {_validate.show(values)}")
        values = values.tolist()
    if isinstance(values, (str, bytes)) or not isinstance(values, (tuple, list)):
        raise _validate.ArgumentTypeError(f"{name} must be {allowed}, got "
                                          f"{_validate.show(values)}")
    for value in values:
        if allow_text and isinstance(value, str):
            continue
        if not _validate.is_real(value):
            raise _validate.ArgumentTypeError(f"{name} must be {allowed}, got "
                                              f"{_validate.show(values)}")
        if not math.isfinite(value):
            raise ValueError(f"{name} must be {allowed}, got {_validate.show(values)}")
    return tuple(_validate.scalar(v) for v in values)


def check_state(name, state):
    """Returns `state` if it is hashable (a valid key of a table), else raises."""
    try:
        hash(state)
    except TypeError:
        raise _validate.ArgumentTypeError(f"{name} must be hashable (a number, string or "
                                          f"tuple), got {_validate.show(state)}") from None
    if isinstance(state, float) and not math.isfinite(state):
        raise ValueError(f"{name} must not be NaN or infinite, got {state!r}")
    return state


def check_keys(name, keys):
    """`keys` as a tuple of observation entry names (a sequence of strings; a single
    string is refused, since it would be read letter by letter)."""
    if isinstance(keys, str) or not isinstance(keys, (tuple, list)) or \
            not all(isinstance(k, str) for k in keys) or not keys:
        raise _validate.ArgumentTypeError(f"{name} must be a non-empty tuple of observation "
                                          f"entry names, got {_validate.show(keys)}")
    return tuple(keys)


def read_observation(name, observation, keys):
    """The entries `keys` of `observation` (a mapping of arrays), flattened into one
    tuple of numbers; raises if it is not a mapping, lacks an entry or holds NaN."""
    if not isinstance(observation, collections.abc.Mapping):
        raise _validate.ArgumentTypeError(f"{name} must be an observation (a mapping of "
                                          f"entry name to array), got {_validate.show(observation)}")
    values = []
    for key in keys:
        if key not in observation:
            raise ValueError(f"{name} has no entry {key!r}; it has {', '.join(map(repr, observation))}")
        values.extend(np.asarray(observation[key]).ravel().tolist())
    return check_values(f"{name}[{', '.join(map(repr, keys))}]", values)
