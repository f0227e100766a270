"""The engine of the long studies: it runs a registered study (`icm.studies.registry.
STUDIES`) unit by unit on the sweep engine (`icm.experiments.sweep.run_units`: on every
core of this machine with joblib, or on a Dask cluster, with the same numbers either
way) and writes its file.

Every finished unit is appended to a journal beside the output file, so a study killed
half-way (Ctrl-C or SIGKILL) continues from the units it saved and writes the same
file; the file is written at the end, atomically (`icm.store.write_text`). It records
what produced it under "produced_by" (`icm.store.provenance`): the study, the command,
its settings, the versions of Python, icm, NumPy and MuJoCo, the seeds, and the units.
How long the run took (which depends on the machine, not on the numbers) goes to a
sibling file, ``<out>.runs.jsonl``, one line per run, so that the study's own file is
byte-identical between a serial run, joblib and a Dask cluster.

From the command line: ``python -m icm study NAME --seeds N --backend joblib|dask
[--scheduler ADDRESS] --out FILE`` (see `icm.cli`).
"""

import functools
import json
import os
import pathlib
import time

from icm import _validate, files, records, store
from icm.experiments.sweep import append_unit, read_journal, run_units, start_journal
from icm.studies.registry import DEFAULT_UNIT_SECONDS, SEEDS, SIZE_MAX, STUDIES

MAX_CPU_HOURS = 4.0
"""The longest run (estimated CPU-hours, `estimate`) a study starts without being told
that it is meant (`long_run=True`, ``--confirm-long-run``): the 80-seed remedies study,
the longest the chapters read, took 1.2."""


def _sizes(name, seeds, options):
    """Study `name`'s sizes as given: {"seeds": ..., option: value}, defaults filled in,
    each checked against its range (before the study's own `check`)."""
    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    unknown = sorted(set(options) - set(study.options) - {"imported_seeds"})
    if unknown:
        raise ValueError(f"{unknown[0]!r} is not an option of study {name!r}; allowed: "
                         f"{', '.join(study.options) or 'none'}")
    sizes = {"seeds": _validate.integer("seeds", study.seeds[0] if seeds is None else seeds,
                                        *SEEDS)}
    for option, (default, minimum, _) in study.options.items():
        value = options.get(option)
        sizes[option] = _validate.integer(option, default if value is None else value,
                                          minimum, SIZE_MAX)
    if options.get("imported_seeds"):
        sizes["imported_seeds"] = _validate.integer("imported_seeds",
                                                    options["imported_seeds"], 1,
                                                    SEEDS[1])
    return sizes


def check_settings(name, seeds=None, **options):
    """The full settings of study `name`: {"seeds": ..., option: value}, defaults
    filled in, each checked (ValueError naming the bad one): seeds within
    `registry.SEEDS`, every other size option from its least value (`Study.options`) to
    `registry.SIZE_MAX`, then the study's own `check`."""
    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    settings = _sizes(name, seeds, options)
    return study.check(settings) if study.check else settings


def journal_of(out):
    """The journal beside the output file `out`: ``<out>.journal``."""
    return pathlib.Path(str(out) + ".journal")


def run_log_of(out):
    """The run log beside the output file `out`: ``<out>.runs.jsonl``."""
    return pathlib.Path(str(out) + ".runs.jsonl")


def journal_header(name, settings):
    """A study's journal's header: the study's name and its settings (a journal of
    another study, or of other settings, is refused by name)."""
    return {"study": name, **settings}


def is_study_file(path, name):
    """Whether `path` is a file of study `name`: JSON whose "produced_by" names it
    (`icm.records.StudyFileStamp`).

    Args:
      path: the file.
      name: the study's name.

    Returns:
      True or False (for a file that cannot be read, or is not such JSON).
    """
    try:
        return records.read_json(path, records.StudyFileStamp).produced_by.study == name
    except records.RecordError:
        return False


def is_journal(path):
    """Whether `path` is a study's journal (its first line a `records.JournalHeader`,
    or cut short while being written) or an empty file (a journal just created).

    Args:
      path: the file.

    Returns:
      True or False.
    """
    try:
        data = records.read_bytes(path, limit=2 ** 30, follow=False)
    except records.RecordError:
        return False
    first, newline, _ = data.partition(b"\n")
    if not newline:  # (empty, or the header cut short)
        return first == b"" or first.startswith(b'{"header":')
    try:
        records.parse_json(first, records.JournalHeader, str(path))
    except records.RecordError:
        return False
    return True


