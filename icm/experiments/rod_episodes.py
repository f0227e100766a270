"""The rods' episodes, shared by the two ways `icm.experiments.run_rod_toppling`
plays them: the loop of the per-agent learners (`play_episodes`, the physics runs; its
public loop), the summary of played episodes that the compiled loop
(`icm.experiments._rods_kernel`) also gives (`summarize`), and what a run costs in
memory (`memory_needed`)."""

import math

import numpy as np

from icm import _streams, _validate
from icm.envs import rods
from icm.experiments._memory import FIXED_BYTES, PHYSICS_SCENE_BYTES
from icm.experiments._progress import progress_bar
from icm.learners import action_selection, interest, predictors
from icm.stats import first_from_which

RODS = rods.ROD_NAMES
"""Order of the rod axis in the result arrays: red, blue (with the wobbly rod, the
arrays of what the robot predicted and was paid, `prediction_error` and
`predictions`, have a third entry, wobbly; see `RodTopplingResult.rod_names`)."""
WELL_PREDICTED_ERROR = 0.1
"""A rod is *predicted well* when the predictor's error on its pairs is below this."""
MOMENTS = ("first episode", "red predicted well", "red predicted well (toppled)",
           "blue begins")
"""The moments of Figure 7, found in each run's data, snapshot after the episode:

- "first episode": episode 1 (Figure 7a);
- "red predicted well": the episode `predicted_well[seed, 0]` (reading "all"; Figure
  7b, "it eventually predicts it and gets bored");
- "red predicted well (toppled)": the same with reading "toppled";
- "blue begins": the first episode that ends with the blue rod toppled (Figure 7c,
  "it starts to interact with the blue rod").

A moment that never came has episode -1."""
N_STATES = rods.N_COLUMNS * rods.N_ROWS
N_ACTIONS = len(rods.ACTIONS)

LOOP_ROW_BYTES = 500
"""An upper bound on the play's own small arrays and temporaries, per row."""


def memory_needed(n_rows, n_episodes, reward="prediction_error", window=interest.DEFAULT_WINDOW,
                  wobbly_rod=False, physics=False, max_moves=rods.DEFAULT_MAX_MOVES,
                  n_snapshot_episodes=0):
    """An upper bound on the memory a batch of `n_rows` runs of `run_rod_toppling` adds
    to the process, in bytes, counted from its arrays' shapes (see
    `icm.experiments._memory`). The learner is kept at the moments only, so that
    memory grows with the episodes by the result alone.

    Returns:
      (peak, kept): the bound on the run's peak, and the bytes of its result.
    """
    n_rods = len(rods.rod_names(wobbly_rod))
    n_fixed, pairs = len(RODS), N_STATES * N_ACTIONS
    n_snapshots = len(MOMENTS) + n_snapshot_episodes
    # The result, per row and episode: toppled, episode_length, edge_moves;
    # prediction_error [rod]; rod_error, rod_error_toppled [red and blue] ...
    kept = 8 * n_rows * n_episodes * (3 + n_rods + 2 * n_fixed)
    # ... per row and snapshot: q_table, predictions [cell, action, ...], confidence [cell].
    kept += 8 * n_rows * n_snapshots * (pairs * (1 + n_rods) + N_STATES)
    # While it is made: the masks that find the moments, per episode; the snapshots as
    # the loop keeps them (q, predictions, last errors) and the confidence's terms.
    making = n_rows * (8 * n_episodes + 8 * n_snapshots * pairs * (2 + n_rods + 2))
    # The learner: q, predictions, last errors, and the first topple of each pair.
    learner = n_rows * (8 * pairs * (2 + 2 * n_rods) + LOOP_ROW_BYTES)
    # The reward's slope table, and its last errors, count (and progress) per pair: the
    # compiled loop keeps its own (the batched learner's, never written, take no memory).
    kmax = 1 if reward == "prediction_error" else window
    learner += 8 * (kmax + 1) ** 2 * kmax
    if physics:
        learner += n_rows * 8 * pairs * (kmax + 2)
    elif reward != "prediction_error":
        learner += n_rows * 8 * pairs * ((window if reward == "learning_progress" else 1) + 1)
    moves = n_episodes * (math.inf if max_moves is None else max_moves)  # at most
    streams = _streams.memory_bound(n_rows, moves * action_selection.DRAWS_PER_CHOICE)
    if physics:  # a simulated table per row
        tables = n_rows * PHYSICS_SCENE_BYTES
    else:  # the tabular tables' numbers: one a move beside the wobbly rod
        tables = _streams.memory_bound(n_rows, moves, chunk=16) if wobbly_rod else 0
    return FIXED_BYTES + kept + making + learner + streams + tables, kept


