"""Summaries over seeds: means with confidence bands, "from when on" trial numbers, the
Wilson interval of a share of seeds and the verdict it gives on a threshold."""

import functools
import statistics

import numpy as np

from icm import _exact, _validate


BAND_LEVEL = 0.95
"""The confidence level of every band the book draws around a mean over seeds."""


def _per_seed_values(values):
    """`values` as a float array [seed, ...] of finite numbers, with at least one seed
    and at least one value per seed (`mean_band`, `bootstrap_band`)."""
    values = _validate.finite_array("values", values)
    if values.ndim < 1 or values.shape[0] < 1:
        raise ValueError(f"values must have a seed axis with at least one seed, got shape "
                         f"{values.shape}")
    if values.size == 0:
        raise ValueError(f"values must hold at least one value per seed, got shape "
                         f"{values.shape}")
    return values


def _level(level):
    """A confidence level: None for `BAND_LEVEL`, else a number in (0, 1)."""
    if level is None:
        return BAND_LEVEL
    return _validate.real("level", level, 0.0, 1.0, low_open=True, high_open=True)


def mean_band(values, level=BAND_LEVEL):
    """Mean over the first axis (seeds) and a confidence band for that mean.

    The band is mean +/- t * standard error, with Student's t for n - 1 degrees of
    freedom (n = number of seeds), so it is honest for few seeds too.

    Args:
      values: array [seed, ...] of finite numbers, at least one seed and one value.
      level: confidence level in (0, 1); default (or None) `BAND_LEVEL`.

    Returns:
      (mean, low, high), arrays of shape values.shape[1:], low <= mean <= high. With
      one seed the band is the mean itself.

    Raises:
      ValueError: for values that are not a non-empty array of finite numbers with a
        seed axis, or a level outside (0, 1) (NaN included).
      ArgumentTypeError: for values that are not numbers, or a level that is not one.
    """
    from scipy import stats as _scipy_stats  # here: scipy is slow to import

    values = _per_seed_values(values)
    level = _level(level)
    n = values.shape[0]
    with np.errstate(over="ignore", invalid="ignore"):  # refused below
        mean = values.mean(axis=0)
        if n < 2:
            _validate.finite_results("values", values, mean)
            return mean, mean.copy(), mean.copy()
        half = _scipy_stats.t.ppf(0.5 + level / 2, n - 1) * values.std(axis=0, ddof=1) / \
            np.sqrt(n)
        low, high = mean - half, mean + half
    _validate.finite_results("values", values, mean, low, high)
    return mean, low, high


def first_from_which(condition):
    """For a boolean array [..., time], the first index from which `condition` holds
    until the end, or -1 where it does not hold at the last index.

    Args:
      condition: boolean array [..., time], at least one value.

    Returns:
      An integer array of shape condition.shape[:-1]: indices from 0 (add 1 for a
      trial or an episode counted from 1), -1 where the condition fails at the end.

    Raises:
      ArgumentTypeError: for a condition that is not a boolean array.
      ValueError: for one without a time axis, or empty.
    """
    raw = np.asarray(condition)
    if raw.dtype != bool:
        raise _validate.ArgumentTypeError(f"condition must be a boolean array with a time "
                                          f"axis, got {_validate.show(condition)}")
    if raw.ndim < 1 or raw.size == 0:
        raise ValueError(f"condition must be a boolean array with a time axis and at least "
                         f"one value, got shape {raw.shape}: {_validate.show(condition)}")
    condition = raw
    # Index of the last False, + 1; where everything holds, 0.
    reversed_false = ~condition[..., ::-1]
    has_false = reversed_false.any(axis=-1)
    last_false = condition.shape[-1] - 1 - np.argmax(reversed_false, axis=-1)
    first = np.where(has_false, last_false + 1, 0)
    return np.where(condition[..., -1], first, -1)