def _run_log_lines(path):
    """The lines of a run log, each read as a `records.RunLogLine` (RecordError naming
    the file and the line)."""
    text = records.read_text(path, limit=2 ** 26)
    return [records.parse_json(line, records.RunLogLine, f"{path}, line {number}")
            for number, line in enumerate(text.splitlines(), 1) if line.strip()]


def is_run_log(path):
    """Whether `path` is a study's run log: each line a `records.RunLogLine`.

    Args:
      path: the file.

    Returns:
      True or False.
    """
    try:
        return bool(_run_log_lines(path))
    except records.RecordError:
        return False


def check_destinations(name, out, force=False, inputs=(), what="out"):
    """Refuses, before any work, an output file of study `name` that the engine must
    not write, and the same for its journal and run log (`icm.files.check_file`): a
    folder, a symbolic link, a path in a folder that does not exist or is read-only, a
    path that is one of `inputs` or lies inside one, or an existing file the engine did
    not write (a study file whose "produced_by" names another study, or none; a journal
    or run log that is not one), unless `force`.

    Args:
      name: the study's name.
      out: the file to write.
      force: replace an existing file that the engine did not write.
      inputs: the run's input files (e.g. the file whose seeds are imported).
      what: how messages name `out` (e.g. "--out").

    Returns:
      `out`, a `pathlib.Path`.

    Raises:
      icm.files.DestinationError: naming the refused path and why.
    """
    _validate.one_of("name", name, tuple(STUDIES))
    if not isinstance(out, (str, os.PathLike)):
        raise _validate.ArgumentTypeError(f"{what} must be a file path, got "
                                          f"{_validate.show(out)}")
    force = _validate.boolean("force", force)
    out = pathlib.Path(out)
    if not out.parent.is_dir():
        raise files.DestinationError(f"{what} {out}: the folder {out.parent} does not "
                                     f"exist")
    inputs = [pathlib.Path(i) for i in inputs]
    files.check_file(out, own=functools.partial(is_study_file, name=name), force=force,
                     inputs=inputs, what=what)
    files.check_file(journal_of(out), own=is_journal, force=force, inputs=inputs,
                     what=f"{what}'s journal")
    files.check_file(run_log_of(out), own=is_run_log, force=force, inputs=inputs,
                     what=f"{what}'s run log")
    return out


def _measured(name, settings, out):
    """(settings, mean CPU seconds a unit, when) of the last run of study `name`
    recorded in the run log beside `out` whose settings are this run's but for the
    seeds (a run of other rollouts or trials, whose fixed costs weigh otherwise, is not
    used), or None."""
    log = None if out is None else run_log_of(out)
    if log is None or not log.is_file() or log.is_symlink():
        return None
    try:
        lines = _run_log_lines(log)
    except records.RecordError:
        return None
    def sizes(options):
        return {k: v for k, v in options.items() if k not in ("seeds", "imported_seeds")}

    for line in reversed(lines):
        if line.study in (None, name) and sizes(line.settings) == sizes(settings) \
                and any(c > 0 for c in line.unit_cpu_seconds):
            cpu = [c for c in line.unit_cpu_seconds if c > 0]  # (not those imported)
            return line.settings, sum(cpu) / len(cpu), line.started
    return None


def _modelled(study, settings, units):
    """The study's rough figure of the CPU seconds of `units`."""
    if study.unit_seconds is None:
        return DEFAULT_UNIT_SECONDS * len(units)
    return sum(study.unit_seconds(settings, unit) for unit in units)


def estimate(name, settings, out=None, done=()):
    """A rough estimate of the CPU seconds a run of study `name` takes, from the study's
    own figure (`Study.unit_seconds`, or `registry.DEFAULT_UNIT_SECONDS` a unit),
    scaled to the last run of the same options recorded beside `out` when there is
    one with the same settings but for the seeds (its units' mean CPU seconds), over
    the units not yet done (those of `out`'s
    journal, when it is of these settings, and `done`).

    Args:
      name: the study's name.
      settings: its settings (`check_settings`).
      out: None, or the file the run writes.
      done: units done already (e.g. those imported from an earlier file).

    Returns:
      (CPU seconds, units to compute, what the figure rests on, in words).
    """
    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    units = study.units(settings)
    skip = {json.dumps(u) for u in done}
    if out is not None:
        try:
            skip |= {json.dumps(json.loads(k)) for k in read_journal(
                journal_of(out), journal_header(name, settings), units)}
        except (ValueError, OSError):
            pass  # (the run itself refuses it)
    todo = [u for u in units if json.dumps(u) not in skip]
    seconds = _modelled(study, settings, todo)
    basis = ("the study's own rough figure" if study.unit_seconds is not None else
             f"a rough {DEFAULT_UNIT_SECONDS:g} CPU-seconds a unit (the study states none)")
    measured = _measured(name, settings, out)
    if measured is not None:
        old, per_unit, when = measured
        try:
            old_units = study.units(old)
            figure = _modelled(study, old, old_units) / len(old_units)
        except (KeyError, TypeError, ValueError, ZeroDivisionError):
            figure = 0
        if figure > 0:
            seconds *= per_unit / figure
            basis = (f"scaled to the run of {when} in {run_log_of(out).name} "
                     f"({per_unit:.2g} CPU-seconds a unit)")
    return seconds, len(todo), basis


