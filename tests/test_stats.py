"""icm.stats: the bands' confidence level, checked against a distribution known exactly."""

import numpy as np
import pytest
from scipy import stats as scipy_stats

from icm import stats

# 100 seeds, 30 of which saw an event (1) and 70 did not (0): the mean of a bootstrap
# resample (100 seeds drawn with replacement) is then Binomial(100, 0.3) / 100, so the
# band's bounds are known quantiles of that distribution.
EVENTS = np.repeat([1.0, 0.0], [30, 70])[:, None]
RESAMPLES = 20_000  # enough for each sample quantile to fall on the exact one


def _binomial_band(level):
    """The central `level` band of Binomial(100, 0.3) / 100: its (1 - level) / 2 and
    (1 + level) / 2 quantiles.

    Args:
      level: the confidence level, in (0, 1).

    Returns:
      (low, high).
    """
    low, high = scipy_stats.binom.ppf([(1 - level) / 2, (1 + level) / 2], 100, 0.3) / 100
    return low, high


def test_the_bootstrap_band_is_95_percent_by_default():
    assert _binomial_band(0.95) == (0.21, 0.39)
    mean, low, high = stats.bootstrap_band(EVENTS, resamples=RESAMPLES)
    assert mean[0] == pytest.approx(0.3)
    # Half an event of tolerance: a 90% band would give 0.22 or 0.23 to 0.38.
    assert low[0] == pytest.approx(0.21, abs=0.005)
    assert high[0] == pytest.approx(0.39, abs=0.005)


@pytest.mark.parametrize("level", [0.5, 0.8])
def test_the_bootstrap_band_holds_the_central_share_level_of_the_resampled_means(level):
    expected = _binomial_band(level)
    _, low, high = stats.bootstrap_band(EVENTS, level=level, resamples=RESAMPLES)
    assert (low[0], high[0]) == pytest.approx(expected, abs=0.005)
    assert expected != pytest.approx(_binomial_band(0.9), abs=0.005)  # the level shows