def first_below(curve, fraction, after=None):
    """The first index, at or after the curve's peak (or `after`), where `curve` falls
    below `fraction` of its peak; -1 if it never does.

    Args:
      curve: 1-d array of finite numbers, at least one.
      fraction: a number in [0, 1].
      after: None (from the peak), or the index to search from (in 0..len(curve) - 1).

    Returns:
      An int: an index at or after the start of the search, or -1.

    Raises:
      ValueError: for an empty curve or one with NaN or infinity, a fraction outside
        [0, 1], or `after` outside the curve.
      ArgumentTypeError: for values that are not numbers, or an `after` that is not an
        integer.
    """
    curve = _validate.finite_array("curve", curve, ndim=1)
    if len(curve) == 0:
        raise ValueError("curve must hold at least one value, got none")
    fraction = _validate.real("fraction", fraction, 0.0, 1.0)
    peak = int(np.argmax(curve)) if after is None else \
        _validate.integer("after", after, 0, len(curve) - 1)
    below = np.flatnonzero(curve[peak:] < fraction * curve.max())
    return int(peak + below[0]) if below.size else -1


def comes_first(first, second):
    """Where an event numbered `first` (a trial or an episode, from 1; -1 for never)
    comes strictly before one numbered `second`: it happened, and the other never did
    or did later. Works on numbers and on arrays (element-wise).

    Args:
      first, second: event numbers (`icm._validate.event_numbers`: integers from 1, or
        -1 for never), numbers or arrays whose shapes broadcast together.

    Returns:
      A bool (a numpy bool for two numbers) or a boolean array.

    Raises:
      ArgumentTypeError: for values that are not integers (bools included).
      ValueError: for 0 or a negative other than -1, empty arrays, or shapes that do
        not broadcast together.
    """
    first = _validate.event_numbers("first", first)
    second = _validate.event_numbers("second", second)
    _validate.broadcastable("first", first, "second", second)
    return (first >= 1) & ((second == -1) | (first < second))


def paired_gaps(arm, baseline):
    """The per-seed differences `arm` - `baseline` of two runs' event numbers (a trial
    or an episode from 1, -1 for never; the same seeds in the same order), on the seeds
    where both events happened: what a paired comparison of "how soon" tests. Floats;
    negative where the arm's event came sooner. Reordering the seeds (the same order
    for both) reorders the gaps the same way.

    Args:
      arm, baseline: 1-d arrays of event numbers (`icm._validate.event_numbers`), one
        per seed, at least one.

    Returns:
      A 1-d float array, one gap per seed where both events happened (empty if none).

    Raises:
      ArgumentTypeError: for arrays that do not hold integers.
      ValueError: for event numbers that are 0 or negatives other than -1, empty
        arrays, or arrays that are not one-dimensional or differ in length.
    """
    arm = _validate.event_numbers("arm", arm)
    baseline = _validate.event_numbers("baseline", baseline)
    for name, value in (("arm", arm), ("baseline", baseline)):
        if value.ndim != 1:
            raise ValueError(f"{name} must be one-dimensional (one event number per seed), "
                             f"got shape {value.shape}")
    if arm.shape != baseline.shape:
        raise ValueError(f"arm and baseline must hold one event number per seed each, "
                         f"got {len(arm)} and {len(baseline)}")
    both = (arm >= 1) & (baseline >= 1)
    return (arm[both] - baseline[both]).astype(float)


@functools.lru_cache(maxsize=16)
def _resample_counts(n, resamples, seed):
    """How many times each of n seeds is drawn in each of `resamples` resamples (kept:
    every band of a panel uses the same ones). Read-only."""
    counts = np.random.default_rng(seed).multinomial(n, np.full(n, 1.0 / n), size=resamples)
    counts = counts.astype(float)  # exact small integers, ready for a float matrix product
    counts.flags.writeable = False
    return counts


