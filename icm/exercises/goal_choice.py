"""Check of the goal-babbling exercise: a rule that chooses the region of the next goal
by learning progress.

The check depends only on the rule's public behaviour, as `run_goal_babbling`
documents it: with probability epsilon a region drawn uniformly, otherwise a region
drawn with probability proportional to its interest, uniformly while every interest is
0. A rule is a function `choose_region(interests, epsilon, rng)` returning a region's
index; it is random, so the check draws it many times and compares the shares of the
regions with the rule's probabilities."""

import math
import warnings

import numpy as np

from icm import _validate
from icm.exercises import _core
from icm.exercises._core import Case
from icm.exercises._own import Borrowed, Forbidden, call_own_many

PARAMETERS = ("interests", "epsilon", "rng")
DRAWS = 3000
"""Draws of the student's rule per case."""
SIGMAS = 5.0
"""A share may differ from its probability by this many standard errors of a share of
`DRAWS` draws (a correct rule fails a case with probability below 1e-5)."""
SEQUENCE = 40
"""Choices compared in the generator's case: the same seed twice, then another."""
GENERATOR = "the generator it is given: the same rng, the same choices"
"""The name of the check's last case."""
FORBIDDEN = Forbidden(("icm.learners.goal_choice", "icm.learners.action_selection",
                       "icm.learners.goal_babbling"))
"""What a goal-choice rule must not call: the library's."""


def region_probabilities(interests, epsilon):
    """The probability of each region under the rule.

    Args:
      interests: the regions' interests (>= 0).
      epsilon: the share of uniform choices.

    Returns:
      An array: epsilon / n + (1 - epsilon) * interest / total, or 1 / n for every
      region while the total interest is 0.
    """
    interests = np.asarray(interests, dtype=float)
    n = len(interests)
    total = interests.sum()
    if not total > 0:
        return np.full(n, 1.0 / n)
    return epsilon / n + (1 - epsilon) * interests / total


def public_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    rng = np.random.default_rng(9)
    return [
        Case("every interest 0: uniform", ([0.0, 0.0, 0.0, 0.0], 0.3),
             "While every interest is 0 there is nothing to be proportional to: draw "
             "uniformly (do not divide by a total of 0)."),
        Case("epsilon 0, one interesting region: always that one",
             ([0.0, 0.2, 0.0, 0.0], 0.0),
             "With epsilon 0 every goal follows interest: a region of interest 0 is never "
             "chosen."),
        Case("epsilon 1: uniform whatever the interest", ([0.0, 1.0, 0.0, 0.0], 1.0),
             "With probability epsilon choose a region uniformly, ignoring interest."),
        Case("ties: two regions of the same interest", ([0.1, 0.1, 0.0, 0.0], 0.0),
             "Equal interests must be chosen equally often: draw with probability "
             "proportional to interest, do not take the first maximum."),
        Case("proportional to interest", ([0.1, 0.3, 0.6], 0.0),
             "Choose each region with probability interest / total interest, not always "
             "the most interesting one."),
        Case("epsilon 0.3 (the book's)", ([0.1, 0.3, 0.6, 0.0], 0.3),
             "Probability epsilon / n + (1 - epsilon) * interest / total for each region."),
        Case("one region", ([0.5], 0.3), "With one region, always region 0."),
        Case("14 regions, as the book's goal space",
             (rng.random(14).round(3).tolist(), 0.3),
             "Probability epsilon / n + (1 - epsilon) * interest / total for each region."),
    ]


def _sequence(rule, interests, epsilon, seed, draws):
    """The rule's choices in `draws` draws from one generator seeded with `seed`:
    (the list of choices, None), (None, a value that is not a region) or (None, a
    `Borrowed`)."""
    rng = np.random.default_rng(seed)
    regions, borrowed = call_own_many(rule, (list(interests), epsilon, rng), draws,
                                      FORBIDDEN)
    if borrowed is not None:
        return None, borrowed
    for region in regions:
        if not _validate.is_integer(region) or not 0 <= int(region) < len(interests):
            return None, region
    return [int(region) for region in regions], None


