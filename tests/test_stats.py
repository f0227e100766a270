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


def test_paired_power_is_the_exact_tests_on_known_cases():
    from math import comb

    from icm.stats import paired_power, seeds_for_power
    # Equal positive differences: the exact one-sided test cannot go below 1/16 on 4
    # seeds, so it never rejects at 5% (a t approximation on the standardised effect
    # would say near 1), and always does on 5 (1/32).
    assert paired_power([1.0, 1.0, 1.0], 4, "greater") == 0.0
    assert paired_power([1.0, 1.0, 1.0], 5, "greater") == 1.0
    assert seeds_for_power([1.0, 1.0], "greater") == 5
    # Differences of +1 and -1, three in four positive: on 8 seeds the test rejects
    # when 7 or 8 are positive (P(>= 7 of 8 | fair) = 9/256 < 5%, P(>= 6) = 37/256),
    # so the power is P(Binomial(8, 3/4) >= 7) = 0.367.
    exact = sum(comb(8, k) * 0.75 ** k * 0.25 ** (8 - k) for k in (7, 8))
    simulated = paired_power([1.0, 1.0, 1.0, -1.0], 8, "greater", simulations=4000)
    assert abs(simulated - exact) < 3 * (exact * (1 - exact) / 4000) ** 0.5
    # The other direction, and ties (zeros flip to themselves): power falls with them.
    assert paired_power([-1.0, -1.0, -1.0, 1.0], 8, "less", simulations=4000) == simulated
    assert paired_power([1.0, 0.0, 1.0, 0.0], 8, "greater") < paired_power(
        [1.0, 1.0, 1.0, 1.0], 8, "greater")
    # Same arguments, same power; more seeds, more power.
    differences = np.random.default_rng(3).normal(0.5, 1.0, 30)
    power = lambda n: paired_power(differences, n, "greater", simulations=200)
    assert power(10) == power(10) and power(16) > power(6)
    assert seeds_for_power([1.0, -1.0], "greater", simulations=100, most=12) is None


def test_paired_power_refuses_bad_input():
    from icm.stats import paired_power
    with pytest.raises(ValueError, match="n_seeds"):
        paired_power([1.0], 0, "less")
    with pytest.raises(ValueError, match="alternative"):
        paired_power([1.0], 5, "two-sided")
    with pytest.raises(ValueError, match="differences"):
        paired_power([], 5, "less")