def duration(seconds):
    """A duration in words: "40 s", "12 min", "3.5 h"."""
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def check_run_length(name, settings, out=None, done=(), long_run=False):
    """Refuses a run estimated (`estimate`) to take more than `MAX_CPU_HOURS` of CPU,
    unless `long_run`; returns the estimate (seconds, units, basis).

    Raises:
      ValueError: for a run that long, with the estimate and how to confirm it.
    """
    seconds, n_units, basis = estimate(name, settings, out, done)
    if seconds > MAX_CPU_HOURS * 3600 and not _validate.boolean("long_run", long_run):
        raise ValueError(f"study {name} with seeds {settings['seeds']}: {n_units} units, "
                         f"estimated at {duration(seconds)} of CPU ({basis}), more than "
                         f"{MAX_CPU_HOURS:g} CPU-hours: if you mean it, confirm with "
                         f"--confirm-long-run (long_run=True)")
    return seconds, n_units, basis


def dumps(study, data):
    """The study file's text: `data` as JSON (compact, or with the study's indent)."""
    if study.indent is None:
        return json.dumps(data, separators=(",", ":")) + "\n"
    return json.dumps(data, indent=study.indent) + "\n"


def _replace_foreign(path, own):
    """Removes `path` if it exists and is not the engine's (`own`): what `force` lets
    a run replace."""
    if (path.exists() or path.is_symlink()) and not own(path):
        path.unlink()


def run_study(name, out, seeds=None, backend="joblib", n_jobs=-1, client=None,
              scheduler=None, progress=True, extra=None, force=False, inputs=(),
              long_run=False, **options):
    """Runs study `name` and writes its file `out`.

    Everything is checked before any work: the settings (`check_settings`), the
    destinations (`check_destinations`: `out`, its journal and its run log), the
    estimated run time (`check_run_length`).

    Args:
      name: a key of `STUDIES`.
      out: the file to write (a path); its journal (`journal_of`) keeps the finished
        units until the file is written, and a run log (`run_log_of`) gets one line.
      seeds: the study's seeds (see its `Study.seeds`; default its own).
      backend, n_jobs, client, scheduler, progress: as in `sweep.run_units` ("serial",
        "joblib" or "dask").
      extra: None, or a dict of further keys for "produced_by" (e.g. what was imported
        from an earlier file, and how it was checked).
      force: replace an `out`, journal or run log that the engine did not write.
      inputs: the run's input files, which no destination may be.
      long_run: run even if estimated at more than `MAX_CPU_HOURS` of CPU.
      **options: the study's size options (see its `Study.options`).

    Returns:
      The study's dict, as written.

    Raises:
      ValueError: for bad settings, a destination refused, a journal refused
        (`sweep.read_journal`), a run too long.
      icm.experiments.sweep.UnitError: for units that failed on every attempt.
    """
    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    given = _sizes(name, seeds, options)
    settings = check_settings(name, seeds, **options)
    out = check_destinations(name, out, force=force, inputs=inputs)
    check_run_length(name, settings, out, long_run=long_run)
    units = study.units(settings)
    journal, log = journal_of(out), run_log_of(out)
    if force:
        _replace_foreign(journal, is_journal)
        _replace_foreign(log, is_run_log)
    header = journal_header(name, settings)
    before = len(read_journal(journal, header, units))
    started, wall = time.strftime("%Y-%m-%dT%H:%M:%S%z"), time.perf_counter()
    results, cpu = run_units(functools.partial(study.run_unit, settings), units,
                             backend=backend, n_jobs=n_jobs, client=client,
                             scheduler=scheduler, progress=progress,
                             journal=journal, header=header)
    data = study.assemble(settings, units, results)
    data["produced_by"] = {"study": name, **store.provenance(
        command_of(name, given), settings, store.versions("mujoco"),
        seeds=study.seeding, units=units, **(extra or {}))}
    store.write_text(out, dumps(study, data))
    earlier = log.read_text(encoding="utf-8") if log.exists() else ""
    store.write_text(log, earlier + json.dumps({
        "study": name, "started": started, "settings": settings, "backend": backend,
        "n_jobs": n_jobs if backend == "joblib" else None,
        "scheduler": scheduler, "units": len(units),
        "units_from_journal": before, "wall_seconds": round(time.perf_counter() - wall, 1),
        "unit_cpu_seconds_total": round(sum(cpu), 1),
        "unit_cpu_seconds": [round(c, 2) for c in cpu],
        "cpu_count": os.cpu_count()}) + "\n")
    journal.unlink(missing_ok=True)
    return data


