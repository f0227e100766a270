"""The study engine (icm.studies.engine on icm.experiments.sweep.run_units) on tiny
made-up studies: what it writes and refuses to write (issue 48), the sizes it refuses
before any work, the journal it reads back (validated by icm.records), its retries and
its failures, and the file's mode and recorded command. Each test fails when the
behaviour it names is broken (the module's tests were watched fail with the bug
planted)."""

import importlib
import json
import os
import time

import pytest

from icm import cli, files, records, studies
from icm.studies import engine, registry

sweep = importlib.import_module("icm.experiments.sweep")  # (icm.experiments.sweep is
# also the name of the function the package exports)

LABELS = ("slow", "fast")
ROOTS = (100, 200)
CALLS = []
"""The units the made-up studies computed in this process, in order (serial runs)."""


class Killed(BaseException):
    """What a process killed half-way looks like to the engine: not an Exception, so
    neither retried nor reported: it ends the run."""


KILL_AT = {}
"""{"unit": unit}: the made-up study's unit at which the run is 'killed'."""
FAIL = {}
"""{unit's JSON: how many more times it raises}: units that fail, then succeed."""
BURN = {"seconds": 0.0}
"""CPU seconds each unit spends (so that the run log records times above 0)."""


def _value(label, root, i, rollouts):
    return (len(label) * 1000 + root * 10 + i) * rollouts % 9973


def blocks_units(settings):
    """The made-up study's units: ['reach'], then a block of imported seeds per label
    and root (if any), then [label, root, i, 1] for each other seed (as remedies')."""
    per_root = settings["seeds"] // len(ROOTS)
    kept = settings.get("imported_seeds", 0)
    out = [["reach"]]
    for label in LABELS:
        for root in ROOTS:
            if kept:
                out.append([label, root, 0, kept])
            out.extend([label, root, i, 1] for i in range(kept, per_root))
    return out


def blocks_unit(settings, unit):
    """One unit: a small dict of numbers decided by the unit and the settings."""
    CALLS.append(unit)
    start = time.process_time()
    while time.process_time() - start < BURN["seconds"]:
        pass
    if KILL_AT.get("unit") == unit:
        raise Killed()
    key = json.dumps(unit)
    if FAIL.get(key, 0) > 0:
        FAIL[key] -= 1
        raise RuntimeError(f"transient failure of {key}")
    if unit == ["reach"]:
        return [settings["reach_movements"], 0.5]
    label, root, first, n = unit
    return {"x": [_value(label, root, i, settings["rollouts"]) for i in range(first, first + n)],
            "trials": [settings["trials"]] * n, "count": {"all": n}}


def blocks_assemble(settings, units, results):
    """The file: {"n_seeds", "n_rollouts", "n_trials", "runs": {label: {root: entry}}
    (the blocks of a root joined in the order of their first seeds), "reach"}."""
    runs = {}
    for label in LABELS:
        for root in ROOTS:
            parts = sorted((u[2], r) for u, r in zip(units, results) if u[:2] == [label, root])
            runs.setdefault(label, {})[str(root)] = {
                "x": [v for _, r in parts for v in r["x"]],
                "trials": [v for _, r in parts for v in r["trials"]],
                "count": {"all": sum(r["count"]["all"] for _, r in parts)}}
    reach = [r for u, r in zip(units, results) if u == ["reach"]][0]
    return {"n_seeds": settings["seeds"] // len(ROOTS), "n_rollouts": settings["rollouts"],
            "n_trials": settings["trials"], "runs": runs, "reach": reach}


def _check(settings):
    """As a registered study's check: refuses a bad combination, and reads an option
    (here, as robustness' length: 0 means the default, None)."""
    if settings["seeds"] % len(ROOTS):
        raise ValueError(f"seeds must be a multiple of {len(ROOTS)}, got {settings['seeds']}")
    return {**settings, "length": settings["length"] or None}


UNIT_SECONDS = {"value": 0.01}


def blocks_seconds(settings, unit):
    return UNIT_SECONDS["value"]


NAME = "made-up-blocks"


