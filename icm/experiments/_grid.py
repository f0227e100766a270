"""Many settings of one experiment as one batch: the settings' runs side by side as rows
of the batched learners, which take their settings per row.

Row block k holds setting k's seeds, with the same per-run seeds as a separate run of
that setting (every block uses the same root seed), and the rows never interact, so
block k's numbers are those of the separate run: the grid only saves the per-step
overhead of running the settings one after the other.

A run function made with `icm._settings.with_settings` takes its learner's settings
as keyword arguments; the settings a grid may vary are those its settings class
takes per row (`grid_arguments`).
"""

import dataclasses
import inspect

import numpy as np

from icm import _validate


def grid_arguments(run_fn):
    """The settings of `run_fn`'s learner that may differ between the settings of one
    grid: those the batched learner takes per row, in declaration order."""
    return tuple(name for name, spec in run_fn.settings_class.specs().items() if spec.per_row)


def check_settings_grid(grid, run_fn, arguments):
    """Checks a grid of settings of `run_fn` (decorated with `with_settings`).

    Args:
      grid: a non-empty list of dicts, each naming some of `grid_arguments(run_fn)`.
      run_fn: the run function.
      arguments: its other arguments, the same for every setting: learner settings
        (none of which a grid entry may also give), `settings` (a settings object),
        and the run's own arguments (sizes, world, seed, progress).

    Returns:
      (blocks, others, progress): one settings object per grid entry (the common
      settings with the entry's changes, each checked), the run's own arguments with
      their defaults filled in (a `seed` drawn once for all entries), and whether to
      show progress.

    Raises:
      ArgumentTypeError: if grid is not a non-empty list or tuple of dicts.
      ValueError: for a key no grid entry may vary, a key given both in an entry and
        for all, an argument `run_fn` lacks, or a setting its `Setting` refuses.
    """
    name = run_fn.__name__
    settings_cls = run_fn.settings_class
    allowed = grid_arguments(run_fn)
    arguments = dict(arguments)
    progress = _validate.boolean("progress", arguments.pop("progress", True))
    if "seed" in arguments:  # one root seed for all settings, even if drawn from entropy
        arguments["seed"] = _validate.root_seed("seed", arguments["seed"])
    if not isinstance(grid, (list, tuple)) or not grid or \
            not all(isinstance(s, dict) for s in grid):
        raise _validate.ArgumentTypeError(f"grid must be a non-empty list of dicts (one "
                                          f"setting each), got {_validate.show(grid)}")
    parameters = inspect.signature(run_fn).parameters
    for key in arguments:
        if key not in parameters:
            raise ValueError(f"{key!r} is not an argument of {name}; its arguments are "
                             f"{', '.join(p for p in parameters if p != 'progress')}")
    common = {k: arguments.pop(k) for k in list(arguments) if k in settings_cls.names()}
    base = arguments.pop("settings", None)
    if base is None:
        base = settings_cls.from_arguments(common, name)
    else:
        base = _validate.instance("settings", base, settings_cls).replace(**common)
    blocks = []
    for setting in grid:
        for key in setting:
            if key not in allowed:
                raise ValueError(f"grid settings of {name} may vary only "
                                 f"{', '.join(allowed)}; got {key!r}")
            if key in common:
                raise ValueError(f"{key!r} is given both in a grid setting and as an "
                                 f"argument for every setting")
        blocks.append(base.replace(**setting) if setting else base)
    others = {p.name: p.default for p in parameters.values()
              if p.name not in settings_cls.names() and p.name not in ("settings", "progress")}
    others.update(arguments)
    return blocks, others, progress


def split(result, settings, n_rows):
    """One result per setting from `result`, whose arrays hold the settings' blocks of
    `n_rows` rows one after the other (every array field is cut; `settings[k]`, a dict,
    replaces the settings field of result k)."""
    parts = []
    for k, setting in enumerate(settings):
        rows = slice(k * n_rows, (k + 1) * n_rows)
        changes = {f.name: getattr(result, f.name)[rows] for f in dataclasses.fields(result)
                   if isinstance(getattr(result, f.name), np.ndarray)}
        parts.append(dataclasses.replace(result, settings=setting, **changes))
    return parts
