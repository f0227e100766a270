"""The rod-toppling experiment of the paper (section 2.2): a hand on a 5 x 3 grid.

The robot's right hand moves between the cells of a 5 x 3 grid over a table (actions
forward, backward, left, right; a move off the grid leaves the hand where it is). Two
rods stand on the table: the red one is toppled from many (cell, action) pairs, the
blue one from few. An episode ends when a rod topples. With `wobbly_rod=True` a third
rod stands beside the grid and falls, at random, half of the times the hand passes it.

One module per concept:

- `rules`: the grid (`next_cell`, `ACTIONS`, the start cell) and the stored topple
  map (`load_topple_map`), shared by both versions;
- `twin`: the episode rules (`RodEpisodes`) and the fast tabular environment
  `RodTable`, one run, or many at once (`RodTableBatch`);
- `physics`: the simulated iCub: `RodsPhysics`, `RodsTask` (continuous control),
  `load_continuous` and `PhysicsRodTable`, the discrete moves as arm motions
  (imported on first use: it loads dm_control and MuJoCo);
- `measure`: measuring the topple map (and the wobble map) in physics
  (`python -m icm.envs.rods`).

Every public name of these is also available here, e.g. `rods.RodTable`.
"""

import importlib

from icm.envs.rods.rules import *  # noqa: F401,F403
from icm.envs.rods.rules import __all__ as _rules_all
from icm.envs.rods.twin import RodEpisodes, RodTable, RodTableBatch

_LAZY = {"physics": ("RodsPhysics", "load_physics", "GridMotions", "RodsTask",
                     "load_continuous", "PhysicsRodTable", "PhysicsRodTableBatch"),
         "measure": ("arm_touches_a_rod", "measure_pair", "measure_topple_map",
                     "measure_wobble_map", "write_wobble_map", "main")}

__all__ = list(_rules_all) + ["RodEpisodes", "RodTable", "RodTableBatch",
                              *_LAZY["physics"], *_LAZY["measure"]]


def __getattr__(name):
    for module, names in _LAZY.items():
        if name in names:
            return getattr(importlib.import_module(f"icm.envs.rods.{module}"), name)
    if name in ("rules", "twin", "physics", "measure"):
        return importlib.import_module(f"icm.envs.rods.{name}")
    raise AttributeError(f"module 'icm.envs.rods' has no attribute {name!r}")