@pytest.fixture
def blocks():
    """A made-up study of seed blocks (the remedies' shape), registered for one test."""
    CALLS.clear()
    KILL_AT.clear()
    FAIL.clear()
    BURN["seconds"] = 0.0
    UNIT_SECONDS["value"] = 0.01
    study = registry.register(registry.Study(
        name=NAME, description="a made-up study of seed blocks", seeds=(4, "per label"),
        options={"rollouts": (10, 1, "rollouts"), "trials": (3, 1, "trials"),
                 "reach_movements": (5, 1, "movements"),
                 "length": (0, 0, "a length; 0: the default")},
        units=blocks_units, run_unit=blocks_unit, assemble=blocks_assemble,
        seeding="made up", check=_check, unit_seconds=blocks_seconds))
    yield study
    registry.unregister(NAME)


def _run(out, **more):
    return studies.run_study(NAME, out, backend="serial", progress=False, **more)


def in_process(args, capsys):
    """The command line run in this process: (exit status, stdout, stderr)."""
    try:
        status = cli.main(args)
    except SystemExit as exit_:
        status = exit_.code
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def _journal_units(journal):
    return [json.loads(line)["unit"] for line in journal.read_text().splitlines()[1:]]


# --- 1. what the engine writes, and what it refuses to -------------------------------

def test_a_study_writes_its_file_and_run_log_and_rewrites_only_its_own(blocks, tmp_path):
    out = tmp_path / "s.json"
    data = _run(out, seeds=4)
    assert json.loads(out.read_text()) == data
    assert data["produced_by"]["study"] == NAME
    assert not engine.journal_of(out).exists()
    _run(out, seeds=2)  # its own file: replaced, the run log appended to
    assert json.loads(out.read_text())["n_seeds"] == 1
    log = [json.loads(line) for line in engine.run_log_of(out).read_text().splitlines()]
    assert [line["settings"]["seeds"] for line in log] == [4, 2]


@pytest.mark.parametrize("make, message", [
    (lambda p: p.write_text("my notes\n"), "exists and was not written by this command"),
    (lambda p: p.write_text(json.dumps({"produced_by": {"study": "remedies"}})),
     "exists and was not written by this command"),
    (lambda p: p.mkdir(), "is a folder"),
    (lambda p: p.symlink_to(p.with_name("target.json")), "is a symbolic link"),
])
def test_an_out_that_is_not_this_studys_file_is_refused_before_any_work(
        blocks, tmp_path, make, message, capsys):
    out = tmp_path / "s.json"
    (tmp_path / "target.json").write_text("precious\n")
    make(out)
    before = {p.name: (p.read_bytes() if p.is_file() else None)
              for p in tmp_path.iterdir()}
    with pytest.raises(files.DestinationError, match=message):
        _run(out)
    status, _, err = in_process(["study", NAME, "--out", str(out)], capsys)
    assert status == 2 and message in err and str(out) in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert CALLS == []  # nothing computed
    after = {p.name: (p.read_bytes() if p.is_file() else None) for p in tmp_path.iterdir()}
    assert after == before  # nothing written, nothing changed


def test_force_replaces_a_file_that_is_not_the_studys(blocks, tmp_path, capsys):
    out = tmp_path / "s.json"
    out.write_text("my notes\n")
    engine.journal_of(out).write_text("not a journal\n")
    engine.run_log_of(out).write_text("not a log\n")
    status, stdout, err = in_process(["study", NAME, "--backend", "serial", "--no-progress",
                                      "--force", "--out", str(out)], capsys)
    assert status == 0, err
    assert json.loads(out.read_text())["produced_by"]["study"] == NAME
    assert len(engine.run_log_of(out).read_text().splitlines()) == 1


@pytest.mark.parametrize("beside", ["journal", "run log"])
@pytest.mark.parametrize("make, message", [
    (lambda p: p.write_text("my notes\n"), "exists and was not written by this command"),
    (lambda p: p.mkdir(), "is a folder"),
    (lambda p: p.symlink_to(p.with_name("target.txt")), "is a symbolic link"),
])
def test_a_journal_or_run_log_that_is_not_the_engines_is_refused(blocks, tmp_path, beside,
                                                                 make, message):
    out = tmp_path / "s.json"
    (tmp_path / "target.txt").write_text("precious\n")
    path = engine.journal_of(out) if beside == "journal" else engine.run_log_of(out)
    make(path)
    with pytest.raises(files.DestinationError, match=f"out's {beside} .*{message}"):
        _run(out)
    assert CALLS == [] and not out.exists()
    assert (tmp_path / "target.txt").read_text() == "precious\n"


