"""The curious Q-learner on the tabular rods, many runs at once, compiled with Numba:
the Q-learner's fast form (its teaching form is `icm.learners.q_learning.QLearner`).

Why compiled: the runs' episodes have different lengths, so a batch moves one step at
a time until its longest run is over (about 5,700 steps for 200 seeds of 300
episodes), and in numpy every step costs some 60 small array operations, a few
microseconds each: 1.2 to 1.7 s for 200 seeds, against a target of 1 s. Here each run
is played through in a loop compiled once (Numba caches it on disk), following the
per-agent `QLearner` and `LinearPredictor` operation for operation, so it gives the
same numbers (a test compares them seed by seed). The physics runs, whose cost is the
physics itself, use the per-agent classes.

The loop copies no rule's numbers: the numbers each choice draws
(`icm.learners.action_selection.DRAWS_PER_CHOICE`), the wobbly rod's probability
(`icm.envs.rods.WOBBLE_TOPPLE_PROBABILITY`) and the slope weights
(`icm.learners.interest.slope_weights`) are read from their modules at every run and
passed in (a test changes each in its home and sees the loop's results change). The
reward is one of the interest signals the loop computes (`signal_codes`), kept per
(cell, action) pair as the per-agent classes keep it; `check_reward` refuses, by
name, a signal it does not compute.
"""

import numba
import numpy as np

from icm._validate import one_of
from icm.envs.rods import rules as rod_rules
from icm.learners import action_selection, interest

FORMULAS = ("error", "slope", "novelty", "none")
"""The rewards the compiled loop computes, one branch of `play` each, numbered by their
place here (`ERROR`, `SLOPE`, `NOVELTY`, `NONE`): "error", the move's prediction error
(the paper's reward); "slope", max(0, -slope) of the pair's last `window` errors
(learning progress); "novelty", 1 / sqrt(1 + tries of the pair); "none", no reward and
no values learned (the walk at random). A signal names the one that computes it
(`icm.learners.interest.InterestSignal.KERNEL_FORMULA`); a formula not here is refused
by name (`check_reward`), never paid as 0."""
ERROR, SLOPE, NOVELTY, NONE = range(len(FORMULAS))


def signal_codes():
    """The reward signals the compiled loop computes, by name, each with the number of
    its formula (`FORMULAS`): the signals of `icm.learners.interest.SIGNAL_CLASSES`
    whose `KERNEL_FORMULA` is one of `FORMULAS`. One that is not here runs on the
    physics path (per-agent classes) only; `check_reward` refuses it for the tabular
    loop, by name."""
    return {name: FORMULAS.index(cls.KERNEL_FORMULA)
            for name, cls in interest.SIGNAL_CLASSES.items()
            if cls.KERNEL_FORMULA in FORMULAS}


def kept_errors(reward, window):
    """How many of a pair's last errors the loop keeps for `reward`: `window` for a
    slope, else 1."""
    return int(window) if signal_codes()[check_reward(reward)] == SLOPE else 1


NO_LIMIT = np.iinfo(np.int64).max
"""The time limit the loop is given for `max_moves=None`: more moves than any run."""


def check_reward(reward):
    """`reward` if the compiled loop computes it, else a ValueError that names it and
    the ones it computes (or the formula it asks for that the loop does not have)."""
    codes = signal_codes()
    if reward not in codes:
        formula = getattr(interest.SIGNAL_CLASSES.get(reward), "KERNEL_FORMULA", None)
        if formula is not None:
            raise ValueError(f"reward {reward!r} asks the compiled rod loop for the formula "
                             f"{formula!r}, which it does not have; it has "
                             f"{', '.join(FORMULAS)} (add it to icm.experiments._rods_kernel"
                             f".FORMULAS and to play, or run {reward!r} with physics=True)")
        raise ValueError(f"reward {reward!r} is an interest signal the compiled rod loop "
                         f"does not compute; it computes {', '.join(codes)} (add it "
                         f"to icm.experiments._rods_kernel, or run it with physics=True)")
    return one_of("reward", reward, tuple(codes))