def _draw(rule, interests, epsilon, seed):
    """The rule's choices in `DRAWS` draws: (shares of the regions, None), or (None,
    a bad value or a `Borrowed`)."""
    choices, bad = _sequence(rule, interests, epsilon, seed, DRAWS)
    if choices is None:
        return None, bad
    return np.bincount(choices, minlength=len(interests)) / DRAWS, None


def _agrees(probabilities, shares):
    for p, share in zip(probabilities, shares):
        if p == 0.0 and share > 0.0:
            return False
        if abs(share - p) > SIGMAS * math.sqrt(p * (1 - p) / DRAWS) + 1e-12:
            return False
    return True


def check_goal_choice(choose_region, interests=None, epsilon=0.3, cases=None):
    """Checks a student's goal-choice rule, `choose_region(interests, epsilon, rng)`: the
    index of the region of the next goal, chosen uniformly with probability `epsilon`,
    else with probability proportional to `interests` (uniformly while they are all
    0), drawing its random numbers from `rng` (a `numpy.random.Generator`).

    Each case draws the rule `DRAWS` times and compares the shares with the
    probabilities. If every case passes and `interests` is given (e.g. the regions'
    interest at the end of the chapter's run), it draws the shares of the student's
    rule for those interests beside the rule's probabilities.

    Args:
      choose_region: the student's function.
      interests: interests of the regions to draw the figure for, or None.
      epsilon: the share of uniform choices for that figure, in [0, 1].
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of (interests, epsilon,
        rng); ValueError for bad interests or epsilon.
    """
    choose_region = _core.check_function("choose_region", choose_region, PARAMETERS)
    if interests is not None:
        interests = _validate.finite_array("interests", interests, ndim=1)
        if len(interests) < 1 or np.any(interests < 0):
            raise ValueError(f"interests must hold one number >= 0 per region, got "
                             f"{_validate.show(interests)}")
    epsilon = _validate.in_closed_interval("epsilon", epsilon, 0.0, 1.0)
    cases = public_cases() if cases is None else cases
    result = rule_verdict(choose_region, cases, 1000)
    if not result.passed or interests is None:
        return result
    shares, _ = _draw(choose_region, interests.tolist(), epsilon, 7)
    result.figure = _shares_figure(shares, region_probabilities(interests, epsilon))
    result.notes.append(
        f"For the interests given ({len(interests)} regions, epsilon {epsilon}), your "
        f"rule's shares over {DRAWS} draws differ from the probabilities by at most "
        f"{np.abs(shares - region_probabilities(interests, epsilon)).max():.3f}.")
    return result


def rule_verdict(choose_region, cases, seed):
    """Draws the rule `DRAWS` times on each case and compares the shares with the
    probabilities, then checks that it draws from the generator it is given.

    Args:
      choose_region: the student's rule.
      cases: a list of `Case` (interests, epsilon).
      seed: the first case's generator's seed (the next cases', seed + 1, ...).

    Returns:
      A `CheckResult`.
    """
    names = [case.name for case in cases] + [GENERATOR]
    for i, case in enumerate(cases):
        values, eps = case.args
        expected = region_probabilities(values, eps).round(3).tolist()
        shown = f"interests={_core.show(values, 120)}, epsilon={eps}, rng=<a Generator>"
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")  # the report says what went wrong
                shares, bad = _draw(choose_region, values, eps, seed + i)
        except NotImplementedError:
            return _core.CheckResult("choose_region", _core.NOT_IMPLEMENTED, names)
        except Exception as error:
            return _core.CheckResult("choose_region", _core.FAILED, names, case, shown,
                                     expected, error, f"Your rule raised "
                                     f"{type(error).__name__} on this case. {case.hint}")
        if isinstance(bad, Borrowed):
            return _core.CheckResult("choose_region", _core.FAILED, names, case, shown,
                                     "your own code", f"a call to {bad.name}",
                                     bad.hint("choose_region"), borrowed=bad)
        if shares is None:
            return _core.CheckResult(
                "choose_region", _core.FAILED, names, case, shown, expected, bad,
                f"Your rule must return the index of a region, an integer from 0 to "
                f"{len(values) - 1}. {case.hint}")
        if not _agrees(region_probabilities(values, eps), shares):
            return _core.CheckResult(
                "choose_region", _core.FAILED, names, case, shown,
                f"probabilities {expected}", f"shares of {DRAWS} draws "
                f"{shares.round(3).tolist()}", case.hint)
    return _generator_verdict(choose_region, cases, names, seed + len(cases))


