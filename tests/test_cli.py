"""The command line: figures without Jupyter, clear errors for bad options."""

import pathlib
import subprocess
import sys

import matplotlib.image
import pytest

from icm import cli


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "icm", *args], capture_output=True,
                          text=True, cwd=cwd)


def in_process(args, capsys):
    """Runs the command line in this process: (exit status, stdout, stderr)."""
    try:
        status = cli.main(args)
    except SystemExit as exit_:
        status = exit_.code
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_help_documents_every_figure_and_option(capsys):
    top = run("--help")  # once through `python -m icm`, as users call it
    assert top.returncode == 0
    for name in cli.COMMANDS:
        assert name in top.stdout
        status, out, _ = in_process([name, "--help"], capsys)
        assert status == 0
        for option in ("--seed", "--out", "--dpi"):
            assert option in out
    assert "--epsilon" in in_process(["figure5", "--help"], capsys)[1]
    assert "--temperature" in in_process(["figure6", "--help"], capsys)[1]
    assert "--predictor-lr" in in_process(["figure7", "--help"], capsys)[1]
    babbling_help = in_process(["goal-babbling", "--help"], capsys)[1]
    for option in ("--strategy", "--rollouts", "--exploration-noise", "--window",
                   "--outcome-space", "--inverse-model", "--measure", "--regions", "--threads",
                   "--maturation", "--demonstrations"):
        assert option in babbling_help


@pytest.mark.parametrize("args", [["figure6", "--seeds", "3", "--trials", "10"],
                                  ["figure7", "--episodes", "20"]])
def test_figures_6_and_7_are_written(args, tmp_path, capsys):
    out = tmp_path / "fig.png"
    status, stdout, _ = in_process(args + ["--out", str(out)], capsys)
    assert status == 0 and out.exists() and "wrote" in stdout


def test_figure5_is_written_as_an_image(tmp_path):
    out = tmp_path / "fig5.png"
    completed = run("figure5", "--seeds", "5", "--trials", "10", "--out", str(out))
    assert completed.returncode == 0, completed.stderr
    image = matplotlib.image.imread(out)
    assert image.shape[0] > 100 and image.std() > 0.01


