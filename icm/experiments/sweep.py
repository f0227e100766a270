"""Hyperparameter sweeps: a grid of settings times seeds, on this machine (joblib) or on
a Dask cluster, gathered into one pandas DataFrame."""

import functools
import inspect
import itertools

from icm import _validate
from icm.experiments._progress import progress_bar

BACKENDS = ("joblib", "dask")


def _run_point(run_fn, n_seeds, seed, fixed, point, per_seed=None):
    """Runs one grid point; returns its rows (module level, so workers can unpickle it)."""
    result = run_fn(n_seeds=n_seeds, seed=seed, progress=False, **fixed, **point)
    if per_seed is None and not callable(getattr(result, "seed_summaries", None)):
        raise _validate.ArgumentTypeError(
            f"run_fn must return a run result with seed_summaries() (as the icm.experiments "
            f"run functions do), or sweep needs per_seed; {getattr(run_fn, '__name__', run_fn)} "
            f"returned {_validate.show(result)}")
    rows = result.seed_summaries() if per_seed is None else _per_seed_rows(per_seed, result)
    return [{**point, "seed_index": i, **row} for i, row in enumerate(rows)]


def _per_seed_rows(per_seed, result):
    """The rows `per_seed` makes of `result`, checked: one dict per seed."""
    rows = per_seed(result)
    if not isinstance(rows, list) or len(rows) != result.n_seeds or \
            not all(isinstance(row, dict) for row in rows):
        raise ValueError(f"per_seed must return a list of one dict per seed "
                         f"({result.n_seeds}), got {_validate.show(rows)}")
    return rows


def grid_points(grid):
    """All combinations of a grid {name: [values]}, as a list of dicts (first name
    varies slowest)."""
    if not isinstance(grid, dict):
        raise _validate.ArgumentTypeError(f"grid must be a dict {{argument: [values]}}, got "
                                          f"{_validate.show(grid)}")
    names = list(grid)
    return [dict(zip(names, values)) for values in itertools.product(*grid.values())]


_RESERVED = ("n_seeds", "seed", "progress")


def _check_grid(run_fn, grid, fixed):
    """The grid with every list of values read once into a list (an iterator given as
    values is consumed here, and its values kept)."""
    if not callable(run_fn) or not hasattr(run_fn, "__name__"):
        raise _validate.ArgumentTypeError(f"run_fn must be an experiment function such as "
                                          f"icm.experiments.run_goal_oriented, got "
                                          f"{_validate.show(run_fn)}")
    if not isinstance(grid, dict) or not grid:
        raise _validate.ArgumentTypeError(
            f"grid must be a non-empty dict {{argument: [values]}}, got {_validate.show(grid)}")
    parameters = inspect.signature(run_fn).parameters
    allowed = [p for p in parameters if p not in _RESERVED]
    checked = {}
    for name, values in {**grid, **{k: [v] for k, v in fixed.items()}}.items():
        if name not in allowed:
            raise ValueError(f"{name!r} is not an argument a sweep can set for "
                             f"{run_fn.__name__}; allowed: {', '.join(allowed)}")
        if isinstance(values, (str, bytes, dict)) or not hasattr(values, "__iter__"):
            raise _validate.ArgumentTypeError(f"grid[{name!r}] must be a non-empty list of "
                                              f"values, got {_validate.show(values)}")
        values = list(values)
        if not values:
            raise ValueError(f"grid[{name!r}] must be a non-empty list of values, got an "
                             f"empty one")
        if name in grid:
            checked[name] = values
    return checked


def sweep(run_fn, grid, n_seeds=20, seed=0, n_jobs=1, backend="joblib", client=None,
          progress=True, per_seed=None, **fixed):
    """Runs `run_fn` at every point of `grid`, each on `n_seeds` seeds.

    Args:
      run_fn: an experiment such as `icm.experiments.run_goal_oriented`; it is called
        as ``run_fn(n_seeds=..., seed=..., progress=False, **fixed, **point)`` and its
        result must have `seed_summaries()`.
      grid: {argument name: [values]}, e.g. {"epsilon": [0.05, 0.1], "window": [3, 5]}.
      n_seeds: seeds per grid point (>= 1); every point uses the same seeds.
      seed: root seed (an integer >= 0, a Generator or None; see the run functions).
      n_jobs: parallel jobs for joblib (>= 1, or -1 for one per core).
      backend: "joblib" (processes on this machine) or "dask" (the cluster of a
        `dask.distributed.Client` you created; pass it as `client`, or it is found
        with `dask.distributed.get_client()`).
      client: the Dask client, for backend "dask".
      progress: show a progress bar over the grid points.
      per_seed: None (the run's own `seed_summaries()`), or a function that takes a
        run's result and returns one dict per seed of the numbers to keep (a
        module-level function, so that joblib and Dask workers can unpickle it), e.g.
        `icm.experiments.robustness.goal_oriented_claims`.
      **fixed: arguments of `run_fn` held fixed, e.g. ``n_trials=60``.

    Returns:
      A `pandas.DataFrame`, one row per grid point and seed: the grid values,
      `seed_index`, and the run's per-seed summary numbers (or those of `per_seed`).

    Raises:
      ValueError: for an empty or unknown grid argument, a bad n_seeds, seed, n_jobs or
        backend, a `per_seed` that is not a function (or, at the first point, does not
        return one dict per seed), or (raised by the first run that meets it) a value
        the run function refuses.
    """
    _validate.integer_at_least("n_seeds", n_seeds, 1)
    seed = _validate.root_seed("seed", seed)
    _validate.one_of("backend", backend, BACKENDS)
    _validate.boolean("progress", progress)
    _validate.function("per_seed", per_seed)
    if not _validate.is_integer(n_jobs) or (int(n_jobs) < 1 and int(n_jobs) != -1):
        allowed = "an integer >= 1, or -1 for one job per core"
        if not _validate.is_integer(n_jobs):
            raise _validate.ArgumentTypeError(f"n_jobs must be {allowed}, got {n_jobs!r}")
        raise ValueError(f"n_jobs must be {allowed}, got {n_jobs!r}")
    if client is not None and backend != "dask":
        raise ValueError(f"client is used only with backend 'dask', got backend {backend!r}")
    grid = _check_grid(run_fn, grid, fixed)
    points = grid_points(grid)
    job = functools.partial(_run_point, run_fn, n_seeds, seed, fixed, per_seed=per_seed)
    if backend == "joblib":
        import joblib

        results = joblib.Parallel(n_jobs=n_jobs, return_as="generator")(
            joblib.delayed(job)(point) for point in points)
        rows = [row for point_rows in progress_bar(results, len(points), "sweep", progress,
                                                   unit="point")
                for row in point_rows]
    else:
        from dask import distributed

        if client is None:
            try:
                client = distributed.get_client()
            except ValueError:
                raise ValueError("backend 'dask' needs a dask.distributed.Client: create one "
                                 "and pass it as client (none is running)") from None
        _validate.instance("client", client, distributed.Client)
        futures = client.map(job, points, pure=False)
        rows = [row for future in progress_bar(futures, len(points), "sweep", progress,
                                                unit="point")
                for row in future.result()]
    import pandas as pd  # here: pandas is slow to import

    return pd.DataFrame(rows)
