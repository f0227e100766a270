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
from icm.experiments import loop
from icm.experiments.loop import Transition
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
    signal = interest.SIGNAL_CLASSES[reward]
    kmax = 1 if signal.ONE_ERROR_REWARD else window
    learner += 8 * (kmax + 1) ** 2 * kmax
    if physics:
        learner += n_rows * 8 * pairs * (kmax + 2)
    elif signal.KERNEL_FORMULA != "error":  # the compiled loop's kept errors and count
        # (`_rods_kernel.kept_errors`, not imported here: it loads Numba)
        kept_errors = window if signal.KERNEL_FORMULA == "slope" else 1
        learner += n_rows * 8 * pairs * (kept_errors + 1)
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


class RodEpisodesWorld:
    """A batched rod table as the Q-learner plays it, for the one loop
    (`icm.experiments.loop.play`): an episode starts with the hand over the start cell;
    a state is the hand's cell (its number); a move's outcome is the rod it toppled (0
    red, 1 blue, 2 wobbly, -1 none). A topple ends the episode for good (discount 0),
    and so, with `off_grid="end"`, does a move off the grid (the hand stayed in its
    cell); an episode also ends after `max_moves` moves (a time limit, discount 1).
    The rows move independently.

    Args:
      env: a batched rod table, one row per run (as `icm.envs.rods.RodTableBatch`:
        `start`, `new_episodes(rows)`, `move(rows, cells, actions)`).
      max_moves: moves after which an episode without a topple ends, or None.
      off_grid: what a move off the grid does, "stay" or "end".
    """

    def __init__(self, env, max_moves, off_grid=rods.OFF_GRID.default):
        from icm.experiments import _rods_kernel  # here: it loads Numba

        self.env = env
        self.limit = _rods_kernel.NO_LIMIT if rods.check_max_moves(max_moves) is None \
            else max_moves
        self.off_grid_ends = rods.check_off_grid(off_grid) == "end"
        self.moves = np.zeros(env.n_rows, dtype=np.int64)

    def __len__(self):
        return len(self.moves)

    def reset(self, rows):
        """New episodes in `rows`: their start cells."""
        self.env.new_episodes(rows)
        self.moves[rows] = 0
        return np.full(len(rows), self.env.start)

    def step(self, rows, cells, actions):
        """Moves the hand of `rows` from `cells` by `actions`."""
        next_cells, toppled = self.env.move(rows, cells, actions)
        terminal = (toppled >= 0) | ((next_cells == cells) & self.off_grid_ends)
        self.moves[rows] += 1
        ended = terminal | (self.moves[rows] >= self.limit)
        return Transition(next_cells, toppled, None, np.where(terminal, 0.0, 1.0), ended)


class QLearners:
    """Per-agent Q-learners (`icm.learners.q_learning.QLearner`, one per row) as the one
    loop drives them: each row's agent chooses and learns through its own methods, in
    row order, so that its numbers are its own. A step's `learned` is each row's
    predictor errors on each rod, [rows, rod].

    Args:
      agents: one `QLearner` per row.
    """

    def __init__(self, agents):
        self.agents = list(agents)
        self.n_rods = self.agents[0].predictor.n_outputs

    def act(self, rows, cells):
        """Each row's move from its cell (epsilon-greedy on its Q-table)."""
        return np.array([self.agents[r].select_action(int(c)) for r, c in
                         zip(rows.tolist(), cells.tolist())], dtype=np.int64), None

    def learn(self, step):
        """Each row's agent learns its move (what toppled, the discount)."""
        errors = np.zeros((len(step.rows), self.n_rods))
        for k, (r, c, a, after, rod, discount) in enumerate(zip(
                step.rows.tolist(), step.before.tolist(), step.action.tolist(),
                step.after.tolist(), step.outcome.tolist(), np.broadcast_to(
                    step.discount, step.rows.shape).tolist())):
            observed = [1.0 if rod == i else 0.0 for i in range(self.n_rods)]
            self.agents[r].learn(c, a, observed, after, discount)
            errors[k] = self.agents[r].last_errors
        return errors