def toppling_pairs():
    """The map's pairs that topple a rod, as arrays: cell numbers, actions, rods (0 red,
    1 blue), in the map's order."""
    cells, actions, which = [], [], []
    for (cell, action), rod in rods.load_topple_map()["topples"].items():
        if rod is not None:
            cells.append(rods.cell_number(cell))
            actions.append(action)
            which.append(RODS.index(rod))
    return np.array(cells), np.array(actions), np.array(which)


def play_episodes(env, agents, n_episodes, max_moves, snapshot_episodes=(), progress=False,
                  off_grid=rods.OFF_GRID.default, observe=None):
    """Plays `n_episodes` episodes of each per-agent learner of `agents` (`QLearner` objects,
    one per row of `env`, a batched rod table such as the physics one), and summarises
    them (`summarize`).

    The rows move independently: each acts at every iteration until it has played its
    episodes, starting a new episode (hand over the start cell) as soon as its last one
    ended with a topple, after `max_moves` moves (None: no limit), or with
    `off_grid="end"` at a move off the grid (the hand stayed in its cell). After each episode the compiled
    `icm.experiments._rods_kernel.record_episode` keeps what the result needs, as the
    compiled loop of the tabular runs does (which gives the same numbers).

    Args:
      env: a batched rod table, one row per agent (as `icm.envs.rods.RodTableBatch`:
        `start`, `new_episodes(rows)`, `move(rows, cells, actions)`).
      agents: one `icm.learners.q_learning.QLearner` per row.
      n_episodes: episodes each row plays (>= 1).
      max_moves: moves after which an episode without a topple ends, or None.
      snapshot_episodes: episodes after which to keep a snapshot (see `summarize`).
      progress: show a progress bar over the episodes.
      off_grid: what a move off the grid does, "stay" or "end".
      observe: None, or a function called after every move as
        `observe(rows, cells, actions, next_cells, toppled)` (arrays over the rows that
        moved; `toppled` is the rod toppled, -1 for none): a recorder, for example.

    Returns:
      The summary of the episodes (`summarize`).

    Raises:
      ValueError: for a bad `n_episodes`, `max_moves` or `off_grid`.
    """
    from icm.experiments import _rods_kernel  # here: it loads Numba

    n_episodes = _validate.integer_at_least("n_episodes", n_episodes, 1)
    observe = _validate.function("observe", observe)

    n = len(agents)
    n_states, n_actions = agents[0].n_states, agents[0].n_actions
    n_rods = agents[0].predictor.n_outputs
    raw = {"toppled": np.full((n, n_episodes), -1, dtype=np.int64),
           "length": np.zeros((n, n_episodes), dtype=np.int64),
           "edges": np.zeros((n, n_episodes), dtype=np.int64),
           "errors": np.zeros((n, n_episodes, n_rods))}
    limit = _rods_kernel.NO_LIMIT if rods.check_max_moves(max_moves) is None else max_moves
    off_grid_ends = rods.check_off_grid(off_grid) == "end"
    found = np.full((n, n_states, n_actions, n_rods), n_episodes, dtype=np.int64)
    record = _rods_kernel.recorder(n, n_episodes, n_states, n_actions, n_rods,
                                   toppling_pairs(), snapshot_episodes, WELL_PREDICTED_ERROR)
    # The learners as tables, filled in for a row when its episode ends (what
    # record_episode reads).
    q = np.zeros((n, n_states, n_actions))
    predictions = np.zeros((n, n_states, n_actions, n_rods))
    last_error = np.full((n, n_states, n_actions), np.nan)
    states = list(range(n_states))
    state = np.full(n, env.start)
    episode = np.zeros(n, dtype=np.int64)
    moves = np.zeros(n, dtype=np.int64)
    edges = np.zeros(n, dtype=np.int64)
    error_sum = np.zeros((n, n_rods))
    active = np.arange(n)
    env.new_episodes(active)
    bar = progress_bar(None, n * n_episodes, "Q-learner on the rods", progress, unit="episode")
    while active.size:
        cells = state[active]
        actions = np.array([agents[r].select_action(int(c)) for r, c in zip(active, cells)],
                           dtype=np.int64)
        next_cells, toppled = env.move(active, cells, actions)
        if observe is not None:
            observe(active, cells, actions, next_cells, toppled)
        off = next_cells == cells  # a move off the grid: the hand stayed
        terminal = (toppled >= 0) | (off & off_grid_ends)
        for r, c, a, after, rod, last in zip(active.tolist(), cells.tolist(),
                                             actions.tolist(), next_cells.tolist(),
                                             toppled.tolist(), terminal.tolist()):
            observed = [1.0 if rod == i else 0.0 for i in range(n_rods)]
            agents[r].learn(c, a, observed, after, 0.0 if last else 1.0)
            for i, error in enumerate(agents[r].last_errors):  # in order, as the loop adds
                error_sum[r, i] += error
        moves[active] += 1
        edges[active] += off
        state[active] = next_cells
        ended = terminal | (moves[active] >= limit)
        if not ended.any():
            continue
        done, top, ep = active[ended], toppled[ended], episode[active[ended]]
        raw["toppled"][done, ep] = top
        raw["length"][done, ep] = moves[done]
        raw["edges"][done, ep] = edges[done]
        raw["errors"][done, ep] = error_sum[done]
        hit = top >= 0
        pairs = (done[hit], cells[ended][hit], actions[ended][hit], top[hit])
        found[pairs] = np.minimum(found[pairs], ep[hit])
        for row, row_episode, rod in zip(done.tolist(), ep.tolist(), top.tolist()):
            learner = agents[row]
            q[row] = learner.q
            predictions[row] = learner.predictor.table(states)
            last_error[row] = [[np.nan if e is None else e
                                for e in (learner.predictor.last_error(s, a)
                                          for a in range(n_actions))] for s in states]
            _rods_kernel.record_episode(row, row_episode, rod, q, predictions, last_error,
                                        found, record)
        state[done], moves[done], edges[done], error_sum[done] = env.start, 0, 0, 0.0
        episode[done] += 1
        env.new_episodes(done)
        active = active[episode[active] < n_episodes]
        if bar is not None:
            bar.update(len(done))
    if bar is not None:
        bar.close()
    raw.update(zip(_rods_kernel.RECORD_FIELDS, record[5:]))
    return summarize(raw, snapshot_episodes)


