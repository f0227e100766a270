"""Checks that a tabular twin and its physics version behave the same."""

import numpy as np

from icm import _validate
from icm.envs.loading import load


def compare_twins(name, n_steps=200, seed=0, action_seed=0, twin_seed=None, **kwargs):
    """Plays the same random actions in the tabular and the physics version of `name`.

    Args:
      name: "buttons" or "rods".
      n_steps: number of steps (actions) to play (>= 1).
      seed: the seed of both environments (an integer >= 0).
      action_seed: the seed of the random actions (None, an integer >= 0 or a
        Generator).
      twin_seed: a different seed (integer >= 0) for the tabular twin only (to see
        the comparison fail); default `seed`.
      **kwargs: environment arguments, given to both.

    Returns:
      A dict: "steps" (steps compared), "mismatches" (steps whose step type,
      discount, reward or observation differ), "episodes" (episodes begun),
      "terminations" (episodes that ended with discount 0), "ended" (episodes that
      ended, by a termination or a time limit) and "acted" (steps whose action was
      carried out: every step but those that began an episode, since dm_env's first
      step after an episode's end starts the next one and ignores its action).
    """
    _validate.integer_at_least("n_steps", n_steps, 1)
    _validate.integer("seed", seed, 0, _validate.MAX_SEED)
    if twin_seed is not None:
        _validate.integer("twin_seed", twin_seed, 0, _validate.MAX_SEED)
    action_random = _validate.generator("action_seed", action_seed)
    physics_env = load(name, physics=True, seed=seed, **kwargs)
    tabular_env = load(name, physics=False,
                            seed=seed if twin_seed is None else twin_seed, **kwargs)
    actions = action_random.integers(physics_env.action_spec().num_values, size=n_steps)
    physics_env.reset(), tabular_env.reset()
    counts = {"steps": 0, "mismatches": 0, "episodes": 1, "terminations": 0, "ended": 0,
              "acted": 0}
    for action in actions:
        a, b = physics_env.step(action), tabular_env.step(action)
        same = (a.step_type == b.step_type and a.discount == b.discount
                and (a.reward or 0.0) == (b.reward or 0.0)
                and all(np.array_equal(a.observation[k], b.observation[k])
                        for k in a.observation))
        counts["steps"] += 1
        counts["mismatches"] += not same
        counts["episodes"] += int(a.first())
        counts["acted"] += int(not a.first())
        counts["ended"] += int(a.last())
        counts["terminations"] += int(a.last() and a.discount == 0.0)
    return counts