@pytest.mark.parametrize("args, message", [
    (["figure9"], "invalid choice"),
    (["figure5", "--seeds", "0"], "--seeds"),
    (["figure5", "--seeds", "many"], "--seeds"),
    (["figure5", "--epsilon", "2"], "--epsilon: must be a number in [0, 1], got '2'"),
    (["figure5", "--window", "1"], "--window: must be an integer in 2..100"),
    (["figure5", "--reading", "sideways"], "--reading"),
    (["figure5", "--out", "fig.gif"], "--out must end in"),
    (["figure5", "--out", "/no/such/folder/fig.png"], "does not exist"),
    (["figure5", "--seed", "-1"], "--seed"),
    (["figure6", "--lr-actor", "0"], "--lr-actor: must be a number in (0, 1]"),
    (["figure6", "--variant", "backwards"], "--variant"),
    (["figure7", "--predictor-lr", "1.5"], "--predictor-lr: must be a number in (0, 1]"),
    (["figure5", "--tie", "sideways"], "--tie"),
    (["goal-babbling", "--rollouts", "0"], "--rollouts: must be an integer >= 1"),
    (["goal-babbling", "--strategy", "curious"], "--strategy"),
    (["goal-babbling", "--exploration-noise", "0"],
     "--exploration-noise: must be a number in (0, 1], got '0'"),
    (["goal-babbling", "--epsilon", "x"], "--epsilon: must be a number"),
    (["goal-babbling", "--window", "1"], "--window: must be an integer >= 2"),
    (["goal-babbling", "--outcome-space", "depth"], "--outcome-space"),
    (["goal-babbling", "--inverse-model", "lwpr"], "--inverse-model"),
    (["goal-babbling", "--measure", "novelty"], "--measure"),
    (["goal-babbling", "--regions", "tree"], "--regions"),
    (["goal-babbling", "--threads", "0"], "--threads: must be an integer >= 1"),
    (["goal-babbling", "--maturation", "grow"], "--maturation"),
    (["goal-babbling", "--demonstrations", "x"], "--demonstrations: must be buttons"),
    (["goal-babbling", "--demonstrations", "7", "--rollouts", "3"],
     "demonstrations must be buttons 0 to 4, each shown at most once, got (7,)"),
    (["goal-babbling", "--demonstrations", "1,1", "--rollouts", "3"],
     "demonstrations must be buttons 0 to 4, each shown at most once, got (1, 1)"),
])
def test_bad_options_fail_with_a_clear_message(args, message, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    status, _, err = in_process(args, capsys)
    assert status == 2
    assert message in err
    assert not list(tmp_path.iterdir())  # nothing written


@pytest.mark.parametrize("args", [["figure5", "--seeds", "many"], ["figure5", "--seed", "x"],
                                  ["figure5", "--window", "1.5"], ["figure6", "--gamma", "y"],
                                  ["figure7", "--run", "-2"], ["figure5", "--dpi", "0"]])
def test_error_messages_name_the_option_and_leak_no_internal_names(args, tmp_path,
                                                                    monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    status, _, err = in_process(args, capsys)
    assert status == 2 and args[1] in err
    assert "_positive_int" not in err and "_seed" not in err and "parse" not in err
    assert "_number" not in err and "invalid" not in err


def test_goal_babbling_prints_the_numbers_and_writes_the_test_error(tmp_path, capsys):
    out = tmp_path / "babbling.png"
    status, stdout, _ = in_process(["goal-babbling", "--strategy", "random_goal", "--seeds",
                                    "1", "--rollouts", "25", "--outcome-space", "point",
                                    "--threads", "1", "--out", str(out)], capsys)
    assert status == 0 and "wrote" in stdout
    assert "| random_goal | 1 | 25 |" in stdout
    image = matplotlib.image.imread(out)
    assert image.shape[0] > 100 and image.std() > 0.01


def test_goal_babbling_grows_up_and_is_shown_buttons(tmp_path, monkeypatch, capsys):
    from icm import experiments

    calls = []
    real = experiments.run_goal_babbling
    monkeypatch.setattr(experiments, "run_goal_babbling",
                        lambda **kwargs: calls.append(kwargs) or real(**kwargs))
    out = tmp_path / "babbling.png"
    status, stdout, _ = in_process(["goal-babbling", "--strategy", "learning_progress",
                                    "--seeds", "1", "--rollouts", "25", "--maturation",
                                    "joint_range", "--demonstrations", "0,4", "--threads", "1",
                                    "--out", str(out)], capsys)
    assert status == 0 and "wrote" in stdout and out.exists()
    assert calls[0]["maturation"] == "joint_range" and calls[0]["demonstrations"] == (0, 4)
    status, _, _ = in_process(["goal-babbling", "--strategy", "random_goal", "--seeds", "1",
                               "--rollouts", "2", "--demonstrations", "none", "--threads", "1",
                               "--out", str(out)], capsys)
    assert status == 0 and calls[1]["demonstrations"] == ()


def test_goal_babbling_shows_its_progress_on_the_terminal(tmp_path, monkeypatch, capsys):
    # The run's progress bar is on (tqdm's: on standard error in a terminal, shown once
    # a run lasts over a second, which a short run here may not), the table on
    # standard output.
    from icm.experiments import loop  # every run's bar is the one loop's observer

    bars = []
    real = loop.progress_bar

    def recording(iterable, total, description, enabled=True, unit="seed"):
        bars.append((description, enabled, unit))
        return real(iterable, total, description, enabled, unit)

    monkeypatch.setattr(loop, "progress_bar", recording)
    out = tmp_path / "babbling.png"
    status, stdout, _ = in_process(
        ["goal-babbling", "--strategy", "learning_progress", "--seeds", "2", "--rollouts",
         "30", "--maturation", "joint_range", "--demonstrations", "2", "--threads", "1",
         "--out", str(out)], capsys)
    assert status == 0 and "| learning_progress | 2 | 30 |" in stdout
    assert "(maturation joint_range, the teacher showed button 2)" in stdout
    assert ("goal babbling (learning_progress, 2 seeds at once)", True, "rollout") in bars


def test_figure7_of_run_n_computes_that_run_alone(tmp_path, monkeypatch, capsys):
    from icm import experiments

    calls = []
    real = experiments.run_rod_toppling
    monkeypatch.setattr(experiments, "run_rod_toppling",
                        lambda **kwargs: calls.append(kwargs) or real(**kwargs))
    status, _, _ = in_process(["figure7", "--run", "3", "--episodes", "6", "--out",
                               str(tmp_path / "f.png")], capsys)
    assert status == 0
    assert len(calls) == 1 and calls[0]["n_seeds"] == 1 and calls[0]["first_run"] == 3


def _link_to_a_notebook(folder):
    """An --out named like an image, a symbolic link to a student's notebook."""
    (folder / "notes.ipynb").write_text("{}")
    (folder / "fig.png").symlink_to(folder / "notes.ipynb")
    return folder / "fig.png"


@pytest.mark.parametrize("make_out, message", [
    (lambda d: (d / "a_folder.png").mkdir() or d / "a_folder.png", "must be a file to write"),
    (lambda d: pathlib.Path("/proc/fig5.png"), "cannot be written"),
    (lambda d: _link_to_a_notebook(d), "not a symbolic link"),
])
def test_an_out_that_cannot_be_written_is_refused_before_anything_runs(make_out, message,
                                                                      tmp_path, monkeypatch,
                                                                      capsys):
    from icm import experiments

    out = make_out(tmp_path)
    ran = []
    monkeypatch.setattr(experiments, "run_goal_oriented", lambda **kw: ran.append(kw))
    status, _, err = in_process(["figure5", "--out", str(out)], capsys)
    assert status == 2 and message in err and "Traceback" not in err
    assert ran == []  # refused before the run
    if (tmp_path / "notes.ipynb").exists():
        assert (tmp_path / "notes.ipynb").read_text() == "{}"


def test_an_image_is_replaced_whole_or_not_at_all(tmp_path, monkeypatch, capsys):
    import matplotlib.figure

    out = tmp_path / "fig5.png"
    out.write_bytes(b"the earlier image")

    def dies_half_way(self, target, **kwargs):
        target.write(b"half an image")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", dies_half_way)
    status, _, err = in_process(["figure5", "--seeds", "2", "--trials", "4", "--out",
                                 str(out)], capsys)
    assert status == 2 and "No space left on device" in err
    assert out.read_bytes() == b"the earlier image"
    assert [p.name for p in tmp_path.iterdir()] == ["fig5.png"]  # no half-written file


def test_a_huge_dpi_is_refused_in_one_line(capsys):
    status, _, err = in_process(["figure5", "--dpi", "100000"], capsys)
    assert status == 2 and "--dpi: must be an integer from 1 to 1200" in err
