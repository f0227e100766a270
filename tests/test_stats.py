"""icm.stats: the bands' confidence level, checked against a distribution known exactly;
the sign-flip test, Holm's correction and the power on known cases; and, with
hypothesis, what every function promises on inputs it generates."""

import contextlib
import gc

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
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
    with pytest.raises(TypeError, match="arm must be event numbers"):
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


# --- properties (hypothesis): what each function promises, on many generated inputs ---
#
# A fixed profile: derandomized (the same examples on every run and every machine, no
# example database), few examples and no deadline (a shared machine is slow at times).
# A property that fails prints the smallest input that breaks it.

PROPERTIES = settings(derandomize=True, database=None, max_examples=60, deadline=None,
                      suppress_health_check=[HealthCheck.too_slow], print_blob=False)
FEW = settings(PROPERTIES, max_examples=15)
"""For the properties whose every example costs tens of milliseconds."""


@contextlib.contextmanager
def frozen_heap():
    """The objects made so far left out of garbage collection (`gc.freeze`) while the
    block runs: statsmodels' `multipletests` (`stats.corrected_verdicts`) collects the
    garbage at every call, 0.06 CPU-seconds in a test process, 0.0001 with the heap
    frozen. Nothing made in the block is kept from collection."""
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()

EVENT = st.one_of(st.just(-1), st.integers(1, 300))
"""An event number: a trial or an episode from 1, or -1 for never."""
MODERATE = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)
"""A finite number far from overflow (sums of thousands of them stay finite)."""
P_VALUE = st.floats(0.0, 1.0)
ALTERNATIVES = ("two-sided", "less", "greater")


@st.composite
def differences_and_order(draw, low=1, high=stats.EXACT_FLIPS_UP_TO, elements=MODERATE):
    """Per-seed differences (from `low` to `high` seeds) and another order of them."""
    values = draw(st.lists(elements, min_size=low, max_size=high))
    return np.array(values), np.array(draw(st.permutations(values)))


@st.composite
def paired_events(draw, most=12):
    """Two runs' event numbers on the same seeds (arm, baseline), and a reordering of
    the seeds (the same for both)."""
    n = draw(st.integers(1, most))
    arm = np.array(draw(st.lists(EVENT, min_size=n, max_size=n)))
    baseline = np.array(draw(st.lists(EVENT, min_size=n, max_size=n)))
    return arm, baseline, np.array(draw(st.permutations(range(n))))


@st.composite
def per_seed_values(draw, most_seeds=25):
    """Values [seed, point] of finite numbers: 1 to `most_seeds` seeds, 1 to 3 points."""
    n, m = draw(st.integers(1, most_seeds)), draw(st.integers(1, 3))
    return np.array(draw(st.lists(st.lists(MODERATE, min_size=m, max_size=m),
                                  min_size=n, max_size=n)))


@PROPERTIES
@given(differences_and_order(), st.sampled_from(ALTERNATIVES))
def test_a_paired_p_value_is_in_0_1_and_does_not_depend_on_the_seeds_order(pair, side):
    differences, reordered = pair
    p = stats.paired_p_value(differences, alternative=side)
    assert 0 < p <= 1
    assert stats.paired_p_value(reordered, alternative=side) == p


TIED = st.sampled_from([1e9 / 3, 2e9 / 3, -1e9, 0.1, 0.2, -0.3, 1e6 / 3, 7.0])
"""Differences drawn from a few values some of which add up to 0 (1e9 / 3 + 2e9 / 3 -
1e9, 0.1 + 0.2 - 0.3), so that flipping them ties with the observed mean, while their
sums round differently with the order (by 1e-7 for the large ones)."""


@PROPERTIES
@given(differences_and_order(low=2, elements=TIED), st.sampled_from(ALTERNATIVES))
def test_ties_stay_ties_whatever_the_seeds_order(pair, side):
    differences, reordered = pair
    assert stats.paired_p_value(reordered, alternative=side) == stats.paired_p_value(
        differences, alternative=side)


@PROPERTIES
@given(st.lists(st.integers(7 * 10**3, 7 * 10**12).map(lambda k: k / 7), min_size=8,
                max_size=stats.EXACT_FLIPS_UP_TO))
