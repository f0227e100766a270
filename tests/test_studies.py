"""The long studies on the sweep engine (icm.studies, sweep.run_units): the
same bytes on any backend, a killed run resumed, a killed Dask worker's unit retried,
every registered study run tiny, and bad input refused."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from icm import chapters, cli
import importlib

from icm import studies
from icm.studies import engine, registry
from icm.studies.forming_actions import arms
from icm.studies.forming_actions import remedies as remedies_study
from icm.studies.forming_actions import strategies as goal_babbling_study
from icm.experiments.goal_oriented import run_goal_oriented
from icm.experiments.sweep import read_journal, run_units, sweep

sweep_module = importlib.import_module("icm.experiments.sweep")
ROOT = Path(__file__).resolve().parents[1]
TINY = {"seeds": 3, "trials": 10, "episodes": 10}
"""A curiosity study that takes seconds: 3 seeds, 10 trials, 10 episodes."""


def _tiny(out, **run):
    return studies.run_study("curiosity", out, progress=False, **TINY, **run)


@pytest.fixture(scope="module")
def serial_bytes(tmp_path_factory):
    out = tmp_path_factory.mktemp("serial") / "study.json"
    _tiny(out, backend="serial")
    return out.read_bytes()


def test_a_study_is_byte_identical_serially_on_joblib_and_on_a_dask_cluster(tmp_path,
                                                                              serial_bytes):
    from dask import distributed

    _tiny(tmp_path / "joblib.json", backend="joblib", n_jobs=2)
    assert (tmp_path / "joblib.json").read_bytes() == serial_bytes
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        _tiny(tmp_path / "dask.json", backend="dask", client=client)
    assert (tmp_path / "dask.json").read_bytes() == serial_bytes
    data = json.loads(serial_bytes)
    made = data["produced_by"]
    assert made["study"] == "curiosity" and made["settings"] == {**TINY}
    assert set(made["versions"]) == {"python", "icm", "numpy", "mujoco"}
    assert made["units"] == studies.STUDIES["curiosity"].units(made["settings"])
    # A unit is what the library computes for it, not a copy of another's.
    first = run_goal_oriented(n_seeds=3, n_trials=10, interest="learning_progress",
                              interest_per="task", noisy_button=False, seed=0, progress=False)
    assert data["signals"]["learning_progress|task|False"] == \
        json.loads(json.dumps(registry.plain(first.seed_summaries())))
    # The run log (times, backend) is beside the file, not in it; the journal is gone.
    log = [json.loads(line) for line in
           engine.run_log_of(tmp_path / "joblib.json").read_text().splitlines()]
    assert log[0]["backend"] == "joblib" and log[0]["units"] == len(made["units"])
    assert not engine.journal_of(tmp_path / "joblib.json").exists()


def _journal_lines(path):
    """The units a journal holds (its lines after the header)."""
    return max(path.read_text().count("\n") - 1, 0) if path.exists() else 0


def test_a_study_killed_half_way_resumes_from_its_journal_to_the_same_bytes(tmp_path,
                                                                            serial_bytes):
    out = tmp_path / "study.json"
    journal = engine.journal_of(out)
    command = [sys.executable, "-m", "icm", "study", "curiosity", "--seeds", "3",
               "--trials", "10", "--episodes", "10", "--backend", "serial",
               "--no-progress", "--out", str(out)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    n_units = len(studies.STUDIES["curiosity"].units(studies.check_settings("curiosity",
                                                                             **TINY)))
    process = subprocess.Popen(command, env=env, cwd=tmp_path)
    deadline = time.monotonic() + 300
    while _journal_lines(journal) < 3 and process.poll() is None and \
            time.monotonic() < deadline:
        time.sleep(0.01)
    process.send_signal(signal.SIGKILL)
    process.wait()
    saved = _journal_lines(journal)
    assert 3 <= saved < n_units and not out.exists(), saved  # killed half-way
    # A write cut short by the kill: the last line half there. It is dropped and rerun.
    with open(journal, "a") as file:
        file.write('{"unit":["signal","nov')
    assert len(read_journal(journal, engine.journal_header("curiosity", {**TINY}))) == saved
    subprocess.run(command, env=env, cwd=tmp_path, check=True, capture_output=True)
    assert out.read_bytes() == serial_bytes
    log = json.loads(engine.run_log_of(out).read_text().splitlines()[-1])
    assert log["units_from_journal"] == saved


def test_a_journal_of_other_settings_is_refused(tmp_path):
    out = tmp_path / "study.json"
    engine.journal_of(out).write_text(json.dumps({"header": {**TINY, "trials": 11}})
                                       + "\n")
    with pytest.raises(ValueError, match="written by a run of other settings"):
        _tiny(out, backend="serial")
    journal = tmp_path / "j"
    run_units(abs, [-1, -2], backend="serial", progress=False, journal=journal,
              header={"a": 1})
    assert run_units(abs, [-1, -2, -3], backend="serial", progress=False,
                     journal=journal, header={"a": 1})[0] == [1, 2, 3]
    with pytest.raises(ValueError, match="other settings"):
        run_units(abs, [-1], backend="serial", progress=False, journal=journal,
                  header={"a": 2})


def test_a_journal_with_a_broken_line_in_the_middle_is_refused(tmp_path):
    journal = tmp_path / "j"
    run_units(abs, [-1, -2], backend="serial", progress=False, journal=journal)
    header, first, second = journal.read_text().splitlines()
    journal.write_text("\n".join([header, first, "not json", second]) + "\n")
    with pytest.raises(ValueError, match="line 3: not JSON"):
        read_journal(journal)


def _kill_worker_once(marker, unit):
    """The unit's square; the first call (the marker file absent) kills its process."""
    if not os.path.exists(marker):
        Path(marker).write_text("killed")
        os.kill(os.getpid(), signal.SIGKILL)
    return unit * unit


