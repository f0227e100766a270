"""Loading a scenario of `icm.envs.suite.SUITE` by name: its discrete environment
(`load`, the tabular twin or the simulated iCub) or its continuous dm_control task
(`load_continuous`). `icm.envs` re-exports both; the scenarios register themselves when
`icm.envs` is imported."""

import inspect

from icm import _validate
from icm.envs.suite import SUITE


def _check_kwargs(name, factory, kwargs):
    allowed = [p for p in inspect.signature(factory).parameters if p not in ("seed", "random")]
    unknown = sorted(set(kwargs) - set(allowed))
    if unknown:
        raise ValueError(f"unknown argument(s) {', '.join(unknown)} for {name!r}; "
                         f"allowed: {', '.join(allowed)}")


def load(name, physics=False, seed=None, **kwargs):
    """Loads one of the paper's environments, with its discrete actions.

    Args:
      name: "buttons" (section 2.1) or "rods" (section 2.2), or another scenario of
        `SUITE`.
      physics: False for the fast tabular twin (default), True for the simulated iCub.
      seed: None, an integer >= 0 or a `numpy.random.Generator`; the same seed gives
        the same episodes, in both versions.
      **kwargs: passed to the environment's constructor (see its docstring): for the
        buttons red_button, presses_per_trial, rewarded_box, noisy_button; for the
        rods start_cell, max_moves.

    Returns:
      A `dm_env.Environment`.

    Raises:
      ValueError: for an unknown name, a bad `physics` flag (or physics=True for a
        scenario without a physics version) or a bad keyword argument.
    """
    scenario = SUITE[SUITE.check(name)]
    physics = _validate.boolean("physics", physics)
    factory = scenario.resolve("physics") if physics else scenario.twin
    _check_kwargs(name, factory, kwargs)
    return factory(seed=seed, **kwargs)


def load_continuous(name, seed=None, **kwargs):
    """Loads the continuous dm_control task of a scenario (action: 7 arm joint targets).

    Args:
      name: "buttons" or "rods".
      seed: None, an integer >= 0 or a `numpy.random.Generator`.
      **kwargs: passed to the scenario's `load_continuous` (time_limit, in seconds,
        > 0; and task arguments).

    Returns:
      A `dm_control.rl.control.Environment`.

    Raises:
      ValueError: for an unknown name or a bad argument.
    """
    scenario = SUITE[SUITE.check(name)]
    loader = scenario.resolve("continuous")
    task_kwargs = {k: v for k, v in kwargs.items() if k != "time_limit"}
    _check_kwargs(name, scenario.resolve("task"), task_kwargs)
    return loader(seed=seed, **kwargs)