def test_the_observed_differences_count_as_extreme_as_themselves_at_any_scale(values):
    # All positive: no flip has a larger mean than the observed one, every flip has a
    # smaller or equal one, and the identity counts whatever the rounding of large sums.
    n = len(values)
    assert 1 / 2 ** n <= stats.paired_p_value(values, alternative="greater") <= 1
    assert 2 / 2 ** n <= stats.paired_p_value(values) <= 1
    assert stats.paired_p_value(values, alternative="less") == 1.0


@PROPERTIES
@given(st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=1,
                max_size=stats.EXACT_FLIPS_UP_TO), st.sampled_from(ALTERNATIVES))
def test_differences_whose_sums_overflow_are_refused_the_others_answered(values, side):
    with np.errstate(over="ignore"):
        overflows = not np.isfinite(np.abs(values).sum())
    if overflows:
        with pytest.raises(ValueError, match="sums and squares to stay finite"):
            stats.paired_p_value(values, alternative=side)
    else:
        assert 1 / 2 ** len(values) <= stats.paired_p_value(values, alternative=side) <= 1


@PROPERTIES
@given(differences_and_order(elements=st.integers(-50, 50).map(float)))
def test_the_two_sided_p_value_is_twice_the_smaller_one_sided_one(pair):
    # Every flip enumerated, the null distribution is symmetric: for a mean other than
    # zero, the two-sided p-value counts the flips beyond it on both sides.
    differences, _ = pair
    two = stats.paired_p_value(differences)
    less = stats.paired_p_value(differences, alternative="less")
    greater = stats.paired_p_value(differences, alternative="greater")
    assert stats.paired_p_value(-differences) == two
    assert stats.paired_p_value(-differences, alternative="greater") == less
    if differences.sum() == 0:
        assert two == 1.0
    else:
        assert two == min(1.0, 2 * min(less, greater))
        assert max(less, greater) == 1.0 or less + greater > 1.0


@FEW
@given(differences_and_order(low=stats.EXACT_FLIPS_UP_TO + 1, high=60,
                             elements=st.integers(-3, 3).map(float)))
def test_past_the_enumerated_seeds_the_p_value_is_seeded_and_the_order_moves_it_little(pair):
    differences, reordered = pair
    p = stats.paired_p_value(differences, seed=5)
    assert p == stats.paired_p_value(differences, seed=5) and 0 < p <= 1
    # Two estimates from 20,000 flips each: their standard error is at most 0.005.
    assert abs(stats.paired_p_value(reordered, seed=5) - p) <= 0.03


@st.composite
def families(draw):
    """{name: p-value}, 1 to 8 comparisons (ties likely: p-values from a small grid
    half of the time)."""
    values = st.one_of(P_VALUE, st.sampled_from([0.0, 0.001, 0.01, 0.0125, 0.025, 0.05, 1.0]))
    p = draw(st.lists(values, min_size=1, max_size=8))
    return {f"c{i}": value for i, value in enumerate(p)}


def _holm(p_values):
    """Holm's adjusted p-values written from the definition: the i-th smallest raw
    p-value times the comparisons not yet passed (m - i + 1), raised to the largest
    before it (step-down), at most 1."""
    p = np.asarray(p_values, dtype=float)
    m = len(p)
    passed = np.array([(p < q).sum() for q in p])  # how many come strictly before
    return np.array([min(1.0, max((m - passed[j]) * p[j] for j in range(m) if p[j] <= q))
                     for q in p])


@PROPERTIES
@given(families(), st.floats(0.001, 0.5))
def test_holms_adjusted_p_values_rise_with_the_raw_ones_and_never_fall_below_them(family, rate):
    with frozen_heap():
        verdicts = stats.corrected_verdicts(family, rate=rate)
        backwards = stats.corrected_verdicts(dict(reversed(family.items())), rate=rate)
    assert list(verdicts) == list(family)
    raw = np.array([v["p"] for v in verdicts.values()])
    adjusted = np.array([v["p_holm"] for v in verdicts.values()])
    clear = np.array([v["clear"] for v in verdicts.values()])
    assert raw.tolist() == list(family.values())
    assert np.all(adjusted >= raw) and np.all(adjusted <= 1)
    order = np.argsort(raw, kind="stable")
    assert np.all(np.diff(adjusted[order]) >= 0)  # monotone in the raw p-values
    np.testing.assert_allclose(adjusted, _holm(raw), rtol=1e-12, atol=0)
    # Clear: the adjusted p-value at or below the rate (up to rounding), and a step
    # down: whatever has a smaller raw p-value than a clear one is clear too.
    assert np.all(adjusted[clear] <= rate * (1 + 1e-12))
    assert np.all(adjusted[~clear] >= rate * (1 - 1e-12))
    for i in np.flatnonzero(clear):
        assert np.all(clear[raw <= raw[i]])
    assert all(v["n_family"] == len(family) and v["mean"] is None for v in verdicts.values())
    # The family's order changes nothing.
    assert {name: backwards[name] for name in family} == verdicts


