"""Action selection, shared by the learners: epsilon-greedy (the goal-oriented actor,
section 3.1, and the Q-learner, section 3.3) and softmax (the actor-critic's actor,
Figure 4), each for one agent and for many agents (rows) at once.

Every choice draws `DRAWS_PER_CHOICE` uniform numbers, whether it uses them or not, so
that one agent's stream stays in step with the same agent in a batch.
"""

import functools
import math

import numpy as np

from icm import _exact, _validate

DRAWS_PER_CHOICE = 3
"""Uniform numbers an agent draws for each choice, whether it uses them or not: one for
epsilon, one for the random action, one to break ties. A fixed count keeps one
agent's stream in step with the same agent in a batch."""


def epsilon_greedy(values, epsilon, draws):
    """The epsilon-greedy choice of one agent: with probability epsilon an action drawn
    uniformly (`draws[1]`), otherwise one of the best (`draws[2]` breaks ties).

    Args:
      values: one number per action.
      epsilon: probability of a random action.
      draws: three uniform numbers in [0, 1).
    """
    if draws[0] < epsilon:
        return int(draws[1] * len(values))
    best = max(values)
    candidates = [a for a, v in enumerate(values) if v == best]
    return candidates[int(draws[2] * len(candidates))]


@functools.lru_cache(maxsize=None)
def _best_sets(n_actions):
    """For every set of best actions, as a bit mask: how many they are, and which is
    the i-th of them (tables indexed [mask] and [mask, i])."""
    masks = np.arange(1 << n_actions)
    members = (masks[:, None] >> np.arange(n_actions)) & 1
    nth = np.zeros((1 << n_actions, n_actions), dtype=np.int64)
    for mask in range(1 << n_actions):
        chosen = np.flatnonzero(members[mask])
        nth[mask, :len(chosen)] = chosen
    return (1 << np.arange(n_actions)).astype(float), members.sum(axis=1), nth


def epsilon_greedy_rows(values, epsilon, draws):
    """`epsilon_greedy` for many agents: values [rows, actions], epsilon [rows], draws
    [rows, 3]; returns the actions [rows]. The best actions of a row are a set (a bit
    mask); tables give how many they are and which is the one picked."""
    n_actions = values.shape[1]
    top = values[:, 0]
    for a in range(1, n_actions):  # column by column: quicker than a row-wise max
        top = np.maximum(top, values[:, a])
    powers, count, nth = _best_sets(n_actions)
    best = ((values == top[:, None]) @ powers).astype(np.int64)  # the set, as a bit mask
    pick = (draws[:, 2] * count.take(best)).astype(np.int64)  # which of the best
    greedy = nth.take(best * n_actions + pick)
    explore = draws[:, 0] < epsilon
    return greedy + explore * ((draws[:, 1] * n_actions).astype(np.int64) - greedy)


def softmax(preferences, temperature):
    """Softmax probabilities exp(p / T) / sum(exp(p / T)), computed without overflow.

    The largest preference is subtracted before exponentiating, so every exponent is
    <= 0 and the largest is exactly 0: preferences of 1e6 (or 1e300) give
    probabilities, not inf / inf.

    Args:
      preferences: a non-empty sequence of finite numbers.
      temperature: T, a finite number > 0; the smaller, the greedier.

    Returns:
      A float numpy array of probabilities, same length as `preferences`, summing to 1.

    Raises:
      ValueError: for an empty or non-finite `preferences` or a bad temperature.
    """
    temperature = _validate.positive("temperature", temperature)
    p = [float(x) for x in np.asarray(preferences, dtype=float).ravel()]
    if not p or not all(map(math.isfinite, p)) or np.ndim(preferences) != 1:
        raise ValueError(f"preferences must be a non-empty sequence of finite numbers, "
                         f"got {preferences!r}")
    return np.array(softmax_unchecked(p, temperature))


def softmax_unchecked(preferences, temperature):
    """`softmax` on a list of floats, unchecked (the learner's inner loop). numpy's
    exp, and a sum in order, exactly as `ActorCriticBatch` computes it.

    Args:
      preferences: a non-empty list of floats (not checked).
      temperature: a float > 0 (not checked).

    Returns:
      A float numpy array of probabilities summing to 1.

    Raises:
      FloatingPointError: for an infinite or NaN preference (a diverged actor).
    """
    p = np.asarray(preferences, dtype=float)
    # (p - top) <= 0, so exp never overflows; a difference that overflows to -inf
    # (preferences 1e308 apart) gives exp 0.0, as it should.
    with np.errstate(over="ignore"):
        weights = _exact.exp((p - p.max()) / temperature)  # the same on every processor
    total = 0.0
    for w in weights.tolist():  # >= 1: the top preference contributes exp(0) = 1
        total += w
    if not math.isfinite(total):  # an infinite or NaN preference: a diverged actor
        raise FloatingPointError(f"preferences must be finite, got {preferences!r}")
    return weights / total