def slope_weights(window):
    """weights[m, :m], the least-squares slope weights of m equally spaced values (m = 2
    .. window), from `icm.learners.interest.slope_weights`."""
    weights = np.zeros((window + 1, max(window, 1)))
    for m in range(2, window + 1):
        weights[m, :m] = interest.slope_weights(m)
    return weights


@numba.njit(cache=True, nogil=True)
def play(q, predictions, last_error, draws, cursor, cell, episode, moves, error_sum,
         epsilon, alpha, gamma, lr, next_cell, topples, start, max_moves, n_episodes,
         toppled_out, length_out, errors_out, found, record, signal, window, weights,
         history, count, wobbly, wobbles, env_draws, env_cursor, n_draws,
         wobble_probability, off_grid_ends, edges, edges_out):
    """Plays every row on, move by move, until it has played its episodes or used its
    buffer of uniform numbers (`n_draws` a move, of which it uses the first three, and
    with the wobbly rod one from the environment's buffer at a move beside it, which
    topples it below `wobble_probability`); returns True if every row is done.

    All arrays are updated in place: the learner (q [row, cell, action], predictions
    [row, cell, action, rod], last_error [row, cell, action], and for the reward
    signals the last `window` errors of each pair, history [row, cell, action, window],
    newest last, and its count of tries), the play's state (cell, episode, moves,
    error_sum, edges, cursor, env_cursor), and the record of each episode
    (toppled_out, length_out, errors_out, edges_out, found [row, cell, action, rod],
    and what `record_episode` keeps in the tuple `record`).

    A move off the grid leaves the hand in its cell (`next_cell`); it is counted in
    `edges` (and the episode's `edges_out`), and with `off_grid_ends` it ends the
    episode, as a topple does (nothing follows it). An episode also ends after
    `max_moves` moves (a time limit; pass a number larger than any run for none).
    """
    n, n_cells, n_actions = q.shape
    n_rods = predictions.shape[3]
    chunk = draws.shape[1]
    env_chunk = env_draws.shape[1]
    done = True
    for r in range(n):
        while episode[r] < n_episodes:
            k = cursor[r]
            if k + n_draws > chunk or (wobbly and env_cursor[r] + 1 > env_chunk):
                done = False  # the row needs new numbers
                break
            cursor[r] = k + n_draws
            c = cell[r]
            # Epsilon-greedy on Q(c, .), ties broken by the third number.
            if draws[r, k] < epsilon[r]:
                a = int(draws[r, k + 1] * n_actions)
            else:
                top = q[r, c, 0]
                for b in range(1, n_actions):
                    if q[r, c, b] > top:
                        top = q[r, c, b]
                n_best = 0
                for b in range(n_actions):
                    if q[r, c, b] == top:
                        n_best += 1
                pick = int(draws[r, k + 2] * n_best)
                a = 0
                for b in range(n_actions):
                    if q[r, c, b] == top:
                        if pick == 0:
                            a = b
                            break
                        pick -= 1
            following = next_cell[c, a]
            rod = topples[c, a]
            if wobbly and wobbles[c, a]:  # beside the wobbly rod: it may fall
                u = env_draws[r, env_cursor[r]]
                env_cursor[r] += 1
                if u < wobble_probability:
                    rod = n_rods - 1
            # The predictor: p <- p + lr (o - p); its absolute error, summed over rods.
            total = 0.0
            for i in range(n_rods):
                observed = 1.0 if rod == i else 0.0
                predicted = predictions[r, c, a, i]
                difference = observed - predicted
                predictions[r, c, a, i] = predicted + lr[r] * difference
                error = abs(difference)
                error_sum[r, i] += error
                total = error if i == 0 else total + error
            last_error[r, c, a] = total
            # The reward: the error (the paper's), or another signal of the pair.
            reward = total
            if signal != ERROR:
                tries = count[r, c, a] + 1
                count[r, c, a] = tries
                for i in range(window - 1):  # the pair's last errors, newest last
                    history[r, c, a, i] = history[r, c, a, i + 1]
                history[r, c, a, window - 1] = total
                if signal == SLOPE:  # learning progress: max(0, -slope), from 2 errors on
                    reward = 0.0
                    m = min(tries, window)
                    if m >= 2:
                        slope = 0.0
                        for i in range(m):
                            slope += weights[m, i] * history[r, c, a, window - m + i]
                        if -slope > 0.0:
                            reward = -slope
                elif signal == NOVELTY:
                    reward = 1.0 / np.sqrt(1.0 + tries)
                else:  # NONE: the walk at random is paid nothing
                    reward = 0.0
            off = following == c  # a move off the grid: the hand stayed
            ends = rod >= 0 or (off_grid_ends and off)
            # Equation 3; a topple (or with off_grid_ends a move off the grid) ends the
            # episode, so nothing follows it. The random walker learns no Q: every move
            # stays a tie.
            if signal != NONE:
                target = reward
                if not ends:
                    best = q[r, following, 0]
                    for b in range(1, n_actions):
                        if q[r, following, b] > best:
                            best = q[r, following, b]
                    target += gamma[r] * 1.0 * best
                q[r, c, a] += alpha[r] * (target - q[r, c, a])
            moves[r] += 1
            if off:
                edges[r] += 1
            cell[r] = following
            if ends or moves[r] >= max_moves:
                ep = episode[r]
                toppled_out[r, ep] = rod
                length_out[r, ep] = moves[r]
                edges_out[r, ep] = edges[r]
                edges[r] = 0
                for i in range(n_rods):
                    errors_out[r, ep, i] = error_sum[r, i]
                    error_sum[r, i] = 0.0
                if rod >= 0 and ep < found[r, c, a, rod]:
                    found[r, c, a, rod] = ep
                record_episode(r, ep, rod, q, predictions, last_error, found, record)
                cell[r] = start
                moves[r] = 0
                episode[r] = ep + 1
    return done