def _generator_verdict(choose_region, cases, names, seed):
    """The last case: the same generator state gives the same choices, another one
    other choices (on the case whose choices are the most random)."""
    values, eps = max((case.args for case in cases),
                      key=lambda args: _entropy(region_probabilities(*args)))
    case = Case(GENERATOR, (values, eps), "")
    shown = (f"interests={_core.show(values, 120)}, epsilon={eps}, rng: "
             f"default_rng({seed}) twice, then default_rng({seed + 1})")
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        first, _ = _sequence(choose_region, values, eps, seed, SEQUENCE)
        again, _ = _sequence(choose_region, values, eps, seed, SEQUENCE)
        other, _ = _sequence(choose_region, values, eps, seed + 1, SEQUENCE)
    if first != again:
        return _core.CheckResult(
            "choose_region", _core.FAILED, names, case, shown,
            f"the same {SEQUENCE} choices from two generators in the same state",
            f"{_core.show(first, 100)} and {_core.show(again, 100)}",
            "Draw every random number from `rng`, the generator your rule is given: not "
            "from numpy's global generator (np.random.random, np.random.choice, ...) nor "
            "from the module `random`. The learner seeds `rng`, and its runs must repeat.")
    if first == other:
        return _core.CheckResult(
            "choose_region", _core.FAILED, names, case, shown,
            f"other choices from a generator in another state",
            f"the same {SEQUENCE} choices: {_core.show(first, 100)}",
            "Your rule gives the same choices whatever generator it is given: draw its "
            "random numbers from `rng` (rng.random(), rng.integers(n), rng.choice(n, "
            "p=...)).")
    return _core.CheckResult("choose_region", _core.PASSED, names)


def _entropy(probabilities):
    p = probabilities[probabilities > 0]
    return float(-(p * np.log(p)).sum())


def hidden_cases(rng):
    """Cases of the shapes of the public ones, with interests and epsilons drawn
    from `rng`.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    n = int(rng.integers(3, 9))
    eps = round(float(rng.uniform(0.1, 0.5)), 2)
    one = [0.0] * n
    one[int(rng.integers(n))] = round(float(rng.uniform(0.05, 1)), 3)
    tie = [0.0] * n
    value = round(float(rng.uniform(0.05, 1)), 3)
    for i in rng.choice(n, 2, replace=False):
        tie[int(i)] = value
    hint = "Probability epsilon / n + (1 - epsilon) * interest / total for each region."
    return [
        Case("every interest 0: uniform (hidden)", ([0.0] * n, eps),
             "While every interest is 0, draw uniformly."),
        Case("epsilon 0, one interesting region (hidden)", (one, 0.0),
             "With epsilon 0 a region of interest 0 is never chosen."),
        Case("epsilon 1: uniform (hidden)", (one, 1.0),
             "With probability epsilon choose a region uniformly."),
        Case("ties (hidden)", (tie, 0.0), "Equal interests must be chosen equally often."),
        Case("proportional to interest (hidden)", (rng.random(n).round(3).tolist(), 0.0),
             "Choose each region with probability interest / total interest."),
        Case("epsilon and interest (hidden)", (rng.random(n).round(3).tolist(), eps), hint),
    ]


def _shares_figure(shares, probabilities):
    """Bars of a rule's shares beside the probabilities, region by region."""
    from icm.figures import new_figure

    fig, ax = new_figure(width=6.4, height=3.0)
    x = np.arange(len(shares))
    ax.bar(x - 0.2, probabilities, width=0.4, color="0.6", label="the rule's probability")
    ax.bar(x + 0.2, shares, width=0.4, color="tab:blue", label=f"your rule, {DRAWS} draws")
    ax.set_xticks(x)
    ax.set_xlabel("region")
    ax.set_ylabel("share of goals")
    ax.legend(frameon=False)
    fig.icm_alt = "Bars: your rule's share of goals in each region beside the rule's probability"
    return fig