@FEW
@given(st.lists(differences_and_order(high=10, elements=st.integers(-5, 5).map(float)),
                min_size=1, max_size=4))
def test_holm_on_differences_uses_their_p_values_and_means(members):
    family = {f"c{i}": differences for i, (differences, _) in enumerate(members)}
    reordered = {f"c{i}": again for i, (_, again) in enumerate(members)}
    with frozen_heap():
        verdicts = stats.corrected_verdicts(family)
        again = stats.corrected_verdicts(reordered)
    for name, differences in family.items():
        assert verdicts[name]["p"] == stats.paired_p_value(differences)
        assert verdicts[name]["mean"] == float(differences.mean())
    # Each comparison's seeds in another order: the same verdicts.
    assert [v["clear"] for v in again.values()] == [v["clear"] for v in verdicts.values()]


@PROPERTIES
@given(st.integers(1, 400).flatmap(lambda n: st.tuples(st.integers(0, n), st.just(n))),
       st.floats(0.01, 0.999))
def test_a_shares_interval_holds_the_share_within_0_1(counts, level):
    k, n = counts
    low, high = stats.share_interval(k, n, level)
    assert 0.0 <= low <= k / n <= high <= 1.0
    assert (low == 0.0) == (k == 0) and (high == 1.0) == (k == n)
    assert low < high  # never a point, not even when no seed (or every seed) succeeds
    # The failures' interval is the successes' mirrored.
    mirrored = stats.share_interval(n - k, n, level)
    assert mirrored == (pytest.approx(1 - high, abs=1e-12), pytest.approx(1 - low, abs=1e-12))
    # A higher level holds the lower level's interval.
    wider = stats.share_interval(k, n, min(0.9999, level + 0.05))
    assert wider[0] <= low and high <= wider[1]
    # Arrays give what each count gives alone.
    lows, highs = stats.share_interval(np.array([k, 0]), np.array([n, n]), level)
    assert (lows[0], highs[0]) == (low, high)


@PROPERTIES
@given(P_VALUE, P_VALUE, P_VALUE)
def test_a_verdict_reads_the_whole_interval(a, b, threshold):
    low, high = min(a, b), max(a, b)
    words = stats.verdict(low, high, threshold)
    assert words in stats.VERDICTS
    assert (words == "holds") == (low >= threshold)
    assert (words == "fails") == (high < threshold)


@PROPERTIES
@given(per_seed_values(), st.floats(0.05, 0.99))
def test_a_bootstrap_band_holds_its_mean_within_the_values_range(values, level):
    mean, low, high = stats.bootstrap_band(values, level=level, resamples=100, seed=3)
    np.testing.assert_array_equal(mean, values.mean(axis=0))
    assert np.all(values.min(axis=0) <= low) and np.all(low <= mean)
    assert np.all(mean <= high) and np.all(high <= values.max(axis=0))
    again = stats.bootstrap_band(values, level=level, resamples=100, seed=3)
    for first, second in zip((mean, low, high), again):
        np.testing.assert_array_equal(first, second)


@PROPERTIES
@given(per_seed_values(), st.floats(0.05, 0.9))
def test_a_mean_band_holds_its_mean_and_widens_with_its_level(values, level):
    mean, low, high = stats.mean_band(values, level=level)
    np.testing.assert_array_equal(mean, values.mean(axis=0))
    assert np.all(low <= mean) and np.all(mean <= high)
    _, wide_low, wide_high = stats.mean_band(values, level=level + 0.05)
    assert np.all(wide_low <= low) and np.all(high <= wide_high)
    if len(values) == 1:
        np.testing.assert_array_equal(low, mean)
        np.testing.assert_array_equal(high, mean)


