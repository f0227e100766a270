"""The long studies behind the chapters, each cut into units of work that run on the
sweep engine (`icm.experiments.sweep.run_units`): on every core of this machine
(joblib), or on a Dask cluster, with the same numbers either way.

A study is registered in `STUDIES` with:

- its units: JSON lists that carry everything deciding a unit's result, its seeds
  included (e.g. ["growing up", 300, 12, 1]: condition, root seed, first seed index,
  seeds), so that no result depends on which worker ran it or when;
- its unit function, of the settings and one unit;
- its size options (seeds, and for example rollouts), so that a tiny run takes
  seconds;
- how the units' results are assembled into the study's file, in the order of the
  units, whichever order they finished in.

`run_study` runs one: every finished unit is appended to a journal beside the output
file, so a study killed half-way (Ctrl-C or SIGKILL) continues from the units it saved
and writes the same file; the file is written at the end, atomically. It records what
produced it under "produced_by": the study, its settings, the versions of icm, NumPy
and MuJoCo, the seeds, and the units. How long the run took (which depends on the
machine, not on the numbers) goes to a sibling file, ``<out>.runs.jsonl``, one line per
run, so that the study's own file is byte-identical between a serial run, joblib and
a Dask cluster.

From the command line: ``python -m icm study NAME --seeds N --backend joblib|dask
[--scheduler ADDRESS] --out FILE`` (see `icm.cli`).
"""

import dataclasses
import functools
import json
import os
import pathlib
import platform
import sys
import tempfile
import time

from icm import _validate
from icm.experiments import formed_actions, goal_babbling, goal_babbling_study, remedies_study
from icm.experiments.sweep import append_unit, read_journal, run_units, start_journal


@dataclasses.dataclass(frozen=True)
class Study:
    """One registered study.

    Attributes:
      name: its name on the command line.
      description: one line for `--help`.
      seeds: (default seeds, what a seed count means), e.g. (80, "per condition").
      options: the other size options: {name: (default, minimum, help)}.
      units: settings -> the list of units.
      run_unit: a module-level function (settings, unit) -> the unit's result, a
        JSON value.
      assemble: (settings, units, results) -> the study's dict.
      check: settings -> settings, raising ValueError for a bad combination.
      indent: the JSON file's indentation (None: compact), as its committed file has it.
    """

    name: str
    description: str
    seeds: tuple
    options: dict
    units: object
    run_unit: object
    assemble: object
    check: object = None
    indent: object = None


def versions():
    """The versions of what computes a study: Python, icm, NumPy and MuJoCo."""
    import mujoco
    import numpy

    # icm itself is loaded whenever one of its modules is (its version read from there,
    # not imported: the package imports every layer, this module is below some).
    icm_version = sys.modules["icm"].__version__
    return {"python": platform.python_version(), "icm": icm_version,
            "numpy": numpy.__version__, "mujoco": mujoco.__version__}


# --- the remedies study (icm.experiments.remedies_study) ---------------------------

def _remedies_check(settings):
    n_roots = len(remedies_study.ROOTS)
    if settings["seeds"] % n_roots:
        raise ValueError(f"seeds must be a multiple of the {n_roots} root seeds "
                         f"{list(remedies_study.ROOTS)} (the same number of seeds on each), got "
                         f"{settings['seeds']}")
    return settings


def _remedies_units(settings):
    per_root = settings["seeds"] // len(remedies_study.ROOTS)
    kept = settings.get("imported_seeds", 0)
    units = [["reach"]]
    for label in remedies_study.CONDITIONS:
        for root in remedies_study.ROOTS:
            if kept:
                units.append([label, root, 0, kept])
            units.extend([label, root, i, 1] for i in range(kept, per_root))
    return units


def _remedies_unit(settings, unit):
    if unit == ["reach"]:
        return remedies_study.run_reach(settings["reach_movements"])
    label, root, first, n = unit
    return remedies_study.run_condition(label, root, n_seeds=n, first_run=first, threads=1,
                                        n_rollouts=settings["rollouts"],
                                        n_trials=settings["trials"])