def command_of(name, settings):
    """The command line that runs study `name` with `settings` (its sizes as given,
    before the study's own `check`)."""
    options = " ".join(f"--{k.replace('_', '-')} {v}" for k, v in settings.items()
                       if k not in ("seeds", "imported_seeds"))
    return f"python -m icm study {name} --seeds {settings['seeds']} {options}".strip()


def read_seed_blocks(name, source):
    """An earlier file of study `name` whose seeds `import_seeds` keeps, read through
    `icm.records.SeedBlocksFile`.

    Args:
      name: the study's name (one whose units are seed blocks [label, root, first, n]).
      source: the file.

    Returns:
      The `records.SeedBlocksFile`.

    Raises:
      ValueError: for a study that keeps no seed blocks, or a file that is not one of
        this study's (`records.RecordError` naming the file and the field).
    """
    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    if not any(len(u) == 4 for u in study.units(check_settings(name))):
        raise ValueError(f"study {name!r} keeps no blocks of seeds per root: it cannot "
                         f"import seeds")
    if not isinstance(source, (str, os.PathLike)):
        raise _validate.ArgumentTypeError(f"source must be a file path, got "
                                          f"{_validate.show(source)}")
    data = records.read_bytes(pathlib.Path(source))
    try:
        other = records.parse_json(data, records.StudyFileStamp, str(source)).produced_by
    except records.RecordError:
        other = None  # (SeedBlocksFile says what is wrong)
    if other is not None and other.study != name:
        raise records.RecordError(f"{source}: a file of study {other.study!r}, not of "
                                  f"{name!r}")
    return records.parse_json(data, records.SeedBlocksFile, str(source))


def imported_units(old):
    """The units an earlier file's seeds become (`import_seeds`): [label, root, 0, k]
    for each of its entries, and ["reach"] if it has 'reach'."""
    return ([["reach"]] if old.reach is not None else []) + \
        [[label, int(root), 0, old.n_seeds] for label in old.runs for root in old.runs[label]]