def test_a_dask_worker_killed_mid_run_costs_only_its_unit_and_the_result_is_unchanged(tmp_path):
    import functools

    from dask import distributed

    marker = tmp_path / "killed"
    fn = functools.partial(_kill_worker_once, str(marker))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        results, _ = run_units(fn, list(range(8)), backend="dask", client=client,
                               progress=False, journal=tmp_path / "journal")
    assert marker.exists()  # a worker did die
    assert results == [u * u for u in range(8)]
    assert sorted(json.loads(line)["unit"] for line in
                  (tmp_path / "journal").read_text().splitlines()[1:]) == list(range(8))


def test_every_registered_study_runs_tiny(tmp_path):
    sizes = {"remedies": {"seeds": 4, "rollouts": 12, "trials": 3, "reach_movements": 5},
             "goal-babbling": {"seeds": 2, "rollouts": 12, "trials": 3},
             "robustness": {"seeds": 2, "length": 3},
             "curiosity": {"seeds": 2, "trials": 3, "episodes": 3},
             "remedies-replication": {"seeds": 1, "rollouts": 12, "trials": 3}}
    assert set(sizes) == set(studies.STUDIES)
    for name, size in sizes.items():
        data = studies.run_study(name, tmp_path / f"{name}.json", backend="joblib",
                                 n_jobs=2, progress=False, **size)
        assert json.loads((tmp_path / f"{name}.json").read_text()) == \
            json.loads(json.dumps(data))
    # The remedies' file is what the chapter's code reads, and its entries are those of
    # one batched run of the same seeds (seed i of a root is the same run alone).
    remedies = json.loads((tmp_path / "remedies.json").read_text())
    assert remedies["n_seeds"] == 1 and remedies["budgets"] == [12]
    assert remedies["n_rollouts"] == 12 and remedies["n_trials"] == 3
    chapters.forming_actions.remedies.summary(remedies)
    batched = remedies_study.run_condition("growing up", 300, n_seeds=1, n_rollouts=12,
                                           n_trials=3)
    assert remedies["runs"]["growing up"]["300"] == json.loads(json.dumps(batched))
    # The replication runs' file is the one remedies_study.load_fresh_runs reads.
    fresh = json.loads((tmp_path / "remedies-replication.json").read_text())
    assert fresh["root"] == 9001 and fresh["n_seeds"] == 1
    assert list(fresh["runs"]) == list(remedies_study.CLAIMED)
    assert fresh["runs"]["growing up"] == [json.loads(json.dumps(
        remedies_study.run_condition("growing up", 9001, 1, n_rollouts=12, n_trials=3)))]
    babbling = json.loads((tmp_path / "goal-babbling.json").read_text())
    assert babbling["n_rollouts"] == 12 and babbling["n_trials"] == 3
    assert list(babbling["runs"]["learning progress"]) == ["100", "200", "300", "400"]
    assert list(babbling["runs"]["LWLR inverse model"]) == ["100", "200"]
    data = json.loads((tmp_path / "robustness.json").read_text())
    maps = studies.robustness.results_of(data)
    assert set(maps) == {"goal_oriented", "actor_critic", "rod_toppling"}
    assert len(maps["goal_oriented"].points()) > 0
    # A map point's unit gives the rows run_robustness's sweep gives for that point.
    from icm.studies import robustness

    study = robustness.STUDIES["rod_toppling"]
    (a, b), grid = robustness.pair_grids(study)[0]
    point = {a: grid[a][-1], b: grid[b][-1]}
    others = {n: v for n, v in study.defaults().items() if n not in (a, b)}
    frame = sweep(study.run_fn, {a: [point[a]], b: [point[b]]}, n_seeds=2, seed=0,
                  per_seed=study.per_seed, progress=False,
                  **{**study.fixed, "n_episodes": 3}, **others)
    rows = [r for r in data["maps"]["rod_toppling"][f"{a}|{b}"]
            if r[a] == point[a] and r[b] == point[b]]
    assert rows == json.loads(json.dumps(registry.plain(frame.to_dict("records"))))