def _remedies_assemble(settings, units, results):
    study = {"budgets": list(remedies_study.budgets_of(settings["rollouts"])),
             "n_seeds": settings["seeds"] // len(remedies_study.ROOTS),
             "n_rollouts": settings["rollouts"], "n_trials": settings["trials"], "runs": {}}
    done = {json.dumps(u): r for u, r in zip(units, results)}
    study["reach"] = done[json.dumps(["reach"])]
    for label in remedies_study.CONDITIONS:
        study["runs"][label] = {}
        for root in remedies_study.ROOTS:
            parts = sorted((u[2], r) for u, r in zip(units, results)
                           if u[:2] == [label, root])
            study["runs"][label][str(root)] = join_entries([r for _, r in parts])
    return study


def join_entries(entries):
    """One entry of a study from entries of consecutive seed blocks: the per-seed lists
    joined in order, the dicts of counts ("coverage") summed cell by cell."""
    out = {}
    for key, value in entries[0].items():
        if isinstance(value, list):
            out[key] = [item for entry in entries for item in entry[key]]
        elif isinstance(value, dict):
            out[key] = {k: _add([entry[key][k] for entry in entries]) for k in value}
        else:
            raise ValueError(f"entries: {key!r} is neither per seed nor counts")
    return out


def _add(grids):
    """The cell-by-cell sum of nested lists of integers of one shape."""
    if isinstance(grids[0], list):
        return [_add(list(cells)) for cells in zip(*grids)]
    return sum(grids)


# --- the goal-babbling study (icm.experiments.goal_babbling_study) -----------------

def _babbling_check(settings):
    n_roots = len(goal_babbling_study.TUNING_ROOTS)
    if settings["seeds"] % n_roots:
        raise ValueError(f"seeds must be a multiple of the {n_roots} tuning root seeds "
                         f"{list(goal_babbling_study.TUNING_ROOTS)}, got {settings['seeds']}")
    return settings


def _babbling_plan(settings):
    study = goal_babbling_study
    return {label: study.TUNING_ROOTS + (study.HELD_OUT_ROOTS
                                         if label in study.HELD_OUT_VARIANTS else ())
            for label in study.VARIANTS}


def _babbling_units(settings):
    per_root = settings["seeds"] // len(goal_babbling_study.TUNING_ROOTS)
    return [[label, root, i, 1] for label, roots in _babbling_plan(settings).items()
            for root in roots for i in range(per_root)]


def _babbling_unit(settings, unit):
    label, root, first, n = unit
    return goal_babbling_study.run_variant(label, root, n_seeds=n, first_run=first, threads=1,
                                           n_rollouts=settings["rollouts"],
                                           n_trials=settings["trials"])


def _babbling_assemble(settings, units, results):
    study = {"budgets": list(goal_babbling_study.budgets_of(settings["rollouts"])),
             "n_seeds": settings["seeds"] // len(goal_babbling_study.TUNING_ROOTS),
             "n_rollouts": settings["rollouts"], "n_trials": settings["trials"], "runs": {}}
    for label, roots in _babbling_plan(settings).items():
        study["runs"][label] = {}
        for root in roots:
            parts = sorted((u[2], r) for u, r in zip(units, results) if u[:2] == [label, root])
            study["runs"][label][str(root)] = join_entries([r for _, r in parts])
    return study