def bootstrap_band(values, level=None, resamples=1000, seed=0):
    """Mean over the first axis (seeds) and a percentile-bootstrap band for it.

    The band is the (1 - level) / 2 and (1 + level) / 2 quantiles of the means of
    `resamples` resamples of the seeds (with replacement, drawn from `seed`, so the
    same values give the same band). Unlike mean +/- t * standard error, it never
    leaves the range the values can take: the band of an error that cannot be
    negative stays at or above zero.

    Args:
      values: array [seed, ...] of finite numbers, at least one seed and one value.
      level: confidence level in (0, 1); default (or None) `BAND_LEVEL`.
      resamples: bootstrap resamples (integer >= 100).
      seed: seed of the resampling (integer in 0..`icm._validate.MAX_SEED`).

    Returns:
      (mean, low, high), arrays of shape values.shape[1:], with
      min(values) <= low <= mean <= high <= max(values) over the seeds.

    Raises:
      ValueError: for values that are not a non-empty array of finite numbers with a
        seed axis, a level outside (0, 1), fewer than 100 resamples or a negative seed.
      ArgumentTypeError: for arguments of the wrong type (text, bools, a float count).
    """
    values = _per_seed_values(values)
    level = _level(level)
    resamples = _validate.integer("resamples", resamples, 100)
    seed = _validate.integer("seed", seed, 0, _validate.MAX_SEED)
    n = values.shape[0]
    # How many times each seed is drawn in each resample; a resample's mean is then a
    # weighted mean, one matrix product for all of them (_exact's: the same band on
    # every processor).
    counts = _resample_counts(n, resamples, seed)
    with np.errstate(over="ignore", invalid="ignore"):  # refused below
        mean = values.mean(axis=0)
        means = (_exact.matmul(counts, values.reshape(n, -1)) / n).reshape(
            (resamples,) + values.shape[1:])
    _validate.finite_results("values", values, mean, means)
    low, high = np.quantile(means, [(1 - level) / 2, (1 + level) / 2], axis=0)
    # Rounding in the weighted means must not put the band outside the values' range.
    low = np.clip(low, values.min(axis=0), mean)
    high = np.clip(high, mean, values.max(axis=0))
    return mean, low, high


def every_nth(n, every):
    """Indices 0, every, 2 * every, ... below n, and n - 1 (the last point is always
    kept): the points a thinned curve keeps.

    Args:
      n: the number of points (integer >= 1).
      every: the step (integer >= 1).

    Returns:
      A sorted integer array of distinct indices in 0..n - 1, from 0 to n - 1.

    Raises:
      ValueError: for n or every below 1.
      ArgumentTypeError: for an n or every that is not an integer.
    """
    n = _validate.integer("n", n, 1)
    every = _validate.integer("every", every, 1)
    return np.unique(np.r_[np.arange(0, n, every), n - 1])


PANEL_RESAMPLES = 500
"""Bootstrap resamples of the panels' bands: enough for a 95% band to be stable to the
eye, few enough for a panel to redraw at once."""


FAMILY_RATE = 0.05
"""The family-wise error rate at which a chapter's paired comparisons are called clear
(`corrected_verdicts`, Holm's step-down correction)."""
SIGN_FLIPS = 20000
"""Random sign flips of `paired_p_value` when the seeds are too many to enumerate every
flip."""
EXACT_FLIPS_UP_TO = 16
"""Up to this many seeds (2**16 flips) `paired_p_value` enumerates every flip."""


def paired_p_value(differences, seed=0, alternative="two-sided"):
    """The two-sided p-value of a paired comparison: are the per-seed differences
    `differences` (one arm minus the other, on the same seeds) centred on zero?

    The test is a sign-flip permutation test of the mean difference: under the null
    hypothesis each difference is as likely positive as negative, so flipping the signs
    of the differences gives the null distribution of their mean. The p-value is the
    share of flips whose mean is at least as far from zero as the observed one (with a
    tolerance of 1e-12, so that ties count as extreme); one-sided ("less", "greater"),
    at least as far in that direction. Up to `EXACT_FLIPS_UP_TO` seeds
    every flip is enumerated; beyond, `SIGN_FLIPS` random flips drawn from `seed` (the
    identity included), so the same differences give the same p-value. No normality is
    assumed, which matters for differences of 0s and 1s (a press formed or not).

    The observed mean is computed by the same sums as the flips' (it is the identity's),
    so that it always counts as at least as extreme as itself, and the tolerance grows
    with the differences' size (1e-12 times the largest, at least 1e-12): a flip whose
    mean equals the observed one exactly (flipping 1e9 / 3, 2e9 / 3 and -1e9 together)
    but whose sum rounds differently (by 1e-7) still ties. Up to `EXACT_FLIPS_UP_TO`
    seeds the p-value does not depend on the order of the seeds; beyond, each seed
    takes the random signs of its place, so another order gives another estimate of
    the same p-value (within a few hundredths). tests/test_stats.py pins both; the
    book's p-values (of whole numbers, and of test errors below a metre) are the same
    as before either was written.

    Args:
      differences: 1-d array of finite numbers, one per seed, at least one.
      seed: seed of the random flips (integer in 0..`icm._validate.MAX_SEED`).
      alternative: "two-sided", "less" (the differences' mean below zero) or "greater".

    Returns:
      The p-value, a float in (0, 1]; 1 (two-sided) when every difference is zero.

    Raises:
      ValueError: for differences that are empty, not 1-d, not finite or so large that
        their sums overflow; a negative seed; another alternative.
      ArgumentTypeError: for arguments of the wrong type.
    """
    differences = _validate.finite_array("differences", differences, ndim=1)
    if len(differences) == 0:
        raise ValueError("differences must hold one value per seed, got none")
    seed = _validate.integer("seed", seed, 0, _validate.MAX_SEED)
    alternative = _validate.one_of("alternative", alternative,
                                   ("two-sided", "less", "greater"))
    n = len(differences)
    if n <= EXACT_FLIPS_UP_TO:
        signs = 1 - 2 * ((np.arange(2 ** n)[:, None] >> np.arange(n)) & 1)
    else:
        signs = np.random.default_rng(seed).choice([-1, 1], size=(SIGN_FLIPS, n))
        signs[0] = 1  # the observed arrangement is one of the flips
    with np.errstate(over="ignore", invalid="ignore"):  # refused below
        means = _exact.matvec(signs, differences) / n
    _validate.finite_results("differences", differences, means)
    observed = means[0]  # the identity's (signs[0] is every +1)
    tolerance = 1e-12 * max(1.0, float(np.abs(differences).max()))
    if alternative == "two-sided":
        means, observed = np.abs(means), abs(observed)
    elif alternative == "less":
        means, observed = -means, -observed
    return float(np.mean(means >= observed - tolerance))