class EpisodeRecord:
    """The observer that reduces per-agent Q-learners' episodes to what a
    `RodTopplingResult` keeps (`summarize`): after each move the predictor's errors and
    the moves off the grid, and after each episode what it ended with, its length, and
    the compiled `icm.experiments._rods_kernel.record_episode` on the learner, as the
    compiled loop of the tabular runs records it (which gives the same numbers).

    Args:
      agents: the `QLearner` of each row (read when its episode ends).
      n_episodes: episodes per row.
      snapshot_episodes: episodes after which to keep a snapshot (see `summarize`).
    """

    def __init__(self, agents, n_episodes, snapshot_episodes=()):
        from icm.experiments import _rods_kernel  # here: it loads Numba

        self.kernel = _rods_kernel
        self.agents, self.snapshot_episodes = list(agents), snapshot_episodes
        n = len(self.agents)
        n_states, n_actions = self.agents[0].n_states, self.agents[0].n_actions
        n_rods = self.agents[0].predictor.n_outputs
        self.raw = {"toppled": np.full((n, n_episodes), -1, dtype=np.int64),
                    "length": np.zeros((n, n_episodes), dtype=np.int64),
                    "edges": np.zeros((n, n_episodes), dtype=np.int64),
                    "errors": np.zeros((n, n_episodes, n_rods))}
        self.found = np.full((n, n_states, n_actions, n_rods), n_episodes, dtype=np.int64)
        self.record = _rods_kernel.recorder(n, n_episodes, n_states, n_actions, n_rods,
                                            toppling_pairs(), snapshot_episodes,
                                            WELL_PREDICTED_ERROR)
        # The learners as tables, filled in for a row when its episode ends (what
        # record_episode reads).
        self.q = np.zeros((n, n_states, n_actions))
        self.predictions = np.zeros((n, n_states, n_actions, n_rods))
        self.last_error = np.full((n, n_states, n_actions), np.nan)
        self.states = list(range(n_states))
        self.moves = np.zeros(n, dtype=np.int64)
        self.edges = np.zeros(n, dtype=np.int64)
        self.error_sum = np.zeros((n, n_rods))

    def __call__(self, step):
        rows = step.rows
        for i in range(self.error_sum.shape[1]):  # in order, as the loop adds
            self.error_sum[rows, i] += step.learned[:, i]
        self.moves[rows] += 1
        self.edges[rows] += step.after == step.before  # a move off the grid: the hand stayed
        if not step.ended.any():
            return
        ended = step.ended
        done, top, ep = rows[ended], step.outcome[ended], step.episode[ended]
        raw = self.raw
        raw["toppled"][done, ep] = top
        raw["length"][done, ep] = self.moves[done]
        raw["edges"][done, ep] = self.edges[done]
        raw["errors"][done, ep] = self.error_sum[done]
        hit = top >= 0
        pairs = (done[hit], step.before[ended][hit], step.action[ended][hit], top[hit])
        self.found[pairs] = np.minimum(self.found[pairs], ep[hit])
        n_actions = self.q.shape[2]
        for row, row_episode, rod in zip(done.tolist(), ep.tolist(), top.tolist()):
            learner = self.agents[row]
            self.q[row] = learner.q
            self.predictions[row] = learner.predictor.table(self.states)
            self.last_error[row] = [[np.nan if e is None else e
                                     for e in (learner.predictor.last_error(s, a)
                                               for a in range(n_actions))]
                                    for s in self.states]
            self.kernel.record_episode(row, row_episode, rod, self.q, self.predictions,
                                       self.last_error, self.found, self.record)
        self.moves[done], self.edges[done], self.error_sum[done] = 0, 0, 0.0

    def summary(self):
        """The summary of the played episodes (`summarize`)."""
        raw = dict(self.raw)
        raw.update(zip(self.kernel.RECORD_FIELDS, self.record[5:]))
        return summarize(raw, self.snapshot_episodes)


def play_episodes(env, agents, n_episodes, max_moves, snapshot_episodes=(), progress=False,
                  off_grid=rods.OFF_GRID.default, observe=None):
    """Plays `n_episodes` episodes of each per-agent learner of `agents` (`QLearner`
    objects, one per row of `env`, a batched rod table such as the physics one) through
    the one loop (`icm.experiments.loop.play`: `RodEpisodesWorld`, `QLearners`), and
    summarises them (`EpisodeRecord`, `summarize`).

    The rows move independently: each acts at every iteration until it has played its
    episodes, starting a new episode (hand over the start cell) as soon as its last one
    ended with a topple, after `max_moves` moves (None: no limit), or with
    `off_grid="end"` at a move off the grid (the hand stayed in its cell).

    Args:
      env: a batched rod table, one row per agent (as `icm.envs.rods.RodTableBatch`:
        `start`, `new_episodes(rows)`, `move(rows, cells, actions)`).
      agents: one `icm.learners.q_learning.QLearner` per row.
      n_episodes: episodes each row plays (>= 1).
      max_moves: moves after which an episode without a topple ends, or None.
      snapshot_episodes: episodes after which to keep a snapshot (see `summarize`).
      progress: show a progress bar over the episodes.
      off_grid: what a move off the grid does, "stay" or "end".
      observe: None, or a function called with every move, a
        `icm.experiments.loop.Step` of the rows that moved (its `before` and `after`
        the cells, `action` the moves, `outcome` the rod toppled, -1 for none, and
        `learned` the predictor's errors on each rod): a recorder, for example.

    Returns:
      The summary of the episodes (`summarize`).

    Raises:
      ValueError: for a bad `n_episodes`, `max_moves` or `off_grid`.
    """
    n_episodes = _validate.integer_at_least("n_episodes", n_episodes, 1)
    observe = _validate.function("observe", observe)
    record = EpisodeRecord(agents, n_episodes, snapshot_episodes)
    bar = loop.progress(len(agents) * n_episodes, "Q-learner on the rods", progress,
                        "episode")
    try:
        loop.play(RodEpisodesWorld(env, max_moves, off_grid), QLearners(agents), n_episodes,
                  [record, bar, observe])
    finally:
        if bar is not None:
            bar.close()
    return record.summary()


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
