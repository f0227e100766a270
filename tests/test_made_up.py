"""A made-up interest signal added in one file (tests/made_up_signal.py), run in a study
end to end: the study "curiosity" runs it on the buttons and, as a reward, on the rods'
compiled loop, and what it pays there is not zero. A signal that names a formula the
compiled loop does not have is refused by name, never paid 0 (issue 45, point 4)."""

import importlib
import json
import sys

import numpy as np
import pytest

from icm.experiments import run_goal_oriented, run_rod_toppling
from icm.learners import interest
from icm.studies import engine, registry


@pytest.fixture
def made_up_signal(monkeypatch):
    """tests/made_up_signal.py imported, which registers its signal (the registry is
    restored after the test)."""
    monkeypatch.setattr(interest, "SIGNAL_CLASSES", dict(interest.SIGNAL_CLASSES))
    if "made_up_signal" in sys.modules:  # imported by an earlier test: register again
        return importlib.reload(sys.modules["made_up_signal"]).LastErrorInterest.NAME
    return importlib.import_module("made_up_signal").LastErrorInterest.NAME


def test_a_made_up_signal_runs_in_a_study_and_earns_a_reward(made_up_signal, tmp_path):
    name = made_up_signal
    out = tmp_path / "curiosity.json"
    engine.run_study("curiosity", out, seeds=2, backend="serial", progress=False,
                     trials=10, episodes=10)
    data = json.loads(out.read_text())
    # The study ran it in both worlds, on the buttons and on the rods, as its own rows.
    assert {f"{name}|{per}|{noisy}" for per in ("task", "region") for noisy in
            (False, True)} <= set(data["signals"])
    assert {f"{name}|False", f"{name}|True"} <= set(data["rewards"])
    # Its rows are what its run gives alone (NaN compared as JSON writes it).
    rods = run_rod_toppling(n_seeds=2, n_episodes=10, reward=name, seed=0, progress=False)
    assert json.dumps(data["rewards"][f"{name}|False"]) == json.dumps(
        registry.plain(rods.seed_summaries()))
    # Its reward is not zero: with untried moves worth 0, a reward of 0 would leave every
    # value at 0; the move's error (its formula "error") raises them.
    zero_start = run_rod_toppling(n_seeds=2, n_episodes=10, reward=name, initial_q=0.0,
                                  seed=0, progress=False)
    assert np.nanmax(zero_start.q_table) > 0  # (moments not reached are NaN)
    # ... and it is the paper's reward on the rods (the same formula), as its class says.
    paper = run_rod_toppling(n_seeds=2, n_episodes=10, initial_q=0.0, seed=0, progress=False)
    np.testing.assert_array_equal(zero_start.q_table, paper.q_table)
    # On the buttons, its interest is the last error: not zero once a task has erred.
    buttons = run_goal_oriented(n_seeds=2, n_trials=10, interest=name, seed=0,
                                progress=False)
    assert buttons.interest.max() > 0


def test_a_signal_asking_for_a_formula_the_loop_lacks_is_refused_by_name(monkeypatch):
    monkeypatch.setattr(interest, "SIGNAL_CLASSES", dict(interest.SIGNAL_CLASSES))

    @interest.interest_signal
    class Cubed(interest.InterestSignal):
        NAME = "cubed"
        KERNEL_FORMULA = "cube"

        def record(self, task, error):
            self._append(task, error)

        def interest(self, task):
            history = self._history.get(task, ())
            return history[-1] ** 3 if history else 0.0

        @staticmethod
        def table_values(table, rows):
            return np.where(table.count[rows] > 0, table.errors[rows][..., -1] ** 3, 0.0)

    with pytest.raises(ValueError, match="reward 'cubed' asks the compiled rod loop for "
                                         "the formula 'cube', which it does not have"):
        run_rod_toppling(n_seeds=1, n_episodes=2, reward="cubed", progress=False)
