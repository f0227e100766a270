"""The rod experiment's episode rules and its fast tabular twin, one run or many."""

import collections

import dm_env
import numpy as np

from icm import _streams, _validate
from icm.envs._common import check_discrete_action, check_seed
from icm.envs.suite import SUITE
from icm.envs.rods import rules
from icm.envs.rods.rules import (ACTIONS, DEFAULT_MAX_MOVES, DEFAULT_START_CELL, OFF_GRID,
                                     ROD_NAMES, action_spec, cell_number, check_max_moves,
                                     check_off_grid, check_start_cell, leaves_grid,
                                     load_topple_map,
                                     load_wobble_map, next_cell, observation_spec,
                                     rod_names, standable_cells, transition_tables,
                                     wobble_table)


class RodEpisodes(dm_env.Environment):
    """The episode rules of the rod experiment, shared by `RodTable` (tabular) and
    `PhysicsRodTable` (simulated iCub), so both follow them by construction.

    An episode starts with the hand over `start_cell` and both rods standing. Each
    action moves the hand to the neighbouring cell (off the grid: it stays). A move
    that topples a rod ends the episode (discount 0.0, a termination) with the rod
    shown toppled; with `off_grid="end"`, so does a move off the grid (discount 0.0,
    no rod toppled); after `max_moves` moves without a topple the episode ends on a
    time limit (discount 1.0; `max_moves=None`: never). Reward is always 0.0. A step
    after the end of an episode starts a new one.

    With `wobbly_rod`, the scene has a third rod (see `icm.envs.rods.rules`), the
    last entry of `rods`.

    Subclasses say how an episode starts (`_start`, putting the hand's cell in
    `_cell`) and what a move does (`_move`, returning the hand's cell and the rods'
    toppled flags).
    """

    def __init__(self, start_cell, max_moves, wobbly_rod=False, off_grid=OFF_GRID.default):
        self.start_cell = check_start_cell(start_cell, standable_cells())
        self.max_moves = check_max_moves(max_moves)
        self.wobbly_rod = _validate.boolean("wobbly_rod", wobbly_rod)
        self.off_grid = check_off_grid(off_grid)
        self.rod_names = rod_names(self.wobbly_rod)
        self._cell = self.start_cell
        self._moves = 0
        self._reset_next_step = True

    def _start(self):
        raise NotImplementedError

    def _move(self, action):
        raise NotImplementedError

    @staticmethod
    def _observation(cell, rods):
        return collections.OrderedDict(hand=np.array(cell, dtype=np.int64),
                                       rods=np.asarray(rods, dtype=np.int64))

    def reset(self):
        """Starts a new episode: the hand over the start cell, both rods standing.

        Returns:
          The FIRST time step.
        """
        self._start()
        self._moves = 0
        self._reset_next_step = False
        return dm_env.restart(self._observation(self.start_cell, [0] * len(self.rod_names)))

    def step(self, action):
        """Moves the hand: 0 forward, 1 backward, 2 left, 3 right.

        Returns:
          The time step after the move; after the end of an episode, a new one starts
          instead.

        Raises:
          ValueError: if `action` is not 0-3.
        """
        action = check_discrete_action(action, len(ACTIONS))
        if self._reset_next_step:
            return self.reset()
        off = leaves_grid(self._cell, action)
        cell, rods = self._move(action)
        self._moves += 1
        observation = self._observation(cell, rods)
        if any(rods) or (off and self.off_grid == "end"):
            self._reset_next_step = True
            return dm_env.termination(0.0, observation)
        if self.max_moves is not None and self._moves >= self.max_moves:
            self._reset_next_step = True
            return dm_env.truncation(0.0, observation, discount=1.0)
        return dm_env.transition(0.0, observation)

    def observation_spec(self):
        """The observation spec: `hand` and `rods` (see `observation_spec()`)."""
        return observation_spec(self.wobbly_rod)

    def action_spec(self):
        """The action spec: four moves (see `action_spec()`)."""
        return action_spec()


@SUITE.add("rods", episodes=RodEpisodes,
           physics="icm.envs.rods.physics:PhysicsRodTable",
           continuous="icm.envs.rods.physics:load_continuous",
           task="icm.envs.rods.physics:RodsTask")
