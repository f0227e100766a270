"""Summaries over seeds: means with confidence bands, and "from when on" trial numbers."""

import numpy as np
from scipy import stats as _scipy_stats


def mean_band(values, level=0.95):
    """Mean over the first axis (seeds) and a confidence band for that mean.

    The band is mean +/- t * standard error, with Student's t for n - 1 degrees of
    freedom (n = number of seeds), so it is honest for few seeds too.

    Args:
      values: array [seed, ...].
      level: confidence level in (0, 1).

    Returns:
      (mean, low, high), arrays of shape values.shape[1:]. With one seed the band is
      the mean itself.
    """
    values = np.asarray(values, dtype=float)
    if not 0 < level < 1:
        raise ValueError(f"level must be in (0, 1), got {level!r}")
    n = values.shape[0]
    mean = values.mean(axis=0)
    if n < 2:
        return mean, mean.copy(), mean.copy()
    half = _scipy_stats.t.ppf(0.5 + level / 2, n - 1) * values.std(axis=0, ddof=1) / np.sqrt(n)
    return mean, mean - half, mean + half


def first_from_which(condition):
    """For a boolean array [..., time], the first index from which `condition` holds
    until the end, or -1 where it does not hold at the last index."""
    condition = np.asarray(condition, dtype=bool)
    # Index of the last False, + 1; where everything holds, 0.
    reversed_false = ~condition[..., ::-1]
    has_false = reversed_false.any(axis=-1)
    last_false = condition.shape[-1] - 1 - np.argmax(reversed_false, axis=-1)
    first = np.where(has_false, last_false + 1, 0)
    return np.where(condition[..., -1], first, -1)


def first_below(curve, fraction, after=None):
    """The first index, at or after the curve's peak (or `after`), where `curve` falls
    below `fraction` of its peak; -1 if it never does."""
    curve = np.asarray(curve, dtype=float)
    peak = int(np.argmax(curve)) if after is None else int(after)
    below = np.flatnonzero(curve[peak:] < fraction * curve.max())
    return int(peak + below[0]) if below.size else -1


def comes_first(first, second):
    """Where an event numbered `first` (a trial or an episode, from 1; -1 for never)
    comes strictly before one numbered `second`: it happened, and the other never did
    or did later. Works on numbers and on arrays (element-wise)."""
    first, second = np.asarray(first), np.asarray(second)
    return (first >= 1) & ((second == -1) | (first < second))