def test_an_out_equal_to_the_imported_file_is_refused(blocks, tmp_path, capsys):
    source = tmp_path / "s.json"
    _run(source, seeds=2)
    kept = source.read_bytes()
    CALLS.clear()
    status, _, err = in_process(["study", NAME, "--seeds", "4", "--out", str(source),
                                 "--import-seeds", str(source)], capsys)
    assert status == 2 and f"--out {source} is the input" in err
    assert len(err.splitlines()) == 1
    with pytest.raises(files.DestinationError, match="is the input"):
        studies.import_seeds(NAME, source, source, seeds=4, progress=False)
    assert CALLS == [] and source.read_bytes() == kept


def test_an_out_in_a_missing_folder_is_refused_in_one_line(blocks, tmp_path, capsys):
    status, _, err = in_process(["study", NAME, "--out", str(tmp_path / "no" / "s.json")],
                                capsys)
    assert status == 2 and "does not exist" in err and len(err.splitlines()) == 1


# --- 2. sizes refused before any work ---------------------------------------------------

def _size_options():
    for name, study in studies.STUDIES.items():
        yield name, "--seeds", registry.SEEDS[0]
        for option, (_, minimum, _) in study.options.items():
            yield name, "--" + option.replace("_", "-"), minimum


@pytest.mark.parametrize("name, flag, minimum", list(_size_options()))
def test_every_size_option_of_every_study_is_refused_out_of_range_when_read(
        name, flag, minimum, tmp_path, capsys):
    top = registry.SEEDS[1] if flag == "--seeds" else registry.SIZE_MAX
    for text in (str(minimum - 1), "-5", "nan", "inf", "2.5", "1e9", str(top + 1), "many"):
        status, _, err = in_process(["study", name, flag, text, "--out",
                                     str(tmp_path / "s.json")], capsys)
        assert status == 2, (flag, text)
        assert f"argument {flag}: must be an integer from {minimum} to {top:,}, got " \
               f"{text!r}" in err, err
        assert len(err.splitlines()) == 1
    assert not list(tmp_path.iterdir())


def test_the_engine_refuses_the_same_sizes(blocks):
    for seeds in (0, -1, registry.SEEDS[1] + 1):
        with pytest.raises(ValueError, match=f"seeds must be an integer in 1..100000, got "
                                             f"{seeds}"):
            engine.check_settings(NAME, seeds=seeds)
    for bad in (float("nan"), 2.5, "4", True):
        with pytest.raises(TypeError, match="seeds must be an integer"):
            engine.check_settings(NAME, seeds=bad)
    with pytest.raises(ValueError, match="rollouts must be an integer in 1..1000000"):
        engine.check_settings(NAME, rollouts=registry.SIZE_MAX + 1)


def test_a_run_prints_its_estimate_and_a_long_one_needs_confirming(blocks, tmp_path, capsys):
    out = tmp_path / "s.json"
    UNIT_SECONDS["value"] = 3600.0  # (a rough figure of an hour a unit: 9 units)
    status, _, err = in_process(["study", NAME, "--backend", "serial", "--out", str(out)],
                                capsys)
    assert status == 2 and len(err.splitlines()) == 1
    assert "9 units, estimated at 9.0 h of CPU" in err and "--confirm-long-run" in err
    assert CALLS == [] and not list(tmp_path.iterdir())
    with pytest.raises(ValueError, match="more than 4 CPU-hours"):
        _run(out)
    BURN["seconds"] = 0.02
    status, stdout, err = in_process(["study", NAME, "--backend", "serial", "--no-progress",
                                      "--confirm-long-run", "--out", str(out)], capsys)
    assert status == 0, err
    assert stdout.startswith(f"study {NAME}: 9 units to compute, estimated at 9.0 h of CPU "
                             f"(the study's own rough figure)")
    # The next run of these options is estimated from the run log's measured times.
    seconds, n_units, basis = engine.estimate(NAME, engine.check_settings(NAME), out)
    measured = [c for c in json.loads(engine.run_log_of(out).read_text())[
        "unit_cpu_seconds"] if c > 0]
    assert n_units == 9 and "scaled to the run of" in basis and len(measured) == 9
    assert seconds == pytest.approx(9 * sum(measured) / len(measured), rel=1e-6)
    # Units already in the journal are not counted.
    engine.journal_of(out).write_text(json.dumps({"header": engine.journal_header(
        NAME, engine.check_settings(NAME))}) + "\n" + json.dumps(
        {"unit": ["reach"], "result": [5, 0.5], "cpu": 0.0,
         "sha256": records.json_digest([5, 0.5])}) + "\n")
    assert engine.estimate(NAME, engine.check_settings(NAME), out)[1] == 8