def recorder(n_rows, n_episodes, n_cells, n_actions, n_rods, pairs, snapshot_episodes,
             threshold):
    """The arrays `record_episode` fills, as the tuple it takes, for `n_rows` runs of
    `n_episodes` episodes.

    Args:
      pairs: (cells, actions, rods), the map's pairs that topple a rod (red 0 or blue
        1), as `icm.experiments.rod_episodes.toppling_pairs` gives them.
      snapshot_episodes: the episodes (from 1) after which to keep a snapshot, besides
        the four moments.
      threshold: the error below which a rod is predicted well.
    """
    cells, actions, rods = (np.ascontiguousarray(a, dtype=np.int64) for a in pairs)
    n_fixed = N_FIXED_RODS
    n_slots = N_MOMENTS + len(snapshot_episodes)
    return (cells, actions, rods, np.array(snapshot_episodes, dtype=np.int64).reshape(-1) - 1,
            float(threshold),
            np.zeros((n_rows, n_episodes, n_fixed)),  # rod_error
            np.zeros((n_rows, n_episodes, n_fixed)),  # rod_error_toppled
            np.full((n_rows, n_fixed), -1, dtype=np.int64),  # predicted_well_toppled
            np.full((n_rows, n_slots), -1, dtype=np.int64),  # snapshot taken after
            np.zeros((n_rows, n_slots, n_cells, n_actions)),  # q
            np.zeros((n_rows, n_slots, n_cells, n_actions, n_rods)),  # predictions
            np.zeros((n_rows, n_slots, n_cells, n_actions)))  # last_error


RECORD_FIELDS = ("rod_error", "rod_error_toppled", "predicted_well_toppled",
                 "snapshot_taken", "q_snapshots", "p_snapshots", "e_snapshots")