def plain(value):
    """`value` with NumPy scalars and arrays made Python numbers and lists (JSON)."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if hasattr(value, "tolist"):
        return plain(value.tolist())
    return value


# --- the robustness maps (icm.experiments.robustness) ------------------------------

ROBUSTNESS_SEED = 0
"""The root seed of the maps' runs (that of `robustness.run_robustness`'s default)."""


def _robustness_units(settings):
    from icm.experiments import robustness

    units = []
    for name, study in robustness.STUDIES.items():
        for (a, b), grid in robustness.pair_grids(study):
            units.extend([name, a, va, b, vb] for va in grid[a] for vb in grid[b])
    return units


def _robustness_unit(settings, unit):
    """One map point and its block of seeds: the rows `robustness.run_robustness`'s
    sweep keeps for it (the point, `seed_index`, a boolean per claim)."""
    from icm.experiments import robustness
    from icm.experiments.sweep import run_point

    name, a, va, b, vb = unit
    study = robustness.STUDIES[name]
    others = {n: v for n, v in study.defaults().items() if n not in (a, b)}
    fixed = {**study.fixed, **others}
    if settings.get("length") is not None:
        key = "n_trials" if "n_trials" in fixed else "n_episodes"
        fixed[key] = settings["length"]
    return plain(run_point(study.run_fn, settings["seeds"], ROBUSTNESS_SEED, fixed,
                            {a: va, b: vb}, per_seed=study.per_seed))


def _robustness_assemble(settings, units, results):
    maps = {}
    for (name, a, _, b, _), rows in zip(units, results):
        maps.setdefault(name, {}).setdefault(f"{a}|{b}", []).extend(rows)
    return {"n_seeds": settings["seeds"], "seed": ROBUSTNESS_SEED,
            "length": settings.get("length"), "maps": maps}


def robustness_results(data):
    """The `robustness.RobustnessResult` of each learner from a robustness study's dict
    (as `python -m icm study robustness` writes it): {name: result}."""
    import pandas as pd

    from icm.experiments import robustness

    return {name: robustness.RobustnessResult(
                robustness.STUDIES[name], {"n_seeds": data["n_seeds"], "seed": data["seed"]},
                {tuple(pair.split("|")): pd.DataFrame(rows) for pair, rows in maps.items()})
            for name, maps in data["maps"].items()}


# --- the curiosity comparisons (icm.experiments.curiosity) -------------------------

CURIOSITY_SEED = 0
"""The root seed of the comparisons' runs (that of the curiosity functions' default)."""


def _curiosity_units(settings):
    import itertools

    from icm.learners import goal_oriented, interest, q_learning

    return ([["signal", s, per, noisy] for s, per, noisy in itertools.product(
                interest.SIGNALS, goal_oriented.INTEREST_PER, (False, True))]
            + [["reward", r, wobbly] for r, wobbly in itertools.product(
                q_learning.REWARDS, (False, True))])


def _curiosity_unit(settings, unit):
    """One setting of `curiosity.run_signal_comparison` or `run_reward_comparison` on
    all the study's seeds (the same seeds for every setting, as there): its runs'
    `seed_summaries()`."""
    from icm.experiments import goal_oriented, rod_toppling

    if unit[0] == "signal":
        _, signal, per, noisy = unit
        result = goal_oriented.run_goal_oriented(
            n_seeds=settings["seeds"], n_trials=settings["trials"], interest=signal,
            interest_per=per, noisy_button=noisy, seed=CURIOSITY_SEED, progress=False)
    else:
        _, reward, wobbly = unit
        result = rod_toppling.run_rod_toppling(
            n_seeds=settings["seeds"], n_episodes=settings["episodes"], reward=reward,
            wobbly_rod=wobbly, seed=CURIOSITY_SEED, progress=False)
    return plain(result.seed_summaries())


def _curiosity_assemble(settings, units, results):
    signals = {"|".join(map(str, u[1:])): r for u, r in zip(units, results)
               if u[0] == "signal"}
    rewards = {"|".join(map(str, u[1:])): r for u, r in zip(units, results)
               if u[0] == "reward"}
    return {"n_seeds": settings["seeds"], "n_trials": settings["trials"],
            "n_episodes": settings["episodes"], "seed": CURIOSITY_SEED,
            "signals": signals, "rewards": rewards}


STUDIES = {}
"""The registered studies, by name."""

FORMED_TRIALS = (formed_actions.DEFAULT_TRIALS, 1,
                 "trials of the goal-oriented learner on each seed's formed presses")
"""The option "trials" of the studies of formed presses (remedies, goal-babbling)."""


def register(study):
    """Adds `study` (a `Study`) to `STUDIES`."""
    _validate.instance("study", study, Study)
    STUDIES[study.name] = study
    return study


register(Study(
    name="remedies",
    description="growing up and being shown against the three strategies "
                "(icm.experiments.remedies_study; assets/remedies_study.json)",
    seeds=(80, "per condition, spread evenly over the root seeds 100, 200, 300, 400"),
    options={"rollouts": (goal_babbling.DEFAULT_N_ROLLOUTS, 1, "rollouts per seed"),
             "trials": FORMED_TRIALS,
             "reach_movements": (remedies_study.REACH_MOVEMENTS, 1,
                                 "random movements per range share in 'reach'")},
    units=_remedies_units, run_unit=_remedies_unit, assemble=_remedies_assemble,
    check=_remedies_check))

register(Study(
    name="remedies-replication",
    description="the conditions the chapter 'Forming actions' claims about, on its fresh "
                "root 9001, one seed a unit (icm.experiments.remedies_study.FRESH_FILE; "
                "assets/remedies_fresh_runs.json)",
    seeds=(remedies_study.POWERED_SEEDS, "per condition, on the fresh root 9001"),
    options={"rollouts": (goal_babbling.DEFAULT_N_ROLLOUTS, 1, "rollouts per seed"),
             "trials": FORMED_TRIALS},
    units=remedies_study.replication_units, run_unit=remedies_study.replication_unit,
    assemble=remedies_study.assemble_replication))

register(Study(
    name="goal-babbling",
    description="the variants of the goal-babbling learner "
                "(icm.experiments.goal_babbling_study; assets/goal_babbling_study.json)",
    seeds=(20, "per variant and root pair: split over the tuning roots 100 and 200 "
               "(and the held-out roots 300 and 400 for the default and its baseline)"),
    options={"rollouts": (goal_babbling.DEFAULT_N_ROLLOUTS, 1, "rollouts per seed"),
             "trials": FORMED_TRIALS},
    units=_babbling_units, run_unit=_babbling_unit, assemble=_babbling_assemble,
    check=_babbling_check, indent=1))

register(Study(
    name="robustness",
    description="the maps of what the results depend on: every pair of each learner's "
                "unpublished settings (icm.experiments.robustness), one map point and its "
                "seeds a unit",
    seeds=(200, "per map point, the same at every point"),
    options={"length": (0, 0, "trials (episodes on the rods) per run; 0: each "
                              "learner's chapter's")},
    units=_robustness_units, run_unit=_robustness_unit, assemble=_robustness_assemble,
    check=lambda settings: {**settings, "length": settings["length"] or None}))

register(Study(
    name="curiosity",
    description="the interest signals on the buttons and the intrinsic rewards on the rods "
                "(icm.experiments.curiosity), one setting and its seeds a unit",
    seeds=(100, "per setting, the same for every setting"),
    options={"trials": (100, 1, "trials per run on the buttons"),
             "episodes": (300, 1, "episodes per run on the rods")},
    units=_curiosity_units, run_unit=_curiosity_unit, assemble=_curiosity_assemble))


# --- running a study ---------------------------------------------------------------

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


def write_atomically(path, text):
    """Writes `text` to `path` through a temporary file in the same folder and a
    rename, so that `path` is never half written."""
    path = pathlib.Path(path)
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(temporary, 0o666 & ~umask)  # as open() would make it, not mkstemp's 0o600
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as file:
            file.write(text)
            file.flush()
            os.fsync(file.fileno())
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise


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
    data["produced_by"] = {"study": name, "command": command_of(name, settings),
                           "settings": settings, "versions": versions(),
                           "seeds": seeds_of(name, settings), "units": units,
                           **(extra or {})}
    write_atomically(out, dumps(study, data))
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


def seeds_of(name, settings):
    """What seeds a study's units use, in words (kept verbatim as the stored files have
    them, so that a rerun writes the same bytes: `icm.experiments._seeding.run_seeds` is
    now `icm.experiments.seeding.run_seeds`, the same function)."""
    if name in ("remedies", "goal-babbling", "remedies-replication"):
        return ("unit [label, root, first, n]: seeds first..first+n-1 of root seed "
                "'root' (icm.experiments._seeding.run_seeds: child i of "
                "numpy.random.SeedSequence(root)); the goal-oriented learner on the formed "
                "presses uses the same children of the same root")
    if name == "robustness":
        return (f"every map point runs seeds 0..n-1 of root seed {ROBUSTNESS_SEED} "
                "(the same seeds at every point, as in robustness.run_robustness)")
    return (f"every setting runs seeds 0..n-1 of root seed {CURIOSITY_SEED} (the same "
            "seeds for every setting, as in icm.experiments.curiosity)")


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