def corrected_verdicts(family, rate=FAMILY_RATE, seed=0):
    """Which comparisons of a family are clear, corrected for their number: Holm's
    step-down correction at family-wise error rate `rate` (statsmodels'
    `multipletests`, method "holm"), on the p-values of `paired_p_value`.

    Holm's adjusted p-values are never below the raw ones, never above 1, and rise
    with them (a smaller raw p-value never has a larger adjusted one); what is clear
    does not depend on the family's order.

    Args:
      family: {name: per-seed differences (a 1-d array, at least one) or a p-value (a
        number in [0, 1])}: every comparison a chapter makes and calls clear or not.
      rate: the family-wise error rate, in (0, 1); default `FAMILY_RATE`.
      seed: the seed of `paired_p_value`'s random flips (integer >= 0).

    Returns:
      {name: {"p": raw p-value, "p_holm": Holm-adjusted p-value, "clear": bool
      (adjusted p-value at or below `rate`), "mean": mean difference (None for a family
      member given as a p-value), "n_family": the family's size}}, in the family's
      order.

    Raises:
      ArgumentTypeError: for a family that is not a non-empty dict, or arguments of
        the wrong type.
      ValueError: for a member that is an empty, non-finite or not 1-d array, or a
        p-value outside [0, 1] (NaN included); a rate outside (0, 1); a negative seed.
    """
    from statsmodels.stats.multitest import multipletests  # here: slow to import

    if not isinstance(family, dict) or not family:
        raise _validate.ArgumentTypeError(f"family must be a non-empty dict {{name: per-seed "
                                          f"differences or p-value}}, got "
                                          f"{_validate.show(family)}")
    rate = _validate.real("rate", rate, 0.0, 1.0, low_open=True, high_open=True)
    seed = _validate.integer("seed", seed, 0, _validate.MAX_SEED)
    p_values, means = [], []
    for name, member in family.items():
        if np.ndim(member) == 0:
            p_values.append(_validate.real(f"family[{name!r}]", member, 0.0, 1.0))
            means.append(None)
        else:
            differences = _validate.finite_array(f"family[{name!r}]", member, ndim=1)
            if len(differences) == 0:
                raise ValueError(f"family[{name!r}] must hold one difference per seed "
                                 f"(or be a p-value), got none")
            with np.errstate(over="ignore"):  # refused here, under the member's name
                _validate.finite_results(f"family[{name!r}]", differences,
                                         np.abs(differences).sum())
            p_values.append(paired_p_value(differences, seed))
            means.append(float(differences.mean()))
    clear, adjusted, _, _ = multipletests(p_values, alpha=rate, method="holm")
    return {name: {"p": p, "p_holm": float(q), "clear": bool(c), "mean": m,
                   "n_family": len(family)}
            for name, p, q, c, m in zip(family, p_values, adjusted, clear, means)}


