"""The rules of the rod-toppling experiment, shared by the tabular twin and the physics.

The robot's right hand moves between the cells of a 5 x 3 grid over a table (actions
forward, backward, left, right; a move off the grid leaves the hand where it is, or
with `off_grid="end"` ends the episode: `OFF_GRID`). Two rods stand on the table: the
red one is toppled from many (cell, action) pairs, the blue one from few. An episode
ends when a rod topples, or after `max_moves` moves without one (`MAX_MOVES`; None:
no limit, the paper's words). Which pairs topple which rod is measured in physics
(`icm.envs.rods.measure`) and stored in assets/rod_topple_map.json
(`load_topple_map`).

The wobbly rod (`wobbly_rod=True`, a chapter beyond the paper) is a third rod that
stands off the grid, beside the line between two cells. The hand never touches it; a
move that passes beside it makes it fall with probability `WOBBLE_TOPPLE_PROBABILITY`
(1/2), whatever the robot knows: one uniform number u from the environment's
Generator per such move, toppled if u < 1/2. Which moves pass beside it is measured
in physics too, and stored in assets/rod_wobble_map.json (`load_wobble_map`). The red
and blue rods behave exactly as without it.
"""

import collections
import functools
import json

import numpy as np
from dm_env import specs

from icm import _validate
from icm._settings import Setting
from icm.store import ASSETS, asset_path
from icm.envs._common import check_discrete_action

N_COLUMNS, N_ROWS = 5, 3
"""Grid size: columns 0-4 from the robot's left to its right, rows 0-2 from the robot
outwards."""
N_CELLS = N_COLUMNS * N_ROWS
"""Cells of the grid; a cell's number is column + 5 * row (`cell_number`)."""
ACTIONS = ("forward", "backward", "left", "right")
"""Action names by index: forward is away from the robot (row + 1), left is towards
the robot's left (column - 1)."""
_MOVES = {0: (0, 1), 1: (0, -1), 2: (-1, 0), 3: (1, 0)}  # action -> (d column, d row)
ROD_NAMES = ("red", "blue")
"""Order of the rods in the `rods` observation."""
WOBBLY = "wobbly"
"""The name of the third rod, `wobbly_rod=True`: last in the `rods` observation."""
WOBBLE_TOPPLE_PROBABILITY = 0.5
"""The chance that a move beside the wobbly rod topples it."""
WOBBLE_MAP_FILE = "rod_wobble_map.json"
DEFAULT_START_CELL = (0, 0)
"""Episodes start with the hand over the cell nearest the robot on its left."""
MAX_MOVES = Setting(
    default=30, label="moves before an episode without a topple ends", kind="integer",
    low=1,
    source='the paper: "Each episode ends as soon as the robot topples one of the two '
           'rods", with no other end. The book also ends an episode after 30 moves '
           'without a topple (a time limit: the next episode starts over the start cell); '
           'None is the paper\'s reading, no limit',
    others=(None,))
"""Moves before an episode without a topple ends (a time limit; None: no limit), a
world setting the chapter "What the result depends on" measures in both readings."""
DEFAULT_MAX_MOVES = MAX_MOVES.default
"""An episode without a topple ends after this many moves (a time limit)."""
OFF_GRIDS = ("stay", "end")
"""What a move off the grid does: "stay", the hand stays where it is (the move is
spent); "end", the episode ends there, as when a rod topples (nothing follows it)."""
OFF_GRID = Setting(
    default="stay", label="a move off the grid", kind="choice", choices=OFF_GRIDS,
    source="the paper gives the grid and the four moves, not what a move off the grid "
           'does: the book leaves the hand where it is ("stay", as in the textbook '
           'grid worlds); "end" ends the episode there')
"""What a move off the grid does (`OFF_GRIDS`), a world setting the chapter "What the
result depends on" measures in both readings."""
TOPPLE_TILT = np.deg2rad(45.0)
"""A rod counts as toppled when it tilts further than this from upright."""
TOPPLE_MAP_FILE = "rod_topple_map.json"

