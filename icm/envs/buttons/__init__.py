"""The button experiment of the paper (section 2.1): five lit buttons and two boxes.

A console carries 5 buttons. In every trial one button is lit red and one green; the
red one is always at the same place, the green one is drawn at random among the other
four at the start of each trial. Pressing the lit red button opens the red box, the lit
green one the green box, an unlit one nothing. Boxes close again before the next press,
so every press starts from "no box open".

One module per concept:

- `rules`: the rules, shared by both versions (`draw_green`, `press_outcome`,
  `layouts`, the noisy button);
- `twin`: the episode rules (`ButtonTrials`) and the fast tabular environment
  `ButtonConsole`, one run, or many at once (`ButtonConsoleBatch`);
- `physics`: the simulated iCub: `ButtonsPhysics`, `ButtonsTask` (continuous
  control), `load_continuous` and `PhysicsButtonConsole`, the discrete actions as
  motor primitives (imported on first use: it loads dm_control and MuJoCo);
- `movements`: `MovementLab`, movements of the arm (7 joint targets) rolled out many
  at once in C and measured (where the finger stopped, how far each cap went down),
  the environment of goal babbling (imported on first use).

Every public name of the first three is also available here, e.g. `buttons.ButtonConsole`.
"""

import importlib

from icm.envs.buttons.rules import *  # noqa: F401,F403
from icm.envs.buttons.rules import __all__ as _rules_all
from icm.envs.buttons.twin import ButtonConsole, ButtonConsoleBatch, ButtonTrials, outcome_table

_PHYSICS = ("PRESS_DEPTH", "LID_OPEN_ANGLE", "BOX_OPEN_ANGLE", "LID_OPEN_TIME",
            "ButtonsPhysics", "load_physics", "ButtonMotions", "ButtonsTask",
            "load_continuous", "PhysicsButtonConsole", "PhysicsButtonConsoleBatch")

__all__ = list(_rules_all) + ["ButtonConsole", "ButtonConsoleBatch", "ButtonTrials",
                              "outcome_table", *_PHYSICS]


def __getattr__(name):
    if name in _PHYSICS:
        return getattr(importlib.import_module("icm.envs.buttons.physics"), name)
    if name in ("rules", "twin", "physics", "movements"):
        return importlib.import_module(f"icm.envs.buttons.{name}")
    raise AttributeError(f"module 'icm.envs.buttons' has no attribute {name!r}")
