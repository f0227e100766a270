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

from icm import _validate, store
from icm.experiments.sweep import append_unit, read_journal, run_units, start_journal
from icm.studies.registry import STUDIES


def check_settings(name, seeds=None, **options):
    """The full settings of study `name`: {"seeds": ..., option: value}, defaults
    filled in, each checked (ValueError naming the bad one)."""
    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    unknown = sorted(set(options) - set(study.options) - {"imported_seeds"})
    if unknown:
        raise ValueError(f"{unknown[0]!r} is not an option of study {name!r}; allowed: "
                         f"{', '.join(study.options) or 'none'}")
    settings = {"seeds": _validate.integer_at_least(
        "seeds", study.seeds[0] if seeds is None else seeds, 1)}
    for option, (default, minimum, _) in study.options.items():
        value = options.get(option)
        settings[option] = _validate.integer_at_least(option, default if value is None
                                                      else value, minimum)
    if options.get("imported_seeds"):
        settings["imported_seeds"] = options["imported_seeds"]
    return study.check(settings) if study.check else settings


def journal_of(out):
    """The journal beside the output file `out`: ``<out>.journal``."""
    return pathlib.Path(str(out) + ".journal")


def run_log_of(out):
    """The run log beside the output file `out`: ``<out>.runs.jsonl``."""
    return pathlib.Path(str(out) + ".runs.jsonl")


def dumps(study, data):
    """The study file's text: `data` as JSON (compact, or with the study's indent)."""
    if study.indent is None:
        return json.dumps(data, separators=(",", ":")) + "\n"
    return json.dumps(data, indent=study.indent) + "\n"


def run_study(name, out, seeds=None, backend="joblib", n_jobs=-1, client=None,
              scheduler=None, progress=True, extra=None, **options):
    """Runs study `name` and writes its file `out`.

    Args:
      name: a key of `STUDIES`.
      out: the file to write (a path); its journal (`journal_of`) keeps the finished
        units until the file is written, and a run log (`run_log_of`) gets one line.
      seeds: the study's seeds (see its `Study.seeds`; default its own).
      backend, n_jobs, client, scheduler, progress: as in `sweep.run_units` ("serial",
        "joblib" or "dask").
      extra: None, or a dict of further keys for "produced_by" (e.g. what was imported
        from an earlier file, and how it was checked).
      **options: the study's size options (see its `Study.options`).

    Returns:
      The study's dict, as written.
    """
    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    settings = check_settings(name, seeds, **options)
    if not isinstance(out, (str, os.PathLike)):
        raise _validate.ArgumentTypeError(f"out must be a file path, got {_validate.show(out)}")
    out = pathlib.Path(out)
    if not out.parent.is_dir():
        raise ValueError(f"out: the folder {str(out.parent)!r} does not exist")
    units = study.units(settings)
    journal = journal_of(out)
    before = len(read_journal(journal, settings))
    started, wall = time.strftime("%Y-%m-%dT%H:%M:%S%z"), time.perf_counter()
    results, cpu = run_units(functools.partial(study.run_unit, settings), units,
                                   backend=backend, n_jobs=n_jobs, client=client,
                                   scheduler=scheduler, progress=progress,
                                   journal=journal, header=settings)
    data = study.assemble(settings, units, results)
    data["produced_by"] = {"study": name, **store.provenance(
        command_of(name, settings), settings, store.versions("mujoco"),
        seeds=study.seeding, units=units, **(extra or {}))}
    store.write_text(out, dumps(study, data))
    with open(run_log_of(out), "a", encoding="utf-8") as log:
        log.write(json.dumps({
            "started": started, "settings": settings, "backend": backend,
            "n_jobs": n_jobs if backend == "joblib" else None,
            "scheduler": scheduler, "units": len(units),
            "units_from_journal": before, "wall_seconds": round(time.perf_counter() - wall, 1),
            "unit_cpu_seconds_total": round(sum(cpu), 1),
            "unit_cpu_seconds": [round(c, 2) for c in cpu],
            "cpu_count": os.cpu_count()}) + "\n")
    journal.unlink(missing_ok=True)
    return data