def test_every_registered_studys_default_run_starts_without_confirming():
    for name in studies.STUDIES:
        seconds, n_units, _ = engine.check_run_length(name, engine.check_settings(name))
        assert 0 < seconds < engine.MAX_CPU_HOURS * 3600 and n_units > 0
    # The remedies study at 1,000 seeds (CONTRIBUTING: about 15 CPU-hours) is not.
    seconds, _, _ = engine.estimate("remedies", engine.check_settings("remedies",
                                                                      seeds=1000))
    assert 10 * 3600 < seconds < 25 * 3600
    with pytest.raises(ValueError, match="--confirm-long-run"):
        engine.check_run_length("remedies", engine.check_settings("remedies", seeds=1000))


def test_jobs_above_this_machines_cores_are_refused(blocks, tmp_path, capsys):
    cores = os.cpu_count()
    for jobs in (str(cores + 1), "100000", "0", "-2", "two"):
        status, _, err = in_process(["study", NAME, "--jobs", jobs, "--out",
                                     str(tmp_path / "s.json")], capsys)
        assert status == 2 and f"argument --jobs: must be -1 (one per core) or an integer " \
                               f"from 1 to {cores} (this machine's cores), got {jobs!r}" in err
    assert CALLS == []
    status, _, err = in_process(["study", NAME, "--jobs", str(cores), "--backend", "serial",
                                 "--no-progress", "--out", str(tmp_path / "s.json")], capsys)
    assert status == 0, err


def test_a_dask_scheduler_that_does_not_answer_fails_within_seconds(blocks, tmp_path,
                                                                    capsys):
    import socket

    with socket.socket() as probe:  # a port nobody listens on
        probe.bind(("127.0.0.1", 0))
        address = f"tcp://127.0.0.1:{probe.getsockname()[1]}"
    start = time.monotonic()
    status, _, err = in_process(["study", NAME, "--backend", "dask", "--scheduler", address,
                                 "--out", str(tmp_path / "s.json")], capsys)
    assert time.monotonic() - start < 15  # (Dask's own default waits 30 s)
    assert status == 2 and f"no Dask scheduler answered at {address} within 5 s" in err
    assert len(err.splitlines()) == 1 and CALLS == []
    assert not (tmp_path / "s.json.journal").exists()


# --- 3. the journal, validated ---------------------------------------------------------

def _killed_run(out, at, **settings):
    """Runs the made-up study until unit `at`, where it is 'killed'."""
    KILL_AT["unit"] = at
    with pytest.raises(Killed):
        _run(out, **settings)
    KILL_AT.clear()


def test_every_finished_unit_is_in_the_journal_when_the_run_is_killed(blocks, tmp_path):
    out = tmp_path / "s.json"
    _killed_run(out, ["fast", 100, 1, 1])
    units = blocks_units(engine.check_settings(NAME))
    finished = units[:units.index(["fast", 100, 1, 1])]
    journal = engine.journal_of(out)
    assert _journal_units(journal) == finished  # each written as it finished
    done = sweep.read_journal(journal, engine.journal_header(NAME, engine.check_settings(
        NAME)), units)
    assert [json.loads(k) for k in done] == finished
    settings = engine.check_settings(NAME)
    assert [r for r, _ in done.values()] == [blocks_unit(settings, u) for u in finished]
    assert not out.exists()