def test_the_trials_asked_for_are_the_trials_on_the_formed_presses(monkeypatch, tmp_path):
    from icm.experiments import formed_actions

    asked, real = [], formed_actions.run_formed_actions

    def recording(result, n_trials=formed_actions.DEFAULT_TRIALS, **others):
        asked.append(n_trials)
        return real(result, n_trials=n_trials, **others)

    monkeypatch.setattr(formed_actions, "run_formed_actions", recording)
    for name, unit in [("remedies", ["growing up", 100, 0, 1]),
                       ("goal-babbling", ["learning progress", 100, 0, 1])]:
        settings = studies.check_settings(name, rollouts=12, trials=3)
        studies.STUDIES[name].run_unit(settings, unit)
    assert asked == [3, 3]
    # A study's seeds are imported only into a run of the same trials.
    source = tmp_path / "source.json"
    source.write_text(json.dumps({"n_seeds": 1, "n_rollouts": 12, "n_trials": 30,
                                  "runs": {"growing up": {"100": {}}},
                                  "produced_by": {"study": "remedies"}}))
    with pytest.raises(ValueError, match="has 30 trials on the formed presses, the run 3"):
        studies.import_seeds("remedies", tmp_path / "out.json", source, seeds=8, rollouts=12,
                             trials=3, progress=False)


def test_seed_blocks_join_into_one_entry():
    a = {"x": [1, 2], "coverage": {"all": [[1, 0], [0, 2]]}}
    b = {"x": [3], "coverage": {"all": [[0, 5], [1, 1]]}}
    assert arms.join_entries([a, b]) == {"x": [1, 2, 3],
                                            "coverage": {"all": [[1, 5], [1, 3]]}}


def test_remedies_seeds_run_one_at_a_time_are_those_of_a_batched_run():
    batched = remedies_study.run_condition("shown button 2", 200, n_seeds=2, n_rollouts=15)
    parts = [remedies_study.run_condition("shown button 2", 200, n_seeds=1, first_run=i,
                                          n_rollouts=15) for i in (0, 1)]
    assert arms.join_entries(parts) == batched
    assert parts[0] != parts[1]


def test_bad_input_is_refused():
    with pytest.raises(TypeError, match="fn must be a function of one unit"):
        run_units(3, [1])
    with pytest.raises(TypeError, match="units must be JSON values"):
        run_units(abs, [object()])
    with pytest.raises(ValueError, match="units must be distinct"):
        run_units(abs, [1, 2, 1])
    with pytest.raises(ValueError, match="backend"):
        run_units(abs, [1], backend="spark")
    with pytest.raises(ValueError, match="n_jobs"):
        run_units(abs, [1], n_jobs=0)
    with pytest.raises(ValueError, match="scheduler are used only with backend 'dask'"):
        run_units(abs, [1], scheduler="tcp://127.0.0.1:1")
    with pytest.raises(ValueError, match="seeds must be a multiple of the 4 root seeds"):
        studies.check_settings("remedies", seeds=6)
    with pytest.raises(ValueError, match="'episodes' is not an option of study 'remedies'"):
        studies.check_settings("remedies", episodes=3)
    with pytest.raises(ValueError, match="trials must be an integer in 1..1000000, got 0"):
        studies.check_settings("goal-babbling", trials=0)
    with pytest.raises(ValueError, match="rollouts must be an integer in 1..1000000, got 0"):
        studies.check_settings("remedies", rollouts=0)
    with pytest.raises(ValueError, match="name"):
        studies.check_settings("remedy")
    with pytest.raises(ValueError, match="first_run"):
        remedies_study.run_condition("growing up", 100, n_seeds=1, first_run=-1)
    # Refused before any babbling, also where no learner runs on the formed presses.
    with pytest.raises(ValueError, match="n_trials must be an integer >= 1, got 0"):
        remedies_study.run_condition("growing up", 100, n_seeds=1, n_trials=0)
    with pytest.raises(ValueError, match="n_trials must be an integer >= 1, got 0"):
        goal_babbling_study.run_variant("LWLR inverse model", 100, n_seeds=1, n_trials=0)


