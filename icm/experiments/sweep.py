"""Hyperparameter sweeps and studies: a grid of settings times seeds (`sweep`), or any
list of units of work (`run_units`), on this machine (joblib) or on a Dask cluster.

`run_units` is what the long studies run on (`icm.studies`): each unit is
computed by a function of the unit alone (its seeds come from its identity, never from
the order in which workers finish), every finished unit is appended to a journal, so a
study killed half-way resumes from the units it saved, and the results come back in
the order of the units, whichever backend computed them.
"""

import functools
import inspect
import itertools
import json
import os
import time

from icm import _validate
from icm.experiments.progress import progress_bar

BACKENDS = ("joblib", "dask")


def _running_client(client):
    """`client`, or the dask.distributed client already running in this process when it
    is None; a ValueError when there is none (sweep and run_units on backend "dask")."""
    from dask import distributed

    if client is None:
        try:
            client = distributed.get_client()
        except ValueError:
            raise ValueError("backend 'dask' needs a cluster: pass its client (or, to "
                             "run_units, its scheduler's address); none is running") from None
    _validate.instance("client", client, distributed.Client)
    return client


def run_point(run_fn, n_seeds, seed, fixed, point, per_seed=None):
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
    if not isinstance(rows, list) or not all(isinstance(row, dict) for row in rows):
        raise _validate.ArgumentTypeError(
            f"per_seed must return a list of one dict per seed ({result.n_seeds}), got "
            f"{_validate.show(rows)}")
    if len(rows) != result.n_seeds:
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


def _accepts_one_positional(function):
    """Whether `function` can be called with one positional argument (True when its
    signature cannot be read)."""
    try:
        inspect.signature(function).bind(None)
    except TypeError:
        return False
    except ValueError:
        return True
    return True


def _check_grid(run_fn, grid, fixed):
    """The grid with every list of values read once into a list (an iterator given as
    values is consumed here, and its values kept)."""
    if not callable(run_fn) or isinstance(run_fn, type) or not hasattr(run_fn, "__name__"):
        raise _validate.ArgumentTypeError(f"run_fn must be an experiment function such as "
                                          f"icm.experiments.run_goal_oriented, got "
                                          f"{_validate.show(run_fn)}")
    try:
        inspect.signature(run_fn).bind(n_seeds=1, seed=0, progress=False)
    except (TypeError, ValueError):
        raise _validate.ArgumentTypeError(
            f"run_fn must be an experiment function that takes n_seeds, seed and progress "
            f"(such as icm.experiments.run_goal_oriented), got "
            f"{_validate.show(run_fn)}") from None
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
        `icm.studies.robustness.goal_oriented_claims`.
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
    if per_seed is not None and (not callable(per_seed) or isinstance(per_seed, type)
                                 or inspect.isbuiltin(per_seed)
                                 or not _accepts_one_positional(per_seed)):
        raise _validate.ArgumentTypeError(
            f"per_seed must be a function you write (at module level) that takes a run's "
            f"result and returns a list of one dict per seed, such as icm.experiments."
            f"robustness.goal_oriented_claims; got {_validate.show(per_seed)}")
    _validate.n_jobs(n_jobs)
    if client is not None and backend != "dask":
        raise ValueError(f"client is used only with backend 'dask', got backend {backend!r}")
    grid = _check_grid(run_fn, grid, fixed)
    points = grid_points(grid)
    job = functools.partial(run_point, run_fn, n_seeds, seed, fixed, per_seed=per_seed)
    if backend == "joblib":
        import joblib

        results = joblib.Parallel(n_jobs=n_jobs, return_as="generator")(
            joblib.delayed(job)(point) for point in points)
        rows = [row for point_rows in progress_bar(results, len(points), "sweep", progress,
                                                   unit="point")
                for row in point_rows]
    else:
        client = _running_client(client)
        futures = client.map(job, points, pure=False)
        rows = [row for future in progress_bar(futures, len(points), "sweep", progress,
                                                unit="point")
                for row in future.result()]
    import pandas as pd  # here: pandas is slow to import

    return pd.DataFrame(rows)