def test_a_resumed_run_computes_only_the_units_not_journaled(blocks, tmp_path):
    out = tmp_path / "s.json"
    whole = _run(tmp_path / "whole.json")
    _killed_run(out, ["fast", 100, 0, 1])
    CALLS.clear()
    resumed = _run(out)
    units = blocks_units(engine.check_settings(NAME))
    assert CALLS == units[units.index(["fast", 100, 0, 1]):]
    assert {k: v for k, v in resumed.items() if k != "produced_by"} == \
        {k: v for k, v in whole.items() if k != "produced_by"}
    log = json.loads(engine.run_log_of(out).read_text())
    assert log["units_from_journal"] == 5


def test_a_journal_of_other_options_or_another_study_is_refused_naming_what_differs(
        blocks, tmp_path, capsys):
    out = tmp_path / "s.json"
    _killed_run(out, ["fast", 100, 0, 1], trials=3)
    journal = engine.journal_of(out)
    kept = journal.read_bytes()
    CALLS.clear()
    with pytest.raises(ValueError, match=r"other settings \(its trials is 3, this run's 4\)"):
        _run(out, trials=4)
    status, _, err = in_process(["study", NAME, "--trials", "4", "--backend", "serial",
                                 "--out", str(out)], capsys)
    assert status == 2 and "its trials is 3, this run's 4" in err and str(journal) in err
    header = json.loads(kept.splitlines()[0])["header"]
    journal.write_bytes(json.dumps({"header": {**header, "study": "remedies"}}).encode()
                        + b"\n" + b"\n".join(kept.splitlines()[1:]) + b"\n")
    with pytest.raises(ValueError, match="its study is 'remedies', this run's"):
        _run(out, trials=3)
    assert CALLS == [] and not out.exists()


def _record(unit, result, cpu=0.5):
    return json.dumps({"unit": unit, "result": result, "cpu": cpu,
                       "sha256": records.json_digest(result)})


@pytest.mark.parametrize("line, message", [
    (lambda r: r.replace('"result":{', '"result":7,"old":{', 1), "line 3: "),
    (lambda r: json.dumps({**json.loads(r), "result": 7}), "line 3: sha256: not that of the result"),
    (lambda r: json.dumps({**json.loads(r), "result": {"x": [1]}}),
     "line 3: sha256: not that of the result"),
    (lambda r: "7", "line 3: the whole: Input should be a valid dictionary"),
    (lambda r: json.dumps({k: v for k, v in json.loads(r).items() if k != "cpu"}),
     "line 3: cpu: Field required"),
    (lambda r: json.dumps({**json.loads(r), "cpu": -1}), "line 3: cpu: Input should be"),
    (lambda r: "", "line 3: empty"),
    (lambda r: r[:40], "line 3: not JSON"),
    (lambda r: _record(["fast", 999, 0, 1], {"x": [1]}), "line 3: the unit .* is not one of "
                                                          "this run's"),
    (lambda r: _record(["reach"], [5, 0.5]), "line 3: the unit \\[\"reach\"\\] is on line 2"),
])
def test_a_bad_record_is_refused_naming_the_file_and_line(blocks, tmp_path, capsys, line,
                                                          message):
    out = tmp_path / "s.json"
    _killed_run(out, ["slow", 200, 0, 1])
    journal = engine.journal_of(out)
    lines = journal.read_text().splitlines()
    assert len(lines) == 4  # header, reach, slow|100|0, slow|100|1
    lines[2] = line(lines[2])
    journal.write_text("\n".join(lines) + "\n")
    CALLS.clear()
    with pytest.raises(records.RecordError, match=f"journal {journal}, {message}"):
        _run(out)
    status, _, err = in_process(["study", NAME, "--backend", "serial", "--out", str(out)],
                                capsys)
    assert status == 2 and f"journal {journal}, line 3" in err and len(err.splitlines()) == 1
    assert CALLS == [] and not out.exists()  # never written from it


def test_a_journal_without_its_header_first_is_refused(tmp_path):
    journal = tmp_path / "j"
    journal.write_text(_record([1], 2) + "\n")
    with pytest.raises(records.RecordError, match="line 1: header: Field required"):
        sweep.read_journal(journal, {"a": 1}, [[1]])