def test_sweep_refuses_a_per_seed_or_run_fn_of_the_wrong_kind():
    with pytest.raises(TypeError, match="per_seed must be a function you write.*len"):
        sweep(run_goal_oriented, {"epsilon": [0.1]}, per_seed=len, progress=False)
    with pytest.raises(TypeError, match="per_seed must be a function"):
        sweep(run_goal_oriented, {"epsilon": [0.1]}, per_seed=lambda: [], progress=False)
    with pytest.raises(TypeError, match="run_fn must be an experiment function.*n_seeds"):
        sweep(len, {"x": [1]}, progress=False)
    with pytest.raises(TypeError, match="per_seed must return a list of one dict per seed"):
        sweep(run_goal_oriented, {"epsilon": [0.1]}, n_seeds=2, n_trials=2,
              per_seed=lambda result: "rows", progress=False)


def test_the_command_line_runs_a_study_and_refuses_what_it_cannot(tmp_path, capsys,
                                                                  serial_bytes):
    out = tmp_path / "c.json"
    # On a Dask cluster of its own (2 workers), the same bytes as serially.
    assert cli.main(["study", "curiosity", "--seeds", "3", "--trials", "10", "--episodes",
                     "10", "--backend", "dask", "--jobs", str(min(2, os.cpu_count())),
                     "--no-progress",
                     "--out", str(out)]) == 0
    assert out.read_bytes() == serial_bytes
    for argv, message in [
            (["study", "remedies", "--seeds", "5", "--out", str(out)], "multiple of the 4"),
            (["study", "remedies", "--episodes", "5", "--out", str(out)], "--episodes is not"),
            (["study", "curiosity", "--scheduler", "tcp://x:1", "--out", str(out)],
             "--scheduler needs --backend dask"),
            (["study", "curiosity", "--jobs", "0", "--out", str(out)], "--jobs: must be")]:
        with pytest.raises(SystemExit):
            cli.main(argv)
        assert message in capsys.readouterr().err


def test_the_remedies_file_records_what_produced_it_and_its_imported_seeds_were_checked():
    study = remedies_study.load_study()
    made = study["produced_by"]
    assert made["study"] == "remedies" and study["n_seeds"] == remedies_study.N_SEEDS
    assert made["settings"]["seeds"] == remedies_study.N_SEEDS * len(remedies_study.ROOTS)
    # Seeds kept from an earlier file are recorded with their check: at least one
    # recomputed unit of every condition, and one whole block. (The file of 2026-12-03
    # was computed whole: its arithmetic had changed, so no earlier seed could be kept.)
    imported = made.get("imported")
    assert (imported is None) == (made["settings"].get("imported_seeds", 0) == 0)
    if imported is not None:
        assert {u[0] for u in imported["checked"] if len(u) == 4} == \
            set(remedies_study.CONDITIONS)
        assert any(u[3] == imported["seeds_per_root"] for u in imported["checked"]
                   if len(u) == 4)
    per_root = {}
    for unit in made["units"]:
        if len(unit) == 4:
            per_root.setdefault((unit[0], unit[1]), []).append(unit)
    for blocks in per_root.values():  # every seed of every root, once
        covered = [i for _, _, first, n in blocks for i in range(first, first + n)]
        assert covered == list(range(study["n_seeds"]))
    for label, by_root in study["runs"].items():
        for entry in by_root.values():
            assert len(entry["test_error"]) == study["n_seeds"]
            assert np.array(entry["pressed"]).shape[0] == study["n_seeds"]
    # What computing it took, for the chapter: the imported seeds are not counted.
    times = remedies_study.study_times()
    kept = 0 if imported is None else imported["seeds_per_root"] * len(remedies_study.ROOTS)
    assert times["seeds_per_condition"] == 80 and times["imported_seeds_per_condition"] == kept
    reach = 1 if imported is None else 0  # the 'reach' unit, imported with the seeds
    assert times["units_computed"] == len(remedies_study.CONDITIONS) * (80 - kept) + reach
    assert 0 < times["cpu_hours"] and 0 < times["wall_hours"]


def test_the_engine_module_is_the_sweep_module():
    # One engine: the studies run on sweep's run_units, not a copy of it.
    assert engine.run_units is sweep_module.run_units