def _timed(fn, unit):
    """`fn(unit)` and the CPU seconds it took in its process (module level, so that
    workers can unpickle it)."""
    start = time.process_time()
    result = fn(unit)
    return unit, result, time.process_time() - start


def _key(unit):
    """A unit as the journal and the results' dict key it: its JSON text (a tuple and
    the list the journal reads back are the same unit)."""
    return json.dumps(unit, separators=(",", ":"))


def _check_unit(unit):
    """`unit` if its JSON text reads back to itself (up to tuples and lists), else a
    TypeError: a unit is its own identity, written in the journal."""
    try:
        text = _key(unit)
    except (TypeError, ValueError):
        raise _validate.ArgumentTypeError(
            f"units must be JSON values (lists of strings and integers, say), got "
            f"{_validate.show(unit)}") from None
    if _key(json.loads(text)) != text:  # pragma: no cover (json round-trips what it wrote)
        raise ValueError(f"units: {unit!r} does not survive a JSON round trip")
    return unit


def read_journal(path, header=None):
    """The units a journal holds: {unit's JSON text: (result, cpu seconds)}. A last
    line cut short by a killed process is dropped (its unit runs again); any other
    unreadable line raises ValueError, and so does a journal whose header (its first
    line, {"header": ...}: what the units were computed with) is not `header`."""
    done = {}
    if path is None or not os.path.exists(path):
        return done
    with open(path, encoding="utf-8") as file:
        lines = file.read().split("\n")
    found = None
    for number, line in enumerate(lines, 1):
        if not line:
            continue
        try:
            record = json.loads(line)
            if number == 1 and isinstance(record, dict) and set(record) == {"header"}:
                found = record["header"]
                continue
            done[_key(record["unit"])] = (record["result"], record["cpu"])
        except (ValueError, KeyError, TypeError):
            if number == len(lines):  # no newline after it: a write cut short
                continue
            raise ValueError(f"journal {path}: line {number} is not a unit's record "
                             f"({line[:80]!r})") from None
    if (found is not None or done) and found != json.loads(json.dumps(header)):
        raise ValueError(f"journal {path} was written by a run of other settings "
                         f"({found}), not {header}: remove it to start again")
    return done


def start_journal(path, header):
    """Creates the journal `path` with its header line, unless it exists."""
    if not os.path.exists(path):
        with open(path, "w", encoding="utf-8") as file:
            file.write(json.dumps({"header": header}, separators=(",", ":")) + "\n")


def append_unit(file, unit, result, cpu):
    """Appends one finished unit to the open journal and flushes it to the disk."""
    file.write(json.dumps({"unit": unit, "result": result, "cpu": cpu},
                          separators=(",", ":")) + "\n")
    file.flush()
    os.fsync(file.fileno())


