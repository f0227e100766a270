"""Helpers shared by the environments: action, seed and time-limit checks."""

import math

import numpy as np

from icm import _validate


def check_discrete_action(action, num_values, name="action"):
    """Returns `action` as a Python int if it names one of `num_values` choices.

    Accepts Python and numpy integers and 0-d integer arrays (what dm_env agents
    usually pass); refuses bools, floats (even 2.0), strings and arrays with an
    `ArgumentTypeError`, and integers outside 0..num_values-1 with a ValueError.
    """
    return _validate.integer(name, action, 0, num_values - 1)


def check_seed(seed, name="seed"):
    """A `numpy.random.Generator` from `seed`: None, an integer >= 0 or a Generator
    (the one rule for seeds everywhere in the package)."""
    return _validate.generator(name, seed)


def dm_control_random(generator):
    """A `numpy.random.RandomState` for dm_control's `Task.random`, derived from
    `generator` without drawing from it (the episode rules draw from `generator`
    itself, so that the tabular twin and the physics draw the same numbers)."""
    child = generator.spawn(1)[0]
    return np.random.RandomState(int(child.integers(2**32)))


def check_time_limit(time_limit):
    """Returns `time_limit` (seconds) if it is a number > 0; infinity means no limit."""
    if _validate.is_real(time_limit) and math.isinf(float(_validate.scalar(time_limit))) \
            and float(_validate.scalar(time_limit)) > 0:
        return float("inf")
    return _validate.real("time_limit", time_limit, 0.0, low_open=True,
                          allowed="a number of seconds > 0 (float('inf') for no limit)")