def import_seeds(name, out, source, seeds=None, backend="joblib", n_jobs=-1, client=None,
                 scheduler=None, progress=True, force=False, **options):
    """Makes the seeds of an earlier file of study `name` (fewer seeds per root, same
    rollouts) done units of a larger run into `out`, after recomputing a sample of them.

    The earlier file's entries of root r hold seeds 0..k-1 of r, the first seeds of
    any larger run. Before any work, the file is read (`read_seed_blocks`: a file of
    this study, each entry of the shape a study's seed blocks have), and the
    destinations checked (`check_destinations`, the file an input). Before trusting the
    seeds, one seed of every label (seed i of root r, cycling over both) is recomputed
    alone and must give the same per-seed numbers, and the first label's whole block on
    its first root is recomputed and must give the same entry, counts included (with one
    seed per root, that block is the first label's seed: it is computed once). Every
    other entry must have that entry's keys, k values in each per-seed list. Then each
    entry is written to the journal of `out` as the unit [label, root, 0, k] (unless it
    is there already), and `run_study(..., imported_seeds=k, extra=...)` finishes the
    study.

    Returns:
      (k, extra): the seeds per root imported, and the "produced_by" keys saying what
      was imported and how it was checked.

    Raises:
      ValueError: if the earlier file is not one of this study's, of other settings,
        not of the study's labels and roots, or a recomputed unit differs from it.
    """
    import hashlib

    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    settings = check_settings(name, seeds, **options)
    check_destinations(name, out, force=force, inputs=[source])
    source = pathlib.Path(source)
    old = read_seed_blocks(name, source)
    text = records.read_bytes(source)
    kept = old.n_seeds
    if old.n_rollouts != settings["rollouts"]:
        raise ValueError(f"source: {source} has {old.n_rollouts} rollouts, the run "
                         f"{settings['rollouts']}")
    if old.n_trials != settings["trials"]:
        raise ValueError(f"source: {source} has {old.n_trials} trials on the formed "
                         f"presses, the run {settings['trials']}")
    earlier = (old.produced_by.model_extra or {}).get("settings")
    if isinstance(earlier, dict):
        for option in settings:
            if option not in ("seeds", "imported_seeds") and option in earlier and \
                    earlier[option] != settings[option]:
                raise ValueError(f"source: {source} was computed with {option} "
                                 f"{earlier[option]!r}, the run with {settings[option]!r}")
    full = study.units(settings)
    if kept * len({u[1] for u in full if len(u) == 4}) >= settings["seeds"]:
        raise ValueError(f"seeds must be more than the source's ({kept} per root), got "
                         f"{settings['seeds']}")
    header = check_settings(name, seeds, imported_seeds=kept, **options)
    allowed = {json.dumps(u) for u in study.units(header)}
    for unit in imported_units(old):
        if json.dumps(unit) not in allowed:
            raise ValueError(f"source: {source} holds {unit[0]!r}"
                             + (f" on root {unit[1]}" if len(unit) > 1 else "")
                             + f", which study {name!r} does not run")
    runs = {label: {root: dict(entry) for root, entry in by_root.items()}
            for label, by_root in old.runs.items()}
    labels = list(runs)
    checks = []
    for c, label in enumerate(labels):
        roots = [int(r) for r in runs[label]]
        checks.append([label, roots[c % len(roots)], c % kept, 1])
    first = [labels[0], int(next(iter(runs[labels[0]]))), 0, kept]
    if first not in checks:  # (with one seed per root, it is the first check)
        checks.append(first)
    if old.reach is not None:
        checks.append(["reach"])
    results, _ = run_units(functools.partial(study.run_unit, settings), checks,
                           backend=backend, n_jobs=n_jobs, client=client,
                           scheduler=scheduler, progress=progress)
    block = dict(zip(map(json.dumps, checks), results))[json.dumps(first)]
    for label, by_root in runs.items():
        for root, entry in by_root.items():
            shape = _block_shape(entry, block, kept)
            if shape:
                raise ValueError(f"source: {source}, runs[{label!r}][{root!r}]: {shape}")
    for unit, result in zip(checks, results):
        if unit == ["reach"]:
            if result != old.reach:
                raise ValueError(f"source: recomputing 'reach' does not give the numbers of "
                                 f"{source}")
            continue
        label, root, i, n = unit
        entry = runs[label][str(root)]
        if n == kept:
            same = result == entry
        else:
            same = all(result[key] == entry[key][i:i + 1] for key in result
                       if isinstance(result[key], list))
        if not same:
            raise ValueError(f"source: recomputing unit {unit} does not give the numbers "
                             f"of {source}; its seeds cannot be imported")
    journal = journal_of(out)
    if force:
        _replace_foreign(journal, is_journal)
    journal_units = study.units(header)
    there = read_journal(journal, journal_header(name, header), journal_units)
    start_journal(journal, journal_header(name, header))
    with open(journal, "a", encoding="utf-8") as file:
        for unit in imported_units(old):
            if json.dumps(unit, separators=(",", ":")) in there:
                continue
            result = old.reach if unit == ["reach"] else runs[unit[0]][str(unit[1])]
            append_unit(file, unit, result, 0.0)
    extra = {"imported": {
        "from": source.name, "sha256": hashlib.sha256(text).hexdigest(),
        "seeds_per_root": kept,
        "units": [u for u in imported_units(old) if u != ["reach"]]
        + ([["reach"]] if old.reach is not None else []),
        "checked": checks,
        "check": ("each checked unit recomputed here and identical to the source: one "
                  "seed of every label (its per-seed numbers), one whole block (its "
                  "entry, counts included), and 'reach'")}}
    return kept, extra


def _block_shape(entry, block, kept):
    """What is wrong with an entry's shape, against a recomputed block of `kept`
    seeds, in words ("" if nothing)."""
    if set(entry) != set(block):
        missing = sorted(set(block) - set(entry))
        return (f"lacks {missing[0]!r}" if missing else
                f"has {sorted(set(entry) - set(block))[0]!r}, which a block has not")
    for key, value in block.items():
        if isinstance(value, list):
            if not isinstance(entry[key], list) or len(entry[key]) != kept:
                return f"{key} must hold one value per seed ({kept}), got " \
                       f"{_validate.show(entry[key])}"
        elif type(entry[key]) is not type(value):
            return f"{key} must be a {type(value).__name__}, got {_validate.show(entry[key])}"
    return ""