"""The names of the arrays of a `recorder` tuple, from its sixth entry on."""
N_FIXED_RODS = 2
"""The rods that a move topples always or never, red and blue: the rods of `rod_error`."""
N_MOMENTS = 4
"""The moments of `icm.experiments.rod_toppling.MOMENTS`, in their order: the first
episode, red predicted well (reading "all"), red predicted well (reading "toppled"),
the first blue topple."""


@numba.njit(cache=True, nogil=True)
def record_episode(r, ep, rod, q, predictions, last_error, found, record):
    """After episode `ep` (from 0) of row `r`, which ended with `rod` toppled (-1 none),
    and after `found` [row, cell, action, rod] (the first episode each pair toppled each
    rod, or more than any episode) took it in: keeps what the result needs of the
    learner (q, predictions, last_error [row, cell, action, ...]) at this moment, in
    the arrays of `record` (see `recorder`):

    - rod_error [row, episode, rod]: the predictor's largest error (summed over the
      rods, as it is paid) on the map's pairs that topple each rod;
    - rod_error_toppled: the same over the pairs that have toppled it so far, NaN
      before the first;
    - predicted_well_toppled [row, rod]: the first episode (from 1) at which the
      latter is below the threshold, -1 before;
    - the snapshots of the learner [row, slot, ...] at each moment (slots as
      `N_MOMENTS`, then the snapshot episodes), with the episode each was taken after
      in snapshot_taken. The moment "red predicted well" is the first episode from
      which rod_error stays below the threshold to the end of the run: it is known
      only at the end, so its slot is taken again each time the error falls below the
      threshold, and holds the last such episode (the moment, if it came).

    The learner is only read: a run keeps a few snapshots per row, not the learner
    after every episode. Called by `play` and, for the physics, by
    `icm.experiments.rod_episodes.play_episodes`.
    """
    (pair_cells, pair_actions, pair_rods, snapshot_at, threshold, rod_error,
     rod_error_toppled, well_toppled, taken, q_snap, p_snap, e_snap) = record
    n_rods = predictions.shape[3]
    for f in range(rod_error.shape[2]):
        worst = -np.inf
        known = -np.inf
        seen = False
        for p in range(pair_cells.shape[0]):
            if pair_rods[p] != f:
                continue
            c, a = pair_cells[p], pair_actions[p]
            total = 0.0
            for i in range(n_rods):  # in order, as the one-agent sum
                truth = 1.0 if i == f else 0.0
                error = abs(truth - predictions[r, c, a, i])
                total = error if i == 0 else total + error
            if total > worst:
                worst = total
            if found[r, c, a, f] <= ep:
                seen = True
                if total > known:
                    known = total
        rod_error[r, ep, f] = worst
        rod_error_toppled[r, ep, f] = known if seen else np.nan
        if seen and known < threshold and well_toppled[r, f] < 0:
            well_toppled[r, f] = ep + 1
    below = rod_error[r, ep, 0] < threshold
    for s in range(taken.shape[1]):
        if s == 0:
            now = ep == 0
        elif s == 1:
            now = below and (ep == 0 or not rod_error[r, ep - 1, 0] < threshold)
        elif s == 2:
            now = well_toppled[r, 0] == ep + 1
        elif s == 3:
            now = rod == 1 and taken[r, 3] < 0
        else:
            now = ep == snapshot_at[s - N_MOMENTS]
        if now:
            taken[r, s] = ep
            q_snap[r, s] = q[r]
            p_snap[r, s] = predictions[r]
            e_snap[r, s] = last_error[r]


