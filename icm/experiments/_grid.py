"""Many settings of one experiment as one batch: the settings' runs side by side as rows
of the batched learners, which take their settings per row.

Row block k holds setting k's seeds, with the same per-run seeds as a separate run of
that setting (every block uses the same root seed), and the rows never interact, so
block k's numbers are those of the separate run: the grid only saves the per-step
overhead of running the settings one after the other.
"""

import dataclasses
import inspect

import numpy as np

from icm import _validate


def defaults(run_fn):
    """The default of every argument of `run_fn`."""
    return {name: p.default for name, p in inspect.signature(run_fn).parameters.items()}


def check_grid(grid, allowed, run_fn, arguments):
    """Checks `grid` (a non-empty list of dicts whose keys are among `allowed`) and
    `arguments` (other arguments of `run_fn`, none of which a setting may also give;
    `progress` is taken out of them, and a `seed` drawn once for all settings).

    Returns:
      (full, progress): the list of every setting's full arguments (`run_fn`'s
      defaults, then `arguments`, then the setting), and whether to show progress.

    Raises:
      ArgumentTypeError: if grid is not a non-empty list or tuple of dicts.
      ValueError: for a key no setting may vary, or an argument `run_fn` lacks.
    """
    name = run_fn.__name__
    arguments = dict(arguments)
    progress = _validate.boolean("progress", arguments.pop("progress", True))
    if "seed" in arguments:  # one root seed for all settings, even if drawn from entropy
        arguments["seed"] = _validate.root_seed("seed", arguments["seed"])
    if not isinstance(grid, (list, tuple)) or not grid or \
            not all(isinstance(s, dict) for s in grid):
        raise _validate.ArgumentTypeError(f"grid must be a non-empty list of dicts (one "
                                          f"setting each), got {_validate.show(grid)}")
    base = defaults(run_fn)
    for key in arguments:
        if key not in base:
            raise ValueError(f"{key!r} is not an argument of {name}; its arguments are "
                             f"{', '.join(base)}")
    full = []
    for setting in grid:
        for key in setting:
            if key not in allowed:
                raise ValueError(f"grid settings of {name} may vary only "
                                 f"{', '.join(allowed)}; got {key!r}")
            if key in arguments:
                raise ValueError(f"{key!r} is given both in a grid setting and as an "
                                 f"argument for every setting")
        full.append({**base, **arguments, **setting})
    return full, progress


def per_row(settings, name, n_rows):
    """Setting `name` of each setting, repeated for its block of `n_rows` rows."""
    return np.repeat(np.array([s[name] for s in settings], dtype=object
                              if isinstance(settings[0][name], str) else None), n_rows)


def split(result, settings, n_rows):
    """One result per setting from `result`, whose arrays hold the settings' blocks of
    `n_rows` rows one after the other (every array field is cut; `settings` replaces
    the settings field)."""
    parts = []
    for k, setting in enumerate(settings):
        rows = slice(k * n_rows, (k + 1) * n_rows)
        changes = {f.name: getattr(result, f.name)[rows] for f in dataclasses.fields(result)
                   if isinstance(getattr(result, f.name), np.ndarray)}
        parts.append(dataclasses.replace(result, settings=setting, **changes))
    return parts
