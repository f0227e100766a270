"""What each intrinsic reward pays, try after try, for an outcome that is a fair coin
(the wobbly rod) and for one that is sure (`outcome_rewards`): the third study of the
chapter "Which curiosity?", beside `icm.experiments.curiosity`'s two comparisons.
"""

import numpy as np

from icm import _streams, _validate
from icm.experiments._memory import FIXED_BYTES, check_memory
from icm.experiments.progress import progress_bar
from icm.experiments.curiosity import check_choices
from icm.learners import interest, predictors, q_learning


OUTCOME_SECONDS_PER_TRY = 1e-5
"""About what one seed's try of one outcome costs `outcome_rewards` (measured: 10
microseconds on the book's 2-core machine)."""


MAX_OUTCOME_DRAWS = 10_000_000
"""The most seeds times tries `outcome_rewards` takes: a few minutes of computing;
the chapter's call makes 6,000."""


def outcome_rewards(rewards=("prediction_error", "learning_progress", "novelty"),
                    n_tries=60, n_seeds=100, window=interest.DEFAULT_WINDOW,
                    predictor_lr=predictors.DEFAULT_LINEAR_LR, seed=0, progress=True):
    """What each intrinsic reward pays, try after try, for one (state, action) pair
    whose outcome is a fair coin (1 or 0, probability 1/2 each: the wobbly rod) and for
    one whose outcome is always 1 (a rod that always topples), as the rods' Q-learner
    computes it (`icm.learners.q_learning.QLearner.learn` on a one-pair table with a
    `LinearPredictor`: the pair's errors come from a `LinearPredictor` per seed, and
    each reward is its signal of those errors, all seeds at once in
    `icm.learners.interest.InterestTable`, which gives the same numbers).

    It takes about 10 microseconds per seed and try of each outcome (a progress bar,
    with the time left, shows when it lasts over a second), and its memory grows as the
    seeds times the tries (`outcome_rewards_memory`): a call that this machine could not
    hold is refused before it starts, and so is one of more than `MAX_OUTCOME_DRAWS`
    seeds times tries (its message says how long it would take).

    Args:
      rewards: the rewards, names of `REWARDS`.
      n_tries: tries of the pair (>= 1).
      n_seeds: seeds of the coin (>= 1).
      window: errors in the learning-progress slope (>= 2).
      predictor_lr: the predictor's learning rate, in (0, 1].
      seed: the root seed of the coins.
      progress: show a progress bar over the seeds when the call lasts over a second.

    Returns:
      {(reward, "coin" | "sure"): rewards [seed, try]}.

    Raises:
      ValueError: for a bad argument, or a call too large for this machine's memory or
        `MAX_OUTCOME_DRAWS`.
    """
    rewards = check_choices("rewards", rewards, q_learning.REWARDS)
    n_tries = _validate.integer_at_least("n_tries", n_tries, 1)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    window = _validate.integer_at_least("window", window, 2)
    predictor_lr = _validate.learning_rate("predictor_lr", predictor_lr)
    seed = _validate.root_seed("seed", seed)
    _validate.boolean("progress", progress)
    check_memory("outcome_rewards", {"rewards": len(rewards), "n_seeds": n_seeds,
                                     "n_tries": n_tries},
                 outcome_rewards_memory(len(rewards), n_seeds, n_tries, window))
    if n_seeds * n_tries > MAX_OUTCOME_DRAWS:
        hours = 2 * n_seeds * n_tries * OUTCOME_SECONDS_PER_TRY / 3600
        raise ValueError(f"n_seeds x n_tries must be at most {MAX_OUTCOME_DRAWS:,} (about "
                         f"{2 * MAX_OUTCOME_DRAWS * OUTCOME_SECONDS_PER_TRY / 60:.0f} minutes "
                         f"of computing), got n_seeds={n_seeds} x n_tries={n_tries} = "
                         f"{n_seeds * n_tries:,} (about {hours:.1f} hours)")
    coins = np.random.default_rng(seed).random((n_seeds, n_tries)) < 0.5
    sure = np.ones_like(coins)
    rows, pair = np.arange(n_seeds), np.zeros(n_seeds, dtype=np.int64)
    out = {}
    bar = progress_bar(None, 2 * n_seeds, "rewards of a coin and a sure outcome", progress)
    for kind, outcomes in (("coin", coins), ("sure", sure)):
        errors = np.zeros((n_seeds, n_tries))  # the pair's surprise at each try
        for k in range(n_seeds):
            if bar is not None:
                bar.update(1)
            predictor = predictors.LinearPredictor(1, 1, predictor_lr)
            for t, outcome in enumerate(outcomes[k].tolist()):
                errors[k, t] = predictor.update(0, 0, [float(outcome)])
        for reward in rewards:
            signal = interest.InterestTable(
                n_seeds, 1, reward,
                1 if interest.SIGNAL_CLASSES[reward].ONE_ERROR_REWARD else window, 0.0)
            paid = np.zeros((n_seeds, n_tries))
            for t in range(n_tries):
                signal.record(None, pair, errors[:, t])
                # (+ 0.0: the batched progress can be -0.0 where QLearner's max(0, .)
                # gives 0.0; it changes no other number.)
                paid[:, t] = signal.values(rows)[:, 0] + 0.0
            out[(reward, kind)] = paid
    if bar is not None:
        bar.close()
    return {(reward, kind): out[(reward, kind)] for reward in rewards
            for kind in ("coin", "sure")}


def outcome_rewards_memory(n_rewards, n_seeds, n_tries, window=interest.DEFAULT_WINDOW):
    """An upper bound on the memory `outcome_rewards` adds to the process, in bytes,
    counted from its arrays' shapes (see `icm.experiments._memory`)."""
    # Per seed and try: the coins' uniform numbers (8 bytes, until the coins are drawn),
    # the coins and the sure outcomes (a byte each), and every reward paid.
    per_try = 8 + 2 + 8 * 2 * n_rewards
    # Per seed: two learners (the next is made before the last is freed), each with its
    # generator, its numbers and its pair's errors, count and progress; a try's
    # temporaries.
    learner = _streams.memory_bound(1, 0) + 8 * (window + 2 + 4)
    per_seed = 2 * learner + OUTCOME_ROW_BYTES
    slopes = 2 * 8 * (window + 1) ** 2 * window  # the two learners' slope tables
    return FIXED_BYTES + n_seeds * n_tries * per_try + n_seeds * per_seed + slopes


OUTCOME_ROW_BYTES = 500
"""An upper bound on the temporaries of a try, per seed."""
