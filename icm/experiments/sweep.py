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


def _attempts(fn, retries, unit):
    """`fn(unit)`, tried up to 1 + `retries` times while it raises: (unit, result, CPU
    seconds of all the attempts in this process, the last error in words or None,
    attempts made). Module level, so that workers can unpickle it."""
    cpu, failure = 0.0, None
    for attempt in range(1, retries + 2):
        start = time.process_time()
        try:
            result = fn(unit)
        except Exception as error:  # (any: it is reported with its unit, never lost)
            cpu += time.process_time() - start
            failure = f"{type(error).__name__}: {error}".splitlines()[0]
            continue
        return unit, result, cpu + time.process_time() - start, None, attempt
    return unit, None, cpu, failure, retries + 1


class UnitError(RuntimeError):
    """Units whose function raised on every attempt (`run_units`): the message names
    the first, its attempts and its error; the units that finished are in the journal.

    Attributes:
      failures: [(unit, attempts, error in words)], in the order they failed.
    """

    def __init__(self, failures, finished, journal):
        self.failures = failures
        unit, attempts, error = failures[0]
        more = f"; {len(failures) - 1} other unit(s) failed too" if len(failures) > 1 else ""
        kept = (f"; the {finished} unit(s) that finished are kept in the journal "
                f"{journal}, run again to compute the rest" if journal is not None else "")
        super().__init__(f"unit {_key(unit)} failed {attempts} time(s) ({error}){more}{kept}")


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


JOURNAL_BYTES = 2 ** 30
"""The largest journal read back (a robustness study's rows of 1,000 seeds a point take
tens of MiB)."""


def _difference(found, header):
    """In words, the first setting in which a journal's header differs from this
    run's."""
    if isinstance(found, dict) and isinstance(header, dict):
        for key in list(header) + [k for k in found if k not in header]:
            if key not in found:
                return f"it has no {key}, this run's is {header[key]!r}"
            if key not in header:
                return f"its {key} is {found[key]!r}, this run has none"
            if found[key] != header[key]:
                return f"its {key} is {found[key]!r}, this run's {header[key]!r}"
    return f"its header is {found!r}, this run's {header!r}"


def read_journal(path, header=None, units=None):
    """The units a journal holds: {unit's JSON text: (result, cpu seconds)}.

    Each line is read through `icm.records` (`JournalHeader` for the first,
    `JournalRecord` for the others: a unit, its result, its CPU seconds, and the
    result's SHA-256 as written). A last line cut short (no newline after it: a process
    killed while writing) is the one damage forgiven: it is left out and its unit runs
    again (`run_units` cuts it off the file). Anything else is refused.

    Args:
      path: the journal (None, or a file that does not exist: no units).
      header: what this run's units are computed with (a JSON value): the journal's
        header must be the same.
      units: None, or this run's units: a journal's unit must be one of them.

    Returns:
      The dict of units done.

    Raises:
      icm.records.RecordError: for a line that is not a record (a result changed since
        it was written, a bare number for a record, an empty line, a unit repeated or
        not of this run), naming the file and the line.
      ValueError: for a journal whose header is not `header`, naming the first setting
        that differs.
    """
    from icm import records

    done = {}
    if path is None or not os.path.lexists(path):
        return done
    data = records.read_bytes(path, limit=JOURNAL_BYTES, follow=False)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise records.RecordError(f"journal {path}: not UTF-8 text (byte {error.start})") \
            from None
    lines = text.split("\n")[:-1]  # (what follows the last newline is cut short)
    if not lines:
        return done
    where = f"journal {path}, line 1"
    found = records.parse_json(lines[0], records.JournalHeader, where).header
    expected = json.loads(json.dumps(header))
    if found != expected:
        raise ValueError(f"journal {path} was written by a run of other settings "
                         f"({_difference(found, expected)}): remove it to start again, "
                         f"or run with its settings")
    allowed = None if units is None else {_key(u) for u in units}
    first_line = {}
    for number, line in enumerate(lines[1:], 2):
        where = f"journal {path}, line {number}"
        if not line.strip():
            raise records.RecordError(f"{where}: empty, not a unit's record")
        record = records.parse_json(line, records.JournalRecord, where)
        key = _key(record.unit)
        if allowed is not None and key not in allowed:
            raise records.RecordError(f"{where}: the unit {key} is not one of this run's")
        if key in first_line:
            raise records.RecordError(f"{where}: the unit {key} is on line "
                                      f"{first_line[key]} already")
        first_line[key] = number
        done[key] = (record.result, record.cpu)
    return done


def _cut_short_line_removed(path):
    """Cuts off a journal's last line if a killed write left it without its newline
    (the file then ends at its last complete line); returns whether it did."""
    if path is None or not os.path.isfile(path):
        return False
    with open(path, "rb+") as file:
        data = file.read()
        if not data or data.endswith(b"\n"):
            return False
        file.truncate(data.rfind(b"\n") + 1)
        file.flush()
        os.fsync(file.fileno())
    return True


def start_journal(path, header):
    """Creates the journal `path` with its header line, unless it has one."""
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        with open(path, "w", encoding="utf-8") as file:
            file.write(json.dumps({"header": header}, separators=(",", ":")) + "\n")
            file.flush()
            os.fsync(file.fileno())