def play_all(streams, q, predictions, last_error, epsilon, alpha, gamma, lr, next_cell,
             topples, start, max_moves, n_episodes, pairs, snapshot_episodes, threshold,
             bar=None, reward="prediction_error", window=5, wobbles=None, env_streams=None,
             off_grid="stay"):
    """Plays `n_episodes` episodes of every row (see `play`), refilling the rows'
    streams of uniform numbers whenever they run out; `bar`, a tqdm progress bar over
    all rows' episodes, is moved on between the compiled loop's runs. `reward` names
    the reward signal, `window` its slope's length; with the wobbly rod, `wobbles`
    [cell, action] marks the moves beside it and `env_streams` are the tables' own
    streams (`icm.envs.rods.RodTableBatch.streams`). `pairs`, `snapshot_episodes` and
    `threshold` are those of `recorder`. `max_moves` is an integer >= 1, or None for
    no time limit; `off_grid` is "stay" or "end" (`icm.envs.rods.rules.OFF_GRIDS`).

    Returns:
      A dict: "toppled", "length", "edges" (moves off the grid) [row, episode], "errors"
      [row, episode, rod], and the arrays of `record_episode` by the names of
      `RECORD_FIELDS`.
    """
    n, n_cells, n_actions = q.shape
    n_rods = predictions.shape[3]
    cell = np.full(n, start, dtype=np.int64)
    episode = np.zeros(n, dtype=np.int64)
    moves = np.zeros(n, dtype=np.int64)
    error_sum = np.zeros((n, n_rods))
    out = {"toppled": np.full((n, n_episodes), -1, dtype=np.int64),
           "length": np.zeros((n, n_episodes), dtype=np.int64),
           "edges": np.zeros((n, n_episodes), dtype=np.int64),
           "errors": np.zeros((n, n_episodes, n_rods))}
    edges = np.zeros(n, dtype=np.int64)
    limit = NO_LIMIT if max_moves is None else int(max_moves)
    off_grid_ends = one_of("off_grid", off_grid, rod_rules.OFF_GRIDS) == "end"
    found = np.full((n, n_cells, n_actions, n_rods), n_episodes, dtype=np.int64)
    record = recorder(n, n_episodes, n_cells, n_actions, n_rods, pairs, snapshot_episodes,
                      threshold)
    per_row = lambda value: np.ascontiguousarray(np.broadcast_to(
        np.asarray(value, dtype=float), (n,)))
    epsilon, alpha, gamma, lr = per_row(epsilon), per_row(alpha), per_row(gamma), per_row(lr)
    signal = signal_codes()[check_reward(reward)]
    n_draws = int(action_selection.DRAWS_PER_CHOICE)
    window = kept_errors(reward, window)
    weights = slope_weights(window)
    history = np.zeros((n, n_cells, n_actions, window) if signal != ERROR
                       else (0, 0, 0, window))
    count = np.zeros((n, n_cells, n_actions) if signal != ERROR else (0, 0, 0),
                     dtype=np.int64)
    wobbly = wobbles is not None
    if wobbly:
        env_cursor = env_streams.cursor
        wobbles = np.ascontiguousarray(wobbles, dtype=np.bool_)
    else:
        env_draws, env_cursor = np.zeros((n, 1)), np.zeros(n, dtype=np.int64)
        wobbles = np.zeros(next_cell.shape, dtype=np.bool_)
    while True:
        if wobbly:  # read again: a refill may give the streams a longer buffer
            env_draws = env_streams.buffer
        finished = play(q, predictions, last_error, streams.buffer, streams.cursor, cell,
                        episode, moves, error_sum, epsilon, alpha, gamma, lr, next_cell,
                        topples, start, limit, n_episodes, out["toppled"],
                        out["length"], out["errors"], found, record, signal, window,
                        weights, history, count, wobbly, wobbles, env_draws, env_cursor,
                        n_draws, float(rod_rules.WOBBLE_TOPPLE_PROBABILITY),
                        off_grid_ends, edges, out["edges"])
        if bar is not None:
            bar.update(int(episode.sum()) - bar.n)
        if finished:
            return {**out, **dict(zip(RECORD_FIELDS, record[5:]))}
        unfinished = np.flatnonzero(episode < n_episodes)
        streams.refill(unfinished, n_draws)
        if wobbly:
            env_streams.refill(unfinished, 1)