def at_bound(values, low=0.0, high=1.0):
    """"ceiling" when every one of `values` (an arm's per-seed outcomes) is at `high`,
    "floor" when every one is at `low`, else None: a comparison whose baseline is at a
    bound can only move one way, and a verdict on it must say so.

    Args:
      values: array of finite numbers within [low, high], at least one.
      low, high: the lowest and highest value an outcome can take (finite, low < high).

    Returns:
      "ceiling", "floor" or None.

    Raises:
      ValueError: for values that are empty, not finite or outside [low, high], bounds
        that are NaN or infinite, or low >= high.
      ArgumentTypeError: for values or bounds that are not numbers.
    """
    values = _validate.finite_array("values", values)
    if values.size == 0:
        raise ValueError("values must hold at least one value, got none")
    low = _validate.real("low", low)
    high = _validate.real("high", high)
    if low >= high:
        raise ValueError(f"low must be below high, got low {low!r} and high {high!r}")
    if np.any((values < low) | (values > high)):
        raise ValueError(f"values must lie within [low, high] = [{low:g}, {high:g}], got "
                         f"{_validate.show(values)}")
    if np.all(values == high):
        return "ceiling"
    if np.all(values == low):
        return "floor"
    return None


LEVEL = 0.95
"""Confidence level of the interval around every measured share."""


VERDICTS = ("holds", "unclear", "fails")
"""What a measured share says about a claim that needs a threshold share (`verdict`)."""


def share_interval(successes, n, level=LEVEL):
    """The Wilson score interval of a share of `successes` out of `n`.

    Unlike mean +/- z standard errors it stays within [0, 1] and does not shrink to a
    point when every seed (or none) succeeds: 200 successes out of 200 give
    [0.981, 1]. It always holds the share itself: low <= successes / n <= high.

    Args:
      successes: integer (or integer array) in 0..n.
      n: number of trials (integer >= 1, or an array whose shape broadcasts with
        `successes`').
      level: confidence level in (0, 1).

    Returns:
      (low, high), floats (or arrays).

    Raises:
      ValueError: for counts with successes < 0, successes > n or n < 1, empty arrays,
        shapes that do not broadcast together, or a level outside (0, 1).
      ArgumentTypeError: for counts that are not integers (bools and whole floats
        included), or a level that is not a number.
    """
    level = _validate.real("level", level, 0.0, 1.0, low_open=True, high_open=True)
    k = _validate.integer_values("successes", successes, "an integer (or integers) in 0..n")
    n_ = _validate.integer_values("n", n, "an integer (or integers) >= 1")
    for name, value, shown in (("successes", k, successes), ("n", n_, n)):
        if value.size == 0:
            raise ValueError(f"{name} must hold at least one count, got none: "
                             f"{_validate.show(shown)}")
    _validate.broadcastable("successes", k, "n", n_)
    if np.any(n_ < 1):
        raise ValueError(f"n must be an integer (or integers) >= 1, got {_validate.show(n)}")
    if np.any(k < 0) or np.any(k > n_):
        raise ValueError(f"successes must be in 0..n and n >= 1, got successes "
                         f"{_validate.show(successes)} and n {_validate.show(n)}")
    z = statistics.NormalDist().inv_cdf(0.5 + level / 2)  # not scipy: 2 s to import
    p = k / n_
    denominator = 1 + z**2 / n_
    centre = (p + z**2 / (2 * n_)) / denominator
    half = z * np.sqrt(p * (1 - p) / n_ + z**2 / (4 * n_**2)) / denominator
    # Exactly 0 (1) when no (every) seed succeeds, whatever the rounding.
    low = np.where(k == 0, 0.0, np.clip(centre - half, 0.0, 1.0))
    high = np.where(k == n_, 1.0, np.clip(centre + half, 0.0, 1.0))
    if low.ndim == 0:
        return float(low), float(high)
    return low, high


def verdict(low, high, threshold):
    """"holds" if the interval [low, high] is at or above `threshold`, "fails" if it
    is below it, "unclear" if it straddles it.

    Args:
      low, high: the interval of a share (numbers in [0, 1], low <= high).
      threshold: the share a claim needs, in [0, 1].

    Raises:
      ValueError: for a bound or threshold outside [0, 1] (NaN included), or low > high.
    """
    low = _validate.in_closed_interval("low", low, 0.0, 1.0)
    high = _validate.in_closed_interval("high", high, 0.0, 1.0)
    threshold = _validate.in_closed_interval("threshold", threshold, 0.0, 1.0)
    if low > high:
        raise ValueError(f"low must be at most high, got low {low!r} and high {high!r}")
    if low >= threshold:
        return "holds"
    if high < threshold:
        return "fails"
    return "unclear"