class RodTable(RodEpisodes):
    """The tabular rod experiment: the grid rules and the stored topple map, no physics.

    The episode rules are those of `RodEpisodes`; whether a move topples a rod is read
    from the topple map measured in physics (assets/rod_topple_map.json).

    Args:
      start_cell: (column, row) where each episode starts; must be a standable cell of
        the map. Default (0, 0), the cell nearest the robot on its left.
      max_moves: moves before an episode without a topple ends (>= 1, default 30;
        None: no limit, the paper's reading).
      wobbly_rod: add the wobbly rod (default False).
      seed: None, an integer >= 0 or a `numpy.random.Generator`; draws whether a move
        beside the wobbly rod topples it (one number per such move; without the
        wobbly rod the rules use no randomness).
      off_grid: what a move off the grid does: "stay" (default, the hand stays) or
        "end" (the episode ends); see `icm.envs.rods.rules.OFF_GRID`.

    Raises:
      ValueError: for a start cell off the grid or where a rod stands, max_moves < 1,
        an unknown off_grid, or (in `step`) an action that is not 0-3.
    """

    def __init__(self, start_cell=DEFAULT_START_CELL, max_moves=DEFAULT_MAX_MOVES,
                 wobbly_rod=False, seed=None, off_grid=OFF_GRID.default):
        super().__init__(start_cell, max_moves, wobbly_rod, off_grid)
        self._map = load_topple_map()
        self._wobbles = load_wobble_map() if self.wobbly_rod else set()
        self._random = check_seed(seed)
        self._cell = self.start_cell

    def reseed(self, seed):
        """Restarts the random generator (used by the wobbly rod only) from `seed`; the
        next step starts a new episode."""
        self._random = check_seed(seed)
        self._reset_next_step = True

    @property
    def topple_map(self):
        """{(cell, action): "red" | "blue" | None} for the standable cells."""
        return dict(self._map["topples"])

    def _start(self):
        self._cell = self.start_cell

    def _move(self, action):
        toppled = self._map["topples"][(self._cell, action)]
        if (self._cell, action) in self._wobbles and \
                self._random.random() < rules.WOBBLE_TOPPLE_PROBABILITY:
            toppled = self.rod_names[-1]
        self._cell = next_cell(self._cell, action)
        rods = [int(toppled == name) for name in self.rod_names]
        return self._cell, rods


class RodTableBatch:
    """Many tabular rod tables at once, one per row, moving independently: the rows
    need not be in the same episode or at the same move.

    Cells are cell numbers (`icm.envs.rods.rules.cell_number`); a move returns the next
    cell and the rod toppled (0 red, 1 blue, 2 wobbly, -1 none) of each moving row,
    from the same stored maps as `RodTable`. With the wobbly rod, row k draws from
    `seeds[k]` exactly the numbers `RodTable(wobbly_rod=True, seed=seeds[k])` draws.

    Args:
      n_rows: number of tables.
      start_cell: (column, row) where every episode starts.
      wobbly_rod: add the wobbly rod.
      seeds: one seed per row (needed with the wobbly rod; default 0, 1, ...).
    """

    def __init__(self, n_rows, start_cell=DEFAULT_START_CELL, wobbly_rod=False, seeds=None):
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.start = cell_number(check_start_cell(start_cell, standable_cells()))
        self.next_cell, self.topples = transition_tables()
        self.wobbly_rod = _validate.boolean("wobbly_rod", wobbly_rod)
        self.wobbles = wobble_table() if self.wobbly_rod else \
            np.zeros(self.topples.shape, dtype=bool)
        self.streams = None
        if self.wobbly_rod:
            self.streams = _streams.Streams(range(self.n_rows) if seeds is None else seeds,
                                            chunk=16)

    def new_episodes(self, rows):
        """Starts new episodes in `rows` (the tabular rules keep no state)."""

    def move(self, rows, cells, actions):
        """The moves `actions` of the tables `rows`, each from its cell in `cells`:
        returns (next cells, rods toppled), arrays like `rows`."""
        toppled = self.topples[cells, actions]
        if self.wobbly_rod:
            beside = np.flatnonzero(self.wobbles[cells, actions])
            if beside.size:
                toppled = toppled.copy()
                falls = self.streams.draw(np.asarray(rows)[beside], k=1)[:, 0] \
                    < rules.WOBBLE_TOPPLE_PROBABILITY
                toppled[beside[falls]] = len(ROD_NAMES)
        return self.next_cell[cells, actions], toppled