def command_of(name, settings):
    """The command line that runs study `name` with `settings`."""
    options = " ".join(f"--{k.replace('_', '-')} {v}" for k, v in settings.items()
                       if k not in ("seeds", "imported_seeds"))
    return f"python -m icm study {name} --seeds {settings['seeds']} {options}".strip()


def import_seeds(name, out, source, seeds=None, backend="joblib", n_jobs=-1, client=None,
                 scheduler=None, progress=True, **options):
    """Makes the seeds of an earlier file of study `name` (fewer seeds per root, same
    rollouts) done units of a larger run into `out`, after recomputing a sample of them.

    The earlier file's entries of root r hold seeds 0..k-1 of r, the first seeds of
    any larger run. Before trusting them, one seed of every label (seed i of root
    r, cycling over both) is recomputed alone and must give the same per-seed numbers,
    and the first label's whole block on its first root is recomputed and must give
    the same entry, counts included. Then each entry is written to the journal of
    `out` as the unit [label, root, 0, k], and `run_study(..., imported_seeds=k,
    extra=...)` finishes the study.

    Returns:
      (k, extra): the seeds per root imported, and the "produced_by" keys saying what
      was imported and how it was checked.

    Raises:
      ValueError: if the earlier file is of other settings, or a recomputed unit
        differs from it.
    """
    import hashlib

    study = STUDIES[_validate.one_of("name", name, tuple(STUDIES))]
    source = pathlib.Path(source)
    text = source.read_text()
    old = json.loads(text)
    settings = check_settings(name, seeds, **options)
    kept = old["n_seeds"]
    if old["n_rollouts"] != settings["rollouts"]:
        raise ValueError(f"source: {source} has {old['n_rollouts']} rollouts, the run "
                         f"{settings['rollouts']}")
    if old["n_trials"] != settings["trials"]:
        raise ValueError(f"source: {source} has {old['n_trials']} trials on the formed "
                         f"presses, the run {settings['trials']}")
    full = study.units(settings)
    if kept * len({u[1] for u in full if len(u) == 4}) >= settings["seeds"]:
        raise ValueError(f"seeds must be more than the source's ({kept} per root), got "
                         f"{settings['seeds']}")
    labels = list(old["runs"])
    checks = []
    for c, label in enumerate(labels):
        roots = [int(r) for r in old["runs"][label]]
        checks.append([label, roots[c % len(roots)], c % kept, 1])
    first = [labels[0], int(next(iter(old["runs"][labels[0]]))), 0, kept]
    checks.append(first)
    if "reach" in old:
        checks.append(["reach"])
    results, _ = run_units(functools.partial(study.run_unit, settings), checks,
                                 backend=backend, n_jobs=n_jobs, client=client,
                                 scheduler=scheduler, progress=progress)
    for unit, result in zip(checks, results):
        if unit == ["reach"]:
            if result != old["reach"]:
                raise ValueError(f"source: recomputing 'reach' does not give the numbers of "
                                 f"{source}")
            continue
        label, root, i, n = unit
        entry = old["runs"][label][str(root)]
        if n == kept:
            same = result == entry
        else:
            same = all(result[key] == entry[key][i:i + 1] for key in result
                       if isinstance(result[key], list))
        if not same:
            raise ValueError(f"source: recomputing unit {unit} does not give the numbers "
                             f"of {source}; its seeds cannot be imported")
    journal = journal_of(out)
    header = check_settings(name, seeds, imported_seeds=kept, **options)
    read_journal(journal, header)  # refuses a journal of other settings
    start_journal(journal, header)
    with open(journal, "a", encoding="utf-8") as file:
        if "reach" in old:
            append_unit(file, ["reach"], old["reach"], 0.0)
        for label in old["runs"]:
            for root, entry in old["runs"][label].items():
                append_unit(file, [label, int(root), 0, kept], entry, 0.0)
    extra = {"imported": {
        "from": source.name, "sha256": hashlib.sha256(text.encode()).hexdigest(),
        "seeds_per_root": kept,
        "units": [[label, int(root), 0, kept] for label in old["runs"]
                  for root in old["runs"][label]] + ([["reach"]] if "reach" in old else []),
        "checked": checks,
        "check": ("each checked unit recomputed here and identical to the source: one "
                  "seed of every label (its per-seed numbers), one whole block (its "
                  "entry, counts included), and 'reach'")}}
    return kept, extra