def summarize(raw, snapshot_episodes=()):
    """The summary of played episodes (`play_episodes`, or the compiled loop).

    Args:
      raw: over [row, episode], "toppled", "length", "edges", "errors" [..., rod], and what
        `icm.experiments._rods_kernel.record_episode` kept: "rod_error",
        "rod_error_toppled" [..., rod], "predicted_well_toppled" [row, rod], and the
        learner's snapshots [row, slot, ...] "q_snapshots", "p_snapshots",
        "e_snapshots", each taken after episode "snapshot_taken" [row, slot].

    Returns:
      A dict of arrays: over [row, episode], "toppled" (0 red, 1 blue, -1 none),
      "length" (moves), "edges" (moves off the grid), "errors" [..., rod] (the predictor's errors, summed over the
      episode's moves), "rod_error" and "rod_error_toppled" [..., rod] (see
      `RodTopplingResult`); "predicted_well_toppled" [row, rod]; and the snapshots
      over [row, snapshot] at the `MOMENTS` and after the `snapshot_episodes`,
      "snapshot_episode" (-1: never), "q" [..., cell, action], "predictions" [..., cell,
      action, rod], "confidence" [..., cell] (where a moment never came, they hold
      whatever the slot holds: the caller masks them).
    """
    n, n_episodes = raw["toppled"].shape
    out = {key: raw[key] for key in ("toppled", "length", "edges", "errors", "rod_error",
                                     "rod_error_toppled", "predicted_well_toppled")}
    # The moments, and the learner at each of them.
    red_well = first_from_which(out["rod_error"][..., 0] < WELL_PREDICTED_ERROR)
    blue = out["toppled"] == 1
    chosen = np.stack([np.zeros(n, dtype=np.int64), red_well,
                       out["predicted_well_toppled"][:, 0] - 1,
                       np.where(blue.any(axis=1), np.argmax(blue, axis=1), -1)]
                      + [np.full(n, e - 1) for e in snapshot_episodes], axis=1)
    chosen = np.maximum(chosen, -1)  # a moment that never came: -1
    came = chosen >= 0
    if not np.array_equal(raw["snapshot_taken"][came], chosen[came]):
        raise RuntimeError("a snapshot was not taken at its moment: the recorder and "
                           "summarize disagree")
    out["snapshot_episode"] = np.where(came, chosen + 1, -1)
    out["q"] = raw["q_snapshots"]
    out["predictions"] = raw["p_snapshots"]
    last_error = raw["e_snapshots"]
    n_actions = last_error.shape[-1]
    capped = np.where(np.isnan(last_error), predictors.UNTRIED_ERROR,
                      np.minimum(last_error, 1.0))
    total = capped[..., 0]
    for a in range(1, n_actions):  # in order, as the one-agent sum
        total = total + capped[..., a]
    out["confidence"] = 1.0 - total / n_actions
    return out