HAND_HEIGHT = 0.04
"""Height of the fingertip above the table while it moves (the rods are 7 cm tall).
Where the cells are is read from the model: the marker geoms cell_<column>_<row>."""


def check_cell(name, cell):
    """Returns `cell` as a (column, row) tuple of ints if it is on the grid."""
    allowed = "a (column, row) pair of integers"
    if isinstance(cell, (str, bytes)) or not hasattr(cell, "__len__") or \
            np.ndim(cell) != 1 or len(cell) != 2 or \
            not all(_validate.is_integer(v) for v in cell):
        raise _validate.ArgumentTypeError(f"{name} must be {allowed}, got "
                                          f"{_validate.show(cell)}")
    column, row = (int(v) for v in cell)
    if not (0 <= column < N_COLUMNS and 0 <= row < N_ROWS):
        raise ValueError(f"{name} must be on the {N_COLUMNS} x {N_ROWS} grid (column 0-4, "
                         f"row 0-2), got {cell!r}")
    return column, row


def cell_number(cell):
    """The number of a (column, row) cell: column + 5 * row (the Q-learner's state)."""
    column, row = check_cell("cell", cell)
    return column + N_COLUMNS * row


def number_cell(number):
    """The (column, row) cell of a cell number (see `cell_number`)."""
    number = _validate.integer("number", number, 0, N_CELLS - 1)
    return number % N_COLUMNS, number // N_COLUMNS


def check_max_moves(max_moves):
    """`max_moves` if it is None (no limit) or an integer >= 1, else raises."""
    if max_moves is None:
        return None
    return _validate.integer_at_least("max_moves", max_moves, 1)


def check_off_grid(off_grid):
    """`off_grid` if it is one of `OFF_GRIDS`, else raises."""
    return OFF_GRID.check(off_grid, "off_grid")


def leaves_grid(cell, action):
    """Whether `action` from `cell` would take the hand off the grid."""
    cell = check_cell("cell", cell)
    dc, dr = _MOVES[check_discrete_action(action, len(ACTIONS))]
    return not (0 <= cell[0] + dc < N_COLUMNS and 0 <= cell[1] + dr < N_ROWS)


def next_cell(cell, action):
    """The cell the hand ends in after `action` from `cell` (off the grid: stays)."""
    cell = check_cell("cell", cell)
    dc, dr = _MOVES[check_discrete_action(action, len(ACTIONS))]
    column, row = cell[0] + dc, cell[1] + dr
    if 0 <= column < N_COLUMNS and 0 <= row < N_ROWS:
        return column, row
    return tuple(cell)


def rod_names(wobbly_rod=False):
    """The rods of the scene, in the order of the `rods` observation: red, blue, and
    with `wobbly_rod` the wobbly one."""
    return ROD_NAMES + ((WOBBLY,) if _validate.boolean("wobbly_rod", wobbly_rod) else ())


def observation_spec(wobbly_rod=False):
    """The observation spec shared by the tabular and the physics rod environments
    (`rods` has a third entry with the wobbly rod)."""
    n_rods = len(rod_names(wobbly_rod))
    return collections.OrderedDict(
        hand=specs.BoundedArray((2,), np.int64, [0, 0], [N_COLUMNS - 1, N_ROWS - 1],
                                name="hand"),
        rods=specs.BoundedArray((n_rods,), np.int64, 0, 1, name="rods"),
    )


def action_spec():
    """Four discrete moves: 0 forward, 1 backward, 2 left, 3 right."""
    return specs.DiscreteArray(len(ACTIONS), dtype=np.int64, name="move")


@functools.lru_cache(maxsize=4)
def _read_topple_map(text):
    return json.loads(text)


def load_topple_map():
    """The stored topple map (assets/rod_topple_map.json), as a new dict.

    Returns:
      {"standable": set of cells where the hand can rest with both rods standing,
       "topples": {(cell, action): "red" | "blue" | None} for every standable cell}.
    """
    data = _read_topple_map(asset_path(TOPPLE_MAP_FILE).read_text())
    topples = {(tuple(entry["cell"]), entry["action"]): entry["topples"]
               for entry in data["pairs"]}
    return {"standable": {tuple(c) for c in data["standable"]}, "topples": topples}