@PROPERTIES
@given(EVENT, EVENT)
def test_an_event_comes_first_when_it_happened_and_the_other_did_later_or_never(a, b):
    first = bool(stats.comes_first(a, b))
    assert first == (a >= 1 and (b == -1 or a < b))
    assert not (first and stats.comes_first(b, a))  # never both ways


@PROPERTIES
@given(paired_events())
def test_comes_first_works_element_wise(events):
    arm, baseline, _ = events
    np.testing.assert_array_equal(stats.comes_first(arm, baseline),
                                  [stats.comes_first(int(a), int(b))
                                   for a, b in zip(arm, baseline)])


@PROPERTIES
@given(paired_events())
def test_paired_gaps_follow_the_seeds_whatever_their_order(events):
    arm, baseline, order = events
    gaps = stats.paired_gaps(arm, baseline)
    both = (arm >= 1) & (baseline >= 1)
    assert gaps.tolist() == (arm[both] - baseline[both]).astype(float).tolist()
    reordered = stats.paired_gaps(arm[order], baseline[order])
    assert reordered.tolist() == (arm[order][both[order]] - baseline[order][both[order]]
                                  ).astype(float).tolist()
    assert sorted(reordered.tolist()) == sorted(gaps.tolist())


@PROPERTIES
@given(st.lists(st.lists(st.booleans(), min_size=1, max_size=12), min_size=1, max_size=4))
def test_first_from_which_is_where_the_condition_holds_for_good(rows):
    width = min(len(row) for row in rows)
    condition = np.array([row[:width] for row in rows])
    first = stats.first_from_which(condition)
    for row, index in zip(condition, first):
        if index == -1:
            assert not row[-1]
        else:
            assert row[index:].all() and (index == 0 or not row[index - 1])


@PROPERTIES
@given(st.lists(st.floats(0.0, 1e6), min_size=1, max_size=30), st.floats(0.0, 1.0),
       st.data())
def test_first_below_is_the_first_point_under_the_fraction_of_the_peak(curve, fraction, data):
    curve = np.array(curve)
    after = data.draw(st.none() | st.integers(0, len(curve) - 1))
    start = int(np.argmax(curve)) if after is None else after
    index = stats.first_below(curve, fraction, after)
    line = fraction * curve.max()
    assert np.all(curve[start:index if index >= 0 else None] >= line)
    assert index == -1 or (index >= start and curve[index] < line)


@PROPERTIES
@given(st.integers(1, 500), st.integers(1, 600))
def test_every_nth_keeps_every_step_and_the_last_point(n, every):
    kept = stats.every_nth(n, every)
    assert kept[0] == 0 and kept[-1] == n - 1
    assert np.all(np.diff(kept) > 0)
    assert set(kept.tolist()) == set(range(0, n, every)) | {n - 1}


@PROPERTIES
@given(st.lists(st.sampled_from([0.0, 0.5, 1.0]), min_size=1, max_size=10))
def test_a_bound_is_named_only_when_every_value_is_at_it(values):
    where = stats.at_bound(values)
    assert (where == "ceiling") == all(v == 1.0 for v in values)
    assert (where == "floor") == all(v == 0.0 for v in values)


@FEW
@given(st.lists(st.integers(-2, 3).map(float), min_size=1, max_size=6), st.integers(1, 8),
       st.sampled_from(("less", "greater")))
def test_a_power_is_a_share_of_the_simulations(differences, n_seeds, side):
    power = stats.paired_power(differences, n_seeds, side, simulations=100, seed=1)
    assert 0.0 <= power <= 1.0 and round(power * 100) == power * 100
    assert stats.paired_power(differences, n_seeds, side, simulations=100, seed=1) == power


@FEW
@given(st.lists(st.integers(-1, 3).map(float), min_size=1, max_size=5),
       st.floats(0.3, 0.95), st.integers(1, 9))
def test_the_seeds_found_reach_the_power_and_one_fewer_does_not(differences, power, most):
    found = stats.seeds_for_power(differences, "greater", power=power, simulations=100,
                                  most=most)

    def reached(n):
        return stats.paired_power(differences, n, "greater", simulations=100) >= power

    if found is None:
        assert not reached(most)
    else:
        assert 1 <= found <= most and reached(found)
        assert found == 1 or not reached(found - 1)