def run_units(fn, units, backend="joblib", n_jobs=-1, client=None, scheduler=None,
              progress=True, journal=None, retries=2, header=None):
    """Computes `fn(unit)` for every unit, on this machine or on a Dask cluster.

    Each unit must carry everything that decides its result, its seeds included (for
    example ("growing up", 300, 12): condition, root seed and seed index), so that the
    results do not depend on the backend, the number of workers or the order in which
    they finish. Results pass through JSON (as the journal keeps them), so that a
    unit computed now and one read back from a journal are the same.

    Args:
      fn: a module-level function (or a `functools.partial` of one) of one unit that
        returns a JSON value (dicts, lists, strings, numbers).
      units: the units, distinct JSON values (lists of strings and integers, say).
      backend: "serial" (this process, in order), "joblib" (processes on this
        machine) or "dask" (a Dask cluster: `client`, or the scheduler at
        `scheduler`, or the client already running).
      n_jobs: joblib's processes (>= 1, or -1 for one per core).
      client: a `dask.distributed.Client`, for backend "dask".
      scheduler: a Dask scheduler's address (e.g. "tcp://10.0.0.5:8786"), for
        backend "dask" without `client`.
      progress: show a progress bar over the units.
      journal: None, or a file (JSON lines) to which every finished unit is appended
        and flushed; the units it already holds are not computed again, so a run
        killed half-way continues where it stopped.
      retries: how many times Dask reruns a unit whose function raised (a unit whose
        worker died is rerun by Dask's scheduler in any case).
      header: what the units are computed with (a JSON value, e.g. the study's
        settings), written as the journal's first line; a journal of another header
        is refused, so that no run reuses units computed with other settings.

    Returns:
      (results, cpu): two lists in the order of `units`: each unit's result, and the
      CPU seconds its function took in its worker (as recorded in the journal for
      units done earlier).

    Raises:
      TypeError: for a `fn` that is not a function, or units that are not JSON values.
      ValueError: for repeated units, or a bad backend, n_jobs, client or scheduler.
    """
    if not callable(fn) or isinstance(fn, type) or not _accepts_one_positional(fn):
        raise _validate.ArgumentTypeError(f"fn must be a function of one unit, got "
                                          f"{_validate.show(fn)}")
    if isinstance(units, (str, bytes, dict)) or not hasattr(units, "__iter__"):
        raise _validate.ArgumentTypeError(f"units must be a list of units, got "
                                          f"{_validate.show(units)}")
    units = [_check_unit(u) for u in units]
    keys = [_key(u) for u in units]
    if len(set(keys)) != len(keys):
        repeated = sorted({k for k in keys if keys.count(k) > 1})
        raise ValueError(f"units must be distinct, got {repeated[:3]} more than once")
    _validate.one_of("backend", backend, ("serial",) + BACKENDS)
    n_jobs = _validate.n_jobs(n_jobs)
    _validate.boolean("progress", progress)
    _validate.integer_at_least("retries", retries, 0)
    if (client is not None or scheduler is not None) and backend != "dask":
        raise ValueError(f"client and scheduler are used only with backend 'dask', got "
                         f"backend {backend!r}")
    if client is not None and scheduler is not None:
        raise ValueError("give client or scheduler, not both")
    if scheduler is not None and not isinstance(scheduler, str):
        raise _validate.ArgumentTypeError(f"scheduler must be an address such as "
                                          f"'tcp://127.0.0.1:8786', got "
                                          f"{_validate.show(scheduler)}")
    done = read_journal(journal, header)
    todo = [u for u, k in zip(units, keys) if k not in done]
    if journal is not None:
        start_journal(journal, header)
    file = None if journal is None else open(journal, "a", encoding="utf-8")
    try:
        for unit, result, cpu in progress_bar(
                _compute(fn, todo, backend, n_jobs, client, scheduler, retries), len(todo),
                "study", progress, unit="unit"):
            result = json.loads(json.dumps(result))
            done[_key(unit)] = (result, cpu)
            if file is not None:
                append_unit(file, unit, result, cpu)
    finally:
        if file is not None:
            file.close()
    return [done[k][0] for k in keys], [done[k][1] for k in keys]


def _compute(fn, units, backend, n_jobs, client, scheduler, retries):
    """(unit, result, cpu seconds) for every unit, as they finish."""
    if not units:
        return
    job = functools.partial(_timed, fn)
    if backend == "serial":
        yield from map(job, units)
    elif backend == "joblib":
        import joblib

        yield from joblib.Parallel(n_jobs=n_jobs, return_as="generator_unordered")(
            joblib.delayed(job)(unit) for unit in units)
    else:
        from dask import distributed

        own = None
        if client is None and scheduler is not None:
            client = own = distributed.Client(scheduler)
        client = _running_client(client)
        try:
            futures = client.map(job, units, pure=False, retries=retries)
            for future in distributed.as_completed(futures):
                yield future.result()
        finally:
            if own is not None:
                own.close()
