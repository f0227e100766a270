"""The rod experiment's episode rules and its fast tabular twin, one run or many."""

import collections

import dm_env
import numpy as np

from icm import _validate
from icm.envs._common import check_discrete_action, check_seed
from icm.envs.rods.rules import (ACTIONS, DEFAULT_MAX_MOVES, DEFAULT_START_CELL,
                                     ROD_NAMES, action_spec, cell_number, check_start_cell,
                                     load_topple_map, next_cell, observation_spec,
                                     standable_cells, transition_tables)


class RodEpisodes(dm_env.Environment):
    """The episode rules of the rod experiment, shared by `RodTable` (tabular) and
    `PhysicsRodTable` (simulated iCub), so both follow them by construction.

    An episode starts with the hand over `start_cell` and both rods standing. Each
    action moves the hand to the neighbouring cell (off the grid: it stays). A move
    that topples a rod ends the episode (discount 0.0, a termination) with the rod
    shown toppled; after `max_moves` moves without a topple the episode ends on a time
    limit (discount 1.0). Reward is always 0.0. A step after the end of an episode
    starts a new one.

    Subclasses say how an episode starts (`_start`) and what a move does (`_move`,
    returning the hand's cell and the rods' toppled flags).
    """

    def __init__(self, start_cell, max_moves):
        self.start_cell = check_start_cell(start_cell, standable_cells())
        self.max_moves = _validate.integer_at_least("max_moves", max_moves, 1)
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
        return dm_env.restart(self._observation(self.start_cell, [0, 0]))

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
        cell, rods = self._move(action)
        self._moves += 1
        observation = self._observation(cell, rods)
        if any(rods):
            self._reset_next_step = True
            return dm_env.termination(0.0, observation)
        if self._moves >= self.max_moves:
            self._reset_next_step = True
            return dm_env.truncation(0.0, observation, discount=1.0)
        return dm_env.transition(0.0, observation)

    def observation_spec(self):
        """The observation spec: `hand` and `rods` (see `observation_spec()`)."""
        return observation_spec()

    def action_spec(self):
        """The action spec: four moves (see `action_spec()`)."""
        return action_spec()


class RodTable(RodEpisodes):
    """The tabular rod experiment: the grid rules and the stored topple map, no physics.

    The episode rules are those of `RodEpisodes`; whether a move topples a rod is read
    from the topple map measured in physics (assets/rod_topple_map.json).

    Args:
      start_cell: (column, row) where each episode starts; must be a standable cell of
        the map. Default (0, 0), the cell nearest the robot on its left.
      max_moves: moves before an episode without a topple ends (>= 1, default 30).
      seed: None, an integer >= 0 or a `numpy.random.Generator`; accepted for
        symmetry with the other environments (the rules use no randomness).

    Raises:
      ValueError: for a start cell off the grid or where a rod stands, max_moves < 1,
        or (in `step`) an action that is not 0-3.
    """

    def __init__(self, start_cell=DEFAULT_START_CELL, max_moves=DEFAULT_MAX_MOVES, seed=None):
        super().__init__(start_cell, max_moves)
        self._map = load_topple_map()
        self._random = check_seed(seed)
        self._cell = self.start_cell

    def reseed(self, seed):
        """Checks `seed` (the rules use no randomness); the next step starts a new
        episode."""
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
        self._cell = next_cell(self._cell, action)
        rods = [int(toppled == name) for name in ROD_NAMES]
        return self._cell, rods


class RodTableBatch:
    """Many tabular rod tables at once, one per row, moving independently: the rows
    need not be in the same episode or at the same move.

    Cells are cell numbers (`icm.envs.rods.rules.cell_number`); a move returns the next
    cell and the rod toppled (0 red, 1 blue, -1 none) of each moving row, from the
    same stored map as `RodTable`.

    Args:
      n_rows: number of tables.
      start_cell: (column, row) where every episode starts.
    """

    def __init__(self, n_rows, start_cell=DEFAULT_START_CELL):
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.start = cell_number(check_start_cell(start_cell, standable_cells()))
        self.next_cell, self.topples = transition_tables()

    def new_episodes(self, rows):
        """Starts new episodes in `rows` (the tabular rules keep no state)."""

    def move(self, rows, cells, actions):
        """The moves `actions` of the tables `rows`, each from its cell in `cells`:
        returns (next cells, rods toppled), arrays like `rows`."""
        return self.next_cell[cells, actions], self.topples[cells, actions]