def test_a_last_line_cut_short_by_a_kill_is_repaired_silently_and_its_unit_rerun(
        blocks, tmp_path):
    out = tmp_path / "s.json"
    whole = _run(tmp_path / "whole.json")
    _killed_run(out, ["fast", 100, 0, 1])
    journal = engine.journal_of(out)
    complete = journal.read_bytes()
    cut = _record(["fast", 100, 0, 1], {"x": [1], "trials": [3], "count": {"all": 1}})
    assert complete.count(b"\n") == 6  # the header and 5 units
    for tail in (cut[:30], cut):  # half a line; a whole record whose newline is missing
        journal.write_bytes(complete + tail.encode())
        assert len(sweep.read_journal(journal, engine.journal_header(
            NAME, engine.check_settings(NAME)))) == 5
        # Killed again after one more unit: the cut line is gone, the journal whole.
        CALLS.clear()
        _killed_run(out, ["fast", 100, 1, 1])
        assert CALLS == [["fast", 100, 0, 1], ["fast", 100, 1, 1]]
        text = journal.read_text()
        assert text.endswith("\n") and text.count("\n") == 7
        assert sweep.read_journal(journal, engine.journal_header(
            NAME, engine.check_settings(NAME)))  # (every line a record)
        journal.write_bytes(complete)
    CALLS.clear()
    journal.write_bytes(complete + cut[:30].encode())
    resumed = _run(out)
    units = blocks_units(engine.check_settings(NAME))
    assert CALLS == units[5:]
    assert resumed["runs"] == whole["runs"]


def test_a_header_cut_short_starts_the_journal_again(blocks, tmp_path):
    out = tmp_path / "s.json"
    engine.journal_of(out).write_text('{"header":{"stu')
    data = _run(out)
    assert data["n_seeds"] == 2 and len(CALLS) == 9


# --- retries and failures --------------------------------------------------------------

def test_a_unit_is_tried_exactly_one_plus_retries_times(blocks, tmp_path):
    unit = ["slow", 200, 1, 1]
    for retries in (0, 1, 2, 3):
        FAIL[json.dumps(unit)] = retries  # fails `retries` times, then succeeds
        CALLS.clear()
        results, _ = sweep.run_units(
            lambda u: blocks_unit(engine.check_settings(NAME), u), [unit, ["reach"]],
            backend="serial", progress=False, retries=retries)
        assert CALLS.count(unit) == retries + 1 and results[0]["x"]
        FAIL[json.dumps(unit)] = retries + 1  # one failure more than retries: fails
        CALLS.clear()
        with pytest.raises(sweep.UnitError, match=f"failed {retries + 1} time"):
            sweep.run_units(lambda u: blocks_unit(engine.check_settings(NAME), u),
                            [unit, ["reach"]], backend="serial", progress=False,
                            retries=retries)
        assert CALLS.count(unit) == retries + 1
    # A study retries twice, as CONTRIBUTING promises.
    FAIL.clear()
    FAIL[json.dumps(unit)] = 2
    CALLS.clear()
    _run(tmp_path / "s.json")
    assert CALLS.count(unit) == 3


def _fails_on_odd(unit):
    """A unit function that raises for odd units, on every attempt (module level, so
    that joblib's and Dask's workers unpickle it)."""
    if unit % 2:
        raise ZeroDivisionError(f"unit {unit} divides by zero")
    return unit * 10


@pytest.mark.parametrize("backend", ["serial", "joblib"])
def test_a_unit_that_fails_on_every_attempt_is_reported_and_the_others_kept(tmp_path,
                                                                             backend):
    journal = tmp_path / "journal"
    with pytest.raises(sweep.UnitError) as raised:
        sweep.run_units(_fails_on_odd, [0, 1, 2, 3, 4], backend=backend, n_jobs=2,
                        progress=False, journal=journal, header={"h": 1})
    error = raised.value
    assert sorted(u for u, _, _ in error.failures) == [1, 3]
    assert all(attempts == 3 for _, attempts, _ in error.failures)
    assert "failed 3 time(s) (ZeroDivisionError: unit" in str(error)
    assert "1 other unit(s) failed too" in str(error) and "3 unit(s) that finished" in str(error)
    assert sorted(_journal_units(journal)) == [0, 2, 4]  # the others computed and kept