def load_wobble_map():
    """The (cell, action) pairs whose move passes beside the wobbly rod, as measured in
    physics (assets/rod_wobble_map.json): a set of ((column, row), action). None of
    them topples the red or the blue rod."""
    data = _read_topple_map(asset_path(WOBBLE_MAP_FILE).read_text())
    return {(tuple(pair["cell"]), pair["action"]) for pair in data["pairs"] if pair["wobbles"]}


def wobble_table():
    """The wobble map as a bool array [cell number, action] (True: the move passes
    beside the wobbly rod), for the batched twin."""
    table = np.zeros((N_CELLS, len(ACTIONS)), dtype=bool)
    for cell, action in load_wobble_map():
        table[cell_number(cell), action] = True
    return table


def standable_cells():
    """The standable cells of the stored map; every cell if no map is stored yet (when
    `python -m icm.envs.rods` measures the first one)."""
    if not (ASSETS / TOPPLE_MAP_FILE).exists():
        return {(c, r) for c in range(N_COLUMNS) for r in range(N_ROWS)}
    return load_topple_map()["standable"]


def describe_moves(pairs):
    """(cell, action) pairs in words, in cell order: e.g. "forward from cell (0, 1) or
    backward from cell (0, 2)"."""
    words = []
    for cell, action in sorted(pairs, key=lambda pair: (pair[0][::-1], pair[1])):
        column, row = check_cell("cell", cell)
        words.append(f"{ACTIONS[check_discrete_action(action, len(ACTIONS))]} from cell "
                     f"({column}, {row})")
    if not words:
        raise ValueError("pairs must hold at least one (cell, action) pair, got none")
    return ", ".join(words[:-1]) + (" or " if len(words) > 1 else "") + words[-1]


def topple_counts(topple_map):
    """How many (cell, action) pairs topple each rod: {"red": n, "blue": m}."""
    values = list(topple_map["topples"].values())
    return {name: values.count(name) for name in ROD_NAMES}


def check_start_cell(start_cell, standable):
    """Returns `start_cell` if it is on the grid and the hand can rest there."""
    cell = check_cell("start_cell", start_cell)
    if cell not in standable:
        raise ValueError(f"start_cell {cell} is where a rod stands or the arm would touch one; "
                         f"allowed: {sorted(standable)}")
    return cell


def transition_tables(topple_map=None):
    """The grid and the topple map as arrays over cell numbers, for the batched twin:
    next_cell [cell, action] (a cell number) and topples [cell, action] (0 red, 1 blue,
    -1 none; -1 too on the cells the hand never rests on)."""
    topple_map = load_topple_map() if topple_map is None else topple_map
    nxt = np.zeros((N_CELLS, len(ACTIONS)), dtype=np.int64)
    topples = np.full((N_CELLS, len(ACTIONS)), -1, dtype=np.int64)
    for number in range(N_CELLS):
        cell = number_cell(number)
        for action in range(len(ACTIONS)):
            nxt[number, action] = cell_number(next_cell(cell, action))
            rod = topple_map["topples"].get((cell, action))
            if rod is not None:
                topples[number, action] = ROD_NAMES.index(rod)
    return nxt, topples


__all__ = ["N_COLUMNS", "N_ROWS", "N_CELLS", "ACTIONS", "ROD_NAMES", "DEFAULT_START_CELL",
           "MAX_MOVES", "DEFAULT_MAX_MOVES", "OFF_GRIDS", "OFF_GRID", "check_max_moves",
           "check_off_grid", "leaves_grid", "describe_moves", "TOPPLE_TILT", "TOPPLE_MAP_FILE", "HAND_HEIGHT", "WOBBLY",
           "WOBBLE_TOPPLE_PROBABILITY", "WOBBLE_MAP_FILE", "check_cell", "cell_number",
           "number_cell", "next_cell", "rod_names", "observation_spec", "action_spec",
           "load_topple_map", "load_wobble_map", "wobble_table", "standable_cells",
           "topple_counts", "check_start_cell", "transition_tables"]
