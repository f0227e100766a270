"""A Gymnasium view of the package's dm_env environments.

`as_gymnasium(env)` wraps any of the four discrete environments (buttons and rods,
tabular and physics) as a `gymnasium.Env`: the action space is `Discrete`, the
observation space a `Dict` of integer `Box` spaces built from the dm_env specs, a time limit
becomes `truncated` and a topple `terminated`, as Gymnasium distinguishes them.
"""

import gymnasium
import numpy as np
from gymnasium import spaces

from icm import _validate
from icm.envs._common import check_discrete_action


def _box(spec):
    low = np.broadcast_to(np.asarray(spec.minimum, dtype=spec.dtype), spec.shape)
    high = np.broadcast_to(np.asarray(spec.maximum, dtype=spec.dtype), spec.shape)
    return spaces.Box(low=low.copy(), high=high.copy(), shape=spec.shape, dtype=spec.dtype)


class GymnasiumEnv(gymnasium.Env):
    """A `gymnasium.Env` around one of the package's discrete dm_env environments.

    Args:
      env: the dm_env environment (from `icm.envs.load`).
      render_mode: None, or "rgb_array" for a physics environment (renders the
        "front" camera, which shows the robot and the whole scene, 480 x 640).

    Raises:
      ValueError: for an `env` that is not one of the package's discrete
        environments, a render mode other than None or "rgb_array", or "rgb_array" on
        a tabular environment (it has nothing to render).
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 25}

    def __init__(self, env, render_mode=None):
        from icm.envs.suite import SUITE

        _validate.instance("env", env, SUITE.episode_classes(),
                           "a discrete environment from icm.envs.load")
        render_mode = _validate.one_of("render_mode", render_mode, (None, "rgb_array"))
        if render_mode is not None and not hasattr(env, "physics"):
            raise ValueError("render_mode 'rgb_array' needs a physics environment "
                             "(icm.envs.load(..., physics=True))")
        self.env = env
        self.render_mode = render_mode
        self.action_space = spaces.Discrete(int(env.action_spec().num_values))
        self.observation_space = spaces.Dict(
            {name: _box(spec) for name, spec in env.observation_spec().items()})

    def _observation(self, step):
        return {name: np.asarray(value, dtype=self.observation_space[name].dtype)
                for name, value in step.observation.items()}

    def reset(self, *, seed=None, options=None):
        """Starts a new episode; with a `seed` (an integer >= 0), first reseeds the
        environment. `options` must be None or empty: the environments take none."""
        seed = _validate.seed("seed", seed)
        if options:
            raise ValueError(f"options must be None or empty (the environments take no "
                             f"reset options), got {_validate.show(options)}")
        super().reset(seed=seed)
        if seed is not None:
            self.env.reseed(seed)
        step = self.env.reset()
        return self._observation(step), {}

    def step(self, action):
        """One discrete action: returns (observation, reward, terminated, truncated,
        info).

        Raises:
          ValueError: for an action that is not an integer in 0..n-1 (floats such as
            2.0, bools and arrays of several values are refused, not converted).
          RuntimeError: after the end of an episode, until `reset()`.
        """
        action = check_discrete_action(action, int(self.action_space.n))
        step = self.env.step(action)
        if step.first():
            raise RuntimeError("the episode is over: call reset() before step()")
        terminated = bool(step.last() and step.discount == 0.0)
        truncated = bool(step.last() and not terminated)
        return self._observation(step), float(step.reward), terminated, truncated, {}

    def render(self):
        if self.render_mode == "rgb_array":
            return self.env.physics.render(480, 640, camera_id="front")
        return None
