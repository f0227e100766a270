"""Helpers shared by the environments: action checking and seeded generators."""

import numbers

import numpy as np


def check_discrete_action(action, num_values):
    """Returns `action` as a Python int if it names one of `num_values` choices.

    Accepts Python and numpy integers and 0-d integer arrays (what dm_env agents
    usually pass). Anything else raises ValueError saying what is allowed.
    """
    value = action
    if isinstance(value, np.ndarray) and value.shape == ():
        value = value.item()
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ValueError(
            f"action must be an integer in 0..{num_values - 1}, got {action!r}")
    if not 0 <= value < num_values:
        raise ValueError(
            f"action must be an integer in 0..{num_values - 1}, got {action!r}")
    return int(value)


def random_state(seed):
    """Returns a `numpy.random.RandomState` for `seed` (None, an int or a RandomState).

    The environments use RandomState, as dm_control's tasks do, so that a tabular
    twin and its physics version draw the same episode from the same seed.
    """
    if isinstance(seed, np.random.RandomState):
        return seed
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)
                             or seed < 0):
        raise ValueError(f"seed must be None, an integer >= 0 or a RandomState, got {seed!r}")
    return np.random.RandomState(seed)