POWER_SIMULATIONS = 2000
"""Simulated replications of `paired_power`: its Monte Carlo standard error is at most
0.011 (at a power of one half)."""


def paired_power(differences, n_seeds, alternative, rate=FAMILY_RATE,
                 simulations=POWER_SIMULATIONS, seed=0):
    """The power of a replication on `n_seeds` fresh seeds, under the effect measured:
    the share of simulated replications in which the test actually used
    (`paired_p_value`, one-sided in `alternative`, its own flips seeded 0 as in
    `icm.chapters.replication.replicated`) gives a p-value below `rate`.

    Each simulated replication draws `n_seeds` per-seed differences with replacement
    from the measured ones (`differences`), so it keeps their spread, their ties and
    their steps (differences of 0s and 1s, or of counts): a normal approximation
    (Student's t on the standardised effect) does not, and overstates the power of an
    exact test on few seeds (4 equal positive differences: the approximation says
    near 1, the test can never go below 1/16). The measured effect is the one the study
    found significant, so the power it gives tends to be optimistic.

    Args:
      differences: 1-d array of finite numbers, the per-seed differences measured (at
        least one).
      n_seeds: seeds of the replication (integer >= 1).
      alternative: "less" or "greater", the direction the study found.
      rate: the level of the one-sided test, in (0, 1); default `FAMILY_RATE`.
      simulations: simulated replications (integer >= 100).
      seed: seed of the draws (integer in 0..`icm._validate.MAX_SEED`).

    Returns:
      The power, a float in [0, 1] (a multiple of 1 / simulations).

    Raises:
      ValueError: for differences that are empty, not 1-d or not finite; n_seeds < 1;
        another alternative; a rate outside (0, 1); fewer than 100 simulations; a
        negative seed.
      ArgumentTypeError: for arguments of the wrong type.
    """
    differences = _validate.finite_array("differences", differences, ndim=1)
    if len(differences) == 0:
        raise ValueError("differences must hold one value per seed, got none")
    n_seeds = _validate.integer("n_seeds", n_seeds, 1)
    alternative = _validate.one_of("alternative", alternative, ("less", "greater"))
    rate = _validate.real("rate", rate, 0.0, 1.0, low_open=True, high_open=True)
    simulations = _validate.integer("simulations", simulations, 100)
    seed = _validate.integer("seed", seed, 0, _validate.MAX_SEED)
    draws = np.random.default_rng(seed).choice(differences, size=(simulations, n_seeds))
    rejected = [paired_p_value(draw, 0, alternative) < rate for draw in draws]
    return float(np.mean(rejected))


def seeds_for_power(differences, alternative, power=0.9, rate=FAMILY_RATE,
                    simulations=POWER_SIMULATIONS, seed=0, most=400):
    """The fewest seeds at which `paired_power` reaches `power`, searched by doubling
    then halving (the power grows with the seeds, up to the Monte Carlo noise), or None
    if `most` seeds do not reach it. The seeds returned reach the power, and (where the
    power grows with the seeds) one seed fewer does not.

    Args:
      differences, alternative, rate, simulations, seed: as in `paired_power`.
      power: the power wanted, in (0, 1).
      most: the largest number of seeds tried (integer >= 1).

    Returns:
      An int in 1..most, or None.

    Raises:
      ValueError: as `paired_power`, and for a power outside (0, 1) or most < 1.
      ArgumentTypeError: as `paired_power`, and for a power or most of the wrong type.
    """
    power = _validate.real("power", power, 0.0, 1.0, low_open=True, high_open=True)
    most = _validate.integer("most", most, 1)
    reaches = functools.lru_cache(maxsize=None)(
        lambda n: paired_power(differences, n, alternative, rate, simulations, seed) >= power)
    high = 1
    while not reaches(high):
        if high >= most:
            return None
        high = min(2 * high, most)
    low = high // 2  # does not reach (or 0)
    while high - low > 1:
        middle = (low + high) // 2
        low, high = (low, middle) if reaches(middle) else (middle, high)
    return high
