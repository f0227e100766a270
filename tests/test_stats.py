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


def test_the_paired_p_value_is_the_sign_flip_share_enumerated_for_few_seeds():
    # Five differences all positive: of the 32 sign flips, 2 have a mean as far from 0
    # (all +, all -); one-sided, 1 of 32.
    assert stats.paired_p_value([1.0, 2.0, 1.0, 3.0, 1.0]) == pytest.approx(2 / 32)
    assert stats.paired_p_value([1.0, 2.0, 1.0, 3.0, 1.0],
                                alternative="greater") == pytest.approx(1 / 32)
    assert stats.paired_p_value([1.0, 2.0, 1.0, 3.0, 1.0], alternative="less") == 1.0
    assert stats.paired_p_value([0.0, 0.0, 0.0]) == 1.0


def test_the_paired_p_value_of_many_seeds_is_seeded_and_near_the_sign_test():
    # Differences of +1 and -1 only: the sign-flip test is the sign test.
    differences = np.r_[np.ones(30), -np.ones(10)]
    p = stats.paired_p_value(differences, seed=3)
    assert p == stats.paired_p_value(differences, seed=3)
    assert p == pytest.approx(scipy_stats.binomtest(30, 40).pvalue, abs=0.002)


def test_holm_calls_clear_only_what_survives_the_family():
    # Raw p-values 0.01, 0.02, 0.04: each below 5% alone. Holm compares them with
    # 0.05/3, 0.05/2 and 0.05: the first is clear, the second (0.02 < 0.025) too, the
    # third (0.04 < 0.05) too; with a fourth member at 0.5, the thresholds become
    # 0.0125, 0.0167, 0.025, 0.05 and only the first is clear.
    three = stats.corrected_verdicts({"a": 0.01, "b": 0.02, "c": 0.04})
    assert [v["clear"] for v in three.values()] == [True, True, True]
    four = stats.corrected_verdicts({"a": 0.01, "b": 0.02, "c": 0.04, "d": 0.5})
    assert [v["clear"] for v in four.values()] == [True, False, False, False]
    assert four["b"]["p_holm"] == pytest.approx(3 * 0.02)
    assert all(v["n_family"] == 4 for v in four.values())


def test_holm_takes_per_seed_differences_as_well_as_p_values():
    rng = np.random.default_rng(0)
    family = {"shifted": rng.normal(1.0, 0.5, 20), "null": rng.normal(0.0, 0.5, 20)}
    verdicts = stats.corrected_verdicts(family)
    assert verdicts["shifted"]["clear"] and not verdicts["null"]["clear"]
    assert verdicts["shifted"]["mean"] == pytest.approx(family["shifted"].mean())
    assert verdicts["shifted"]["p"] == stats.paired_p_value(family["shifted"])


@pytest.mark.parametrize("family", [{}, [0.1], {"a": 1.5}, {"a": [1.0, np.nan]}])
def test_holm_refuses_a_family_that_is_not_one(family):
    with pytest.raises((ValueError, TypeError), match="family"):
        stats.corrected_verdicts(family)


def test_a_bound_is_named():
    assert stats.at_bound([1.0, 1.0]) == "ceiling"
    assert stats.at_bound([0.0, 0.0]) == "floor"
    assert stats.at_bound([0.0, 1.0]) is None
    assert stats.at_bound([3.0, 3.0], high=3) == "ceiling"


def test_the_paired_p_value_refuses_bad_input():
    with pytest.raises(ValueError, match="differences"):
        stats.paired_p_value([])
    with pytest.raises(ValueError, match="alternative"):
        stats.paired_p_value([1.0, 2.0], alternative="up")
    with pytest.raises((ValueError, TypeError), match="differences"):
        stats.paired_p_value([[1.0, 2.0]])


def test_paired_gaps_keep_the_seeds_where_both_events_happened():
    arm, baseline = np.array([3, -1, 5, 2, 7]), np.array([4, 2, -1, 2, 1])
    gaps = stats.paired_gaps(arm, baseline)
    assert gaps.dtype == float and gaps.tolist() == [-1.0, 0.0, 6.0]
    assert stats.paired_gaps(np.array([-1, -1]), np.array([1, 2])).size == 0
    with pytest.raises(TypeError, match="arm must hold integers"):
        stats.paired_gaps(np.array([1.5, 2.0]), np.array([1, 2]))
    with pytest.raises(ValueError, match="one event number per seed each, got 2 and 3"):
        stats.paired_gaps(np.array([1, 2]), np.array([1, 2, 3]))
    with pytest.raises(ValueError, match="baseline must be one-dimensional"):
        stats.paired_gaps(np.array([1, 2]), np.array([[1, 2]]))
