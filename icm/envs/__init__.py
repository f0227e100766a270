"""The paper's two scenarios as dm_env environments.

`load(name, physics=False, seed=...)` gives the paper's discrete tasks: the fast
tabular twin (physics=False) or the simulated iCub (physics=True), with the same specs
and episode rules. `load_continuous(name, seed=...)` gives the underlying dm_control
tasks, whose action is the 7 arm joint targets. `as_gymnasium` wraps a discrete one
for Gymnasium; `compare_twins` checks that the two versions agree.

MuJoCo, dm_control and Gymnasium are imported only when a physics environment or the
Gymnasium adapter is first used, so that the tabular twins load in a blink.
"""

import os
import sys

if sys.platform.startswith("linux"):
    os.environ.setdefault("MUJOCO_GL", "egl")  # headless rendering, unless the user chose

from icm._settings import Names  # noqa: E402
from icm.envs.suite import SUITE  # noqa: E402
from icm.envs import buttons, rods  # noqa: E402 (each registers its scenario)
from icm.envs.loading import load, load_continuous  # noqa: E402
from icm.envs.twins import compare_twins  # noqa: E402

NAMES = Names(lambda: tuple(sorted(SUITE)))
"""Names that `load` and `load_continuous` know: the scenarios of `SUITE`."""


def as_gymnasium(env, render_mode=None):
    """Wraps a discrete environment of `load` as a `gymnasium.Env` (see
    `icm.envs.gym.GymnasiumEnv`)."""
    from icm.envs.gym import GymnasiumEnv

    return GymnasiumEnv(env, render_mode=render_mode)