def test_a_failed_unit_is_reported_in_one_line_by_the_command(blocks, tmp_path, capsys):
    unit = ["fast", 200, 0, 1]
    FAIL[json.dumps(unit)] = 3  # more than the two retries
    out = tmp_path / "s.json"
    status, _, err = in_process(["study", NAME, "--backend", "serial", "--no-progress",
                                 "--out", str(out)], capsys)
    assert status == 2 and len(err.splitlines()) == 1
    assert f'unit {json.dumps(unit, separators=(",", ":"))} failed 3 time(s) ' \
           f'(RuntimeError: transient failure of' in err
    assert "the 8 unit(s) that finished are kept in the journal" in err
    assert not out.exists() and len(_journal_units(engine.journal_of(out))) == 8
    CALLS.clear()
    _run(out)  # run again: only the failed unit is computed
    assert CALLS == [unit]


# --- the study file: its mode and the command it records ------------------------------

def test_the_study_file_has_the_mode_a_new_file_gets_and_its_run_log_what_ran(blocks,
                                                                             tmp_path):
    for umask in (0o022, 0o077, 0o002):
        old = os.umask(umask)
        try:
            out = tmp_path / f"s{umask:o}.json"
            _run(out)
        finally:
            os.umask(old)
        assert out.stat().st_mode & 0o777 == 0o666 & ~umask
        assert engine.run_log_of(out).stat().st_mode & 0o777 == 0o666 & ~umask
    out = tmp_path / "joblib.json"
    studies.run_study(NAME, out, backend="joblib", n_jobs=2, progress=False)
    log = json.loads(engine.run_log_of(out).read_text())
    assert log["backend"] == "joblib" and log["n_jobs"] == 2 and log["units"] == 9
    assert log["study"] == NAME and log["settings"] == engine.check_settings(NAME)
    assert len(log["unit_cpu_seconds"]) == 9


def _settings_of_command(command):
    """The settings the command line reads from a recorded command."""
    words = command.split()
    assert words[:4] == ["python", "-m", "icm", "study"]
    args = cli.build_parser().parse_args(words[3:] + ["--out", "x.json"])
    study = studies.STUDIES[args.name]
    return engine.check_settings(args.name, args.seeds,
                                 **{o: getattr(args, o) for o in study.options})


def test_the_recorded_command_runs_the_recorded_settings(blocks, tmp_path):
    data = _run(tmp_path / "s.json", seeds=6, trials=2)
    made = data["produced_by"]
    assert made["command"] == (f"python -m icm study {NAME} --seeds 6 --rollouts 10 "
                               f"--trials 2 --reach-movements 5 --length 0")
    assert made["settings"]["length"] is None  # (as the study's check reads 0)
    assert _settings_of_command(made["command"]) == made["settings"]
    # Every registered study's command, at its defaults and at other sizes, reads back
    # as the settings it records (robustness' length 0 is stored as None).
    for name, study in studies.STUDIES.items():
        for pick in (0, 1):  # each option's default, then its least value
            given = {"seeds": study.seeds[0],
                     **{o: spec[pick] for o, spec in study.options.items()}}
            command = engine.command_of(name, given)
            assert _settings_of_command(command) == engine.check_settings(name, **given), \
                command


# --- --import-seeds ---------------------------------------------------------------------

