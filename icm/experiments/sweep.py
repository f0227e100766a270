"""Hyperparameter sweeps: a grid of settings times seeds, on this machine (joblib) or on
a Dask cluster, gathered into one pandas DataFrame."""

import functools
import inspect
import itertools

import pandas as pd

from icm import _validate
from icm.experiments._progress import progress_bar

BACKENDS = ("joblib", "dask")


def _run_point(run_fn, n_seeds, seed, fixed, point):
    """Runs one grid point; returns its rows (module level, so workers can unpickle it)."""
    result = run_fn(n_seeds=n_seeds, seed=seed, progress=False, **fixed, **point)
    return [{**point, "seed_index": i, **row}
            for i, row in enumerate(result.seed_summaries())]


def grid_points(grid):
    """All combinations of a grid {name: [values]}, as a list of dicts (first name
    varies slowest)."""
    names = list(grid)
    return [dict(zip(names, values)) for values in itertools.product(*grid.values())]


def _check_grid(run_fn, grid, fixed):
    if not isinstance(grid, dict) or not grid:
        raise ValueError(f"grid must be a non-empty dict {{argument: [values]}}, got {grid!r}")
    parameters = inspect.signature(run_fn).parameters
    for name, values in {**grid, **{k: [v] for k, v in fixed.items()}}.items():
        if name not in parameters or name in ("n_seeds", "seed", "progress"):
            allowed = [p for p in parameters if p not in ("n_seeds", "seed", "progress")]
            raise ValueError(f"{name!r} is not an argument a sweep can set for "
                             f"{run_fn.__name__}; allowed: {', '.join(allowed)}")
        if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__") or \
                len(list(values)) == 0:
            raise ValueError(f"grid[{name!r}] must be a non-empty list of values, got {values!r}")


def sweep(run_fn, grid, n_seeds=20, seed=0, n_jobs=1, backend="joblib", client=None,
          progress=True, **fixed):
    """Runs `run_fn` at every point of `grid`, each on `n_seeds` seeds.

    Args:
      run_fn: an experiment such as `icm.experiments.run_goal_oriented`; it is called
        as ``run_fn(n_seeds=..., seed=..., progress=False, **fixed, **point)`` and its
        result must have `seed_summaries()`.
      grid: {argument name: [values]}, e.g. {"epsilon": [0.05, 0.1], "window": [3, 5]}.
      n_seeds: seeds per grid point (>= 1); every point uses the same seeds.
      seed: root seed (>= 0).
      n_jobs: parallel jobs for joblib (>= 1, or -1 for one per core).
      backend: "joblib" (processes on this machine) or "dask" (the cluster of a
        `dask.distributed.Client` you created; pass it as `client`, or it is found
        with `dask.distributed.get_client()`).
      client: the Dask client, for backend "dask".
      progress: show a progress bar over the grid points.
      **fixed: arguments of `run_fn` held fixed, e.g. ``n_trials=60``.

    Returns:
      A `pandas.DataFrame`, one row per grid point and seed: the grid values,
      `seed_index`, and the run's per-seed summary numbers.

    Raises:
      ValueError: for an empty or unknown grid argument, a bad n_seeds, seed, n_jobs or
        backend, or (raised by the first run that meets it) a value the run function
        refuses.
    """
    _validate.integer_at_least("n_seeds", n_seeds, 1)
    _validate.integer_at_least("seed", seed, 0)
    _validate.one_of("backend", backend, BACKENDS)
    if n_jobs != -1:
        _validate.integer_at_least("n_jobs", n_jobs, 1)
    _check_grid(run_fn, grid, fixed)
    points = grid_points(grid)
    job = functools.partial(_run_point, run_fn, n_seeds, seed, fixed)
    if backend == "joblib":
        import joblib

        results = joblib.Parallel(n_jobs=n_jobs, return_as="generator")(
            joblib.delayed(job)(point) for point in points)
        rows = [row for point_rows in progress_bar(results, len(points), "sweep", progress,
                                                   unit="point")
                for row in point_rows]
    else:
        from dask import distributed

        client = distributed.get_client() if client is None else client
        futures = client.map(job, points, pure=False)
        rows = [row for future in progress_bar(futures, len(points), "sweep", progress,
                                                unit="point")
                for row in future.result()]
    return pd.DataFrame(rows)