def append_unit(file, unit, result, cpu):
    """Appends one finished unit to the open journal (with its result's SHA-256,
    `icm.records.json_digest`) and flushes it to the disk."""
    from icm import records

    file.write(json.dumps({"unit": unit, "result": result, "cpu": cpu,
                           "sha256": records.json_digest(result)},
                          separators=(",", ":")) + "\n")
    file.flush()
    os.fsync(file.fileno())


SCHEDULER_SECONDS = 5
"""How long `run_units` waits for a Dask scheduler to answer before it gives up."""


def connect(scheduler, timeout=None):
    """A `dask.distributed.Client` of the scheduler at `scheduler`, or a ValueError
    naming the address if none answers within `timeout` seconds.

    Args:
      scheduler: the address, e.g. "tcp://10.0.0.5:8786".
      timeout: seconds to wait (None: `SCHEDULER_SECONDS`).

    Returns:
      The client (close it when done).

    Raises:
      ValueError: for an address that is not one, or a scheduler that does not answer.
    """
    from dask import distributed

    if not isinstance(scheduler, str):
        raise _validate.ArgumentTypeError(f"scheduler must be an address such as "
                                          f"'tcp://127.0.0.1:8786', got "
                                          f"{_validate.show(scheduler)}")
    timeout = SCHEDULER_SECONDS if timeout is None else _validate.real(
        "timeout", timeout, 0, low_open=True)
    try:
        return distributed.Client(scheduler, timeout=timeout)
    except (OSError, TimeoutError) as error:
        raise ValueError(f"scheduler: no Dask scheduler answered at {scheduler} within "
                         f"{timeout:g} s ({type(error).__name__})") from None
    except (ValueError, TypeError) as error:
        raise ValueError(f"scheduler: {scheduler!r} is not a Dask scheduler's address "
                         f"({error})") from None


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
        backend "dask" without `client`; one that does not answer within
        `SCHEDULER_SECONDS` is refused (`connect`).
      progress: show a progress bar over the units.
      journal: None, or a file (JSON lines, `read_journal`) to which every finished
        unit is appended and flushed as it finishes; the units it already holds are
        not computed again, so a run killed half-way continues where it stopped.
      retries: how many more times a unit whose function raised is tried, on every
        backend (in the worker that ran it; a unit whose Dask worker died is rerun by
        Dask's scheduler in any case).
      header: what the units are computed with (a JSON value, e.g. the study's
        settings), written as the journal's first line; a journal of another header
        is refused, so that no run reuses units computed with other settings.

    Returns:
      (results, cpu): two lists in the order of `units`: each unit's result, and the
      CPU seconds its function took in its worker, its failed attempts included (as
      recorded in the journal for units done earlier).

    Raises:
      TypeError: for a `fn` that is not a function, or units that are not JSON values.
      ValueError: for repeated units, a bad backend, n_jobs, client or scheduler, or a
        journal refused (`read_journal`).
      UnitError: when units failed on every attempt: after every other unit is
        computed and journaled, naming the first failed unit and its error.
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
    retries = _validate.integer_at_least("retries", retries, 0)
    if (client is not None or scheduler is not None) and backend != "dask":
        raise ValueError(f"client and scheduler are used only with backend 'dask', got "
                         f"backend {backend!r}")
    if client is not None and scheduler is not None:
        raise ValueError("give client or scheduler, not both")
    if scheduler is not None and not isinstance(scheduler, str):
        raise _validate.ArgumentTypeError(f"scheduler must be an address such as "
                                          f"'tcp://127.0.0.1:8786', got "
                                          f"{_validate.show(scheduler)}")
    done = read_journal(journal, header, units)
    todo = [u for u, k in zip(units, keys) if k not in done]
    own = connect(scheduler) if todo and scheduler is not None else None
    failures = []
    try:
        if journal is not None:
            _cut_short_line_removed(journal)
            start_journal(journal, header)
        file = None if journal is None else open(journal, "a", encoding="utf-8")
        try:
            for unit, result, cpu, failure, attempts in progress_bar(
                    _compute(fn, todo, backend, n_jobs, own or client, retries), len(todo),
                    "study", progress, unit="unit"):
                if failure is not None:
                    failures.append((unit, attempts, failure))
                    continue
                result = json.loads(json.dumps(result))
                done[_key(unit)] = (result, cpu)
                if file is not None:
                    append_unit(file, unit, result, cpu)
        finally:
            if file is not None:
                file.close()
    finally:
        if own is not None:
            own.close()
    if failures:
        raise UnitError(failures, len(done), journal)
    return [done[k][0] for k in keys], [done[k][1] for k in keys]


def _compute(fn, units, backend, n_jobs, client, retries):
    """(unit, result, cpu seconds, error or None, attempts) for every unit, as they
    finish (`_attempts`)."""
    if not units:
        return
    job = functools.partial(_attempts, fn, retries)
    if backend == "serial":
        yield from map(job, units)
    elif backend == "joblib":
        import joblib

        yield from joblib.Parallel(n_jobs=n_jobs, return_as="generator_unordered")(
            joblib.delayed(job)(unit) for unit in units)
    else:
        from dask import distributed

        client = _running_client(client)
        futures = client.map(job, units, pure=False)
        for future in distributed.as_completed(futures):
            yield future.result()