@pytest.mark.parametrize("content, message", [
    (None, "does not exist"),
    ("{", "not JSON"),
    ("[1, 2]", "the whole: Input should be"),
    (json.dumps({"produced_by": {"study": "remedies"}}), "a file of study 'remedies'"),
    (json.dumps({"n_seeds": 1, "n_rollouts": 10, "n_trials": 3, "runs": {"slow": {}},
                 "produced_by": {"study": NAME}}), "runs: Value error, 'slow' has no root"),
    (json.dumps({"n_seeds": 0, "n_rollouts": 10, "n_trials": 3, "runs": {"slow": {"100": {}}},
                 "produced_by": {"study": NAME}}), "n_seeds: Input should be greater"),
    (json.dumps({"n_seeds": 1, "n_rollouts": 10, "n_trials": 3,
                 "runs": {"slow": {"-1": {}}}, "produced_by": {"study": NAME}}),
     "'-1' is not a root seed"),
    ("FOLDER", "not a file but a folder"),
])
def test_a_malformed_import_file_is_refused_in_one_line_naming_it(blocks, tmp_path, capsys,
                                                                  content, message):
    source = tmp_path / "old.json"
    if content == "FOLDER":
        source.mkdir()
    elif content is not None:
        source.write_text(content)
    status, _, err = in_process(["study", NAME, "--seeds", "4", "--out",
                                 str(tmp_path / "s.json"), "--import-seeds", str(source)],
                                capsys)
    assert status == 2 and f"--import-seeds {source}" in err and message in err, err
    assert len(err.splitlines()) == 1 and CALLS == []


def test_an_earlier_file_with_one_seed_per_root_is_imported(blocks, tmp_path, capsys):
    source = tmp_path / "old.json"
    _run(source, seeds=2)  # one seed per root
    whole = _run(tmp_path / "whole.json", seeds=6)
    CALLS.clear()
    out = tmp_path / "s.json"
    status, stdout, err = in_process(["study", NAME, "--seeds", "6", "--backend", "serial",
                                      "--no-progress", "--out", str(out), "--import-seeds",
                                      str(source)], capsys)
    assert status == 0, err
    assert "8 units to compute" in stdout  # (the 4 blocks and 'reach' imported)
    data = json.loads(out.read_text())
    imported = data["produced_by"]["imported"]
    assert imported["seeds_per_root"] == 1
    assert imported["checked"] == [["slow", 100, 0, 1], ["fast", 200, 0, 1], ["reach"]]
    assert data["runs"] == whole["runs"] and data["reach"] == whole["reach"]
    # The checks, then the seeds not imported: none of the imported computed again.
    assert CALLS[:3] == imported["checked"]
    assert sorted(CALLS[3:]) == sorted(u for u in blocks_units(engine.check_settings(
        NAME, seeds=6)) if u != ["reach"] and u[2] > 0)


def test_an_imported_entry_of_the_wrong_shape_or_numbers_is_refused(blocks, tmp_path):
    source = tmp_path / "old.json"
    _run(source, seeds=4)
    good = json.loads(source.read_text())
    for change, message in [
            (lambda d: d["runs"]["fast"]["200"].update(x=[1]), r"runs\['fast'\]\['200'\]: "
                                                               r"x must hold one value per seed"),
            (lambda d: d["runs"]["fast"]["200"].pop("trials"), "lacks 'trials'"),
            (lambda d: d["runs"]["fast"]["200"].update(count=7), "count must be a dict"),
            (lambda d: d["runs"]["slow"].update({"300": d["runs"]["slow"]["100"]}),
             "holds 'slow' on root 300, which study"),
            (lambda d: d["runs"]["slow"]["100"]["x"].reverse(),
             r"recomputing unit \['slow', 100, 0, 1\] does not give"),
            (lambda d: d.update(reach=[1, 2]), "recomputing 'reach'"),
            (lambda d: d["produced_by"]["settings"].update(reach_movements=6),
             "computed with reach_movements 6, the run with 5")]:
        data = json.loads(json.dumps(good))
        change(data)
        source.write_text(json.dumps(data))
        with pytest.raises(ValueError, match=message):
            studies.import_seeds(NAME, tmp_path / "s.json", source, seeds=8,
                                 backend="serial", progress=False)
        assert not engine.journal_of(tmp_path / "s.json").exists()


def test_an_import_run_again_after_a_kill_does_not_journal_its_seeds_twice(blocks, tmp_path):
    source = tmp_path / "old.json"
    _run(source, seeds=2)
    out = tmp_path / "s.json"
    for _ in range(2):
        kept, extra = studies.import_seeds(NAME, out, source, seeds=4, backend="serial",
                                           progress=False)
    assert len(_journal_units(engine.journal_of(out))) == 5  # four blocks and 'reach'
    data = _run(out, seeds=4, imported_seeds=kept, extra=extra)
    assert data["produced_by"]["imported"]["seeds_per_root"] == 1
