"""The paper's two scenarios as dm_env environments: `load(name, physics=..., seed=...)`."""

from icm.envs import buttons

_TABULAR = {
    "buttons": buttons.ButtonConsole,
}
NAMES = tuple(sorted(_TABULAR))
"""Names that `load` knows."""


def load(name, physics=False, seed=None, **kwargs):
    """Loads one of the paper's environments.

    Args:
      name: "buttons" (the button experiment).
      physics: False for the fast tabular twin (the default). The simulated iCub
        (`physics=True`) is not part of this package yet.
      seed: None, an int or a `numpy.random.RandomState`; the same seed gives the same
        episodes.
      **kwargs: passed to the environment's constructor (see its docstring).

    Returns:
      A `dm_env.Environment`.

    Raises:
      ValueError: for an unknown name, a bad `physics` flag or a bad keyword argument.
    """
    if name not in _TABULAR:
        raise ValueError(f"unknown environment {name!r}; known: {', '.join(NAMES)}")
    if not isinstance(physics, bool):
        raise ValueError(f"physics must be True or False, got {physics!r}")
    if physics:
        raise ValueError(f"physics=True is not available yet for {name!r}; use physics=False")
    return _TABULAR[name](seed=seed, **kwargs)
