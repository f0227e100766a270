"""The chapter "Forming actions"'s goal-babbling runs, kept in
assets/goal_babbling_runs.npz (icm.experiments.goal_babbling_runs): the file holds the
three strategies on the chapter's seeds with the defaults, and it is what the library
computes (rerun: the first rollouts of the first seed here, the first seed whole in the
slow test); `python -m icm.experiments.goal_babbling_runs` writes it again after a
change to goal babbling."""

import dataclasses

import numpy as np
import pytest

from icm.experiments import goal_babbling, goal_babbling_runs

from test_bad_input import refused

PER_ROLLOUT = ("movements", "outcomes", "depths", "touched", "pressed", "goals", "regions",
               "interest", "maturity")
"""The arrays with a rollout axis (axis 1), which a shorter run reproduces the start of."""


@pytest.fixture(scope="module")
def stored():
    return goal_babbling_runs.chapter_runs()


def test_the_file_holds_the_three_strategies_on_the_chapters_seeds(stored):
    assert list(stored) == list(goal_babbling.STRATEGIES)
    for strategy, result in stored.items():
        assert result.strategy == strategy
        assert result.n_seeds == goal_babbling_runs.N_SEEDS == 10
        assert result.n_rollouts == goal_babbling.DEFAULT_N_ROLLOUTS
        # Run with run_goal_babbling's defaults, on the chapter's root seed.
        defaults = goal_babbling.run_goal_babbling(strategy, n_seeds=1, n_rollouts=1,
                                                   seed=goal_babbling_runs.SEED,
                                                   progress=False).settings
        assert result.settings == {**defaults, "n_seeds": 10,
                                   "n_rollouts": goal_babbling.DEFAULT_N_ROLLOUTS}
        for field in dataclasses.fields(result):
            value = getattr(result, field.name)
            if field.name != "settings":
                assert len(value) == (len(result.checkpoints) if field.name == "checkpoints"
                                      else len(result.test_goals)
                                      if field.name == "test_goals" else 10), field.name
    versions = goal_babbling_runs.recorded_versions()
    assert set(versions) == {"python", "numpy", "mujoco", "machine"}


def test_the_start_of_each_strategys_first_seed_is_what_the_library_computes(stored):
    # The first rollouts of a seed are the same in a run of any length: 100 of the
    # first seed, per strategy, every array with a rollout axis, exactly.
    for strategy, result in stored.items():
        again = goal_babbling.run_goal_babbling(strategy, n_seeds=1, n_rollouts=100,
                                                seed=result.settings["seed"],
                                                progress=False)
        for name in PER_ROLLOUT:
            np.testing.assert_array_equal(getattr(again, name)[0],
                                          getattr(result, name)[0, :100],
                                          err_msg=f"{strategy}: {name}")


def test_the_chapters_runs_are_what_the_library_computes(stored):
    # The first seed of each strategy, whole: every array, exactly (slow: conftest.SLOW).
    for strategy, result in stored.items():
        again = goal_babbling.run_goal_babbling(strategy, n_seeds=1,
                                                seed=result.settings["seed"],
                                                progress=False)
        assert again.settings == {**result.settings, "n_seeds": 1}
        for name in goal_babbling_runs.ARRAYS:
            expected = getattr(result, name)
            if name not in ("checkpoints", "test_goals"):
                expected = expected[:1]
            np.testing.assert_array_equal(getattr(again, name), expected,
                                          err_msg=f"{strategy}: {name}")


def test_runs_saved_are_read_back_the_same(tmp_path):
    runs = {strategy: goal_babbling.run_goal_babbling(strategy, n_seeds=2, n_rollouts=12,
                                                      seed=5, progress=False,
                                                      demonstrations=(1, 3))
            for strategy in ("random_goal", "learning_progress")}
    path = tmp_path / "runs.npz"
    goal_babbling_runs.save_runs(runs, path)
    back = goal_babbling_runs.load_runs(path)
    assert list(back) == list(runs)
    for strategy, result in runs.items():
        assert back[strategy].settings == result.settings
        assert back[strategy].n_demonstrations == 2
        for name in goal_babbling_runs.ARRAYS:
            original, read = getattr(result, name), getattr(back[strategy], name)
            assert read.dtype == original.dtype, name
            np.testing.assert_array_equal(read, original, err_msg=name)
    assert goal_babbling_runs.recorded_versions(path) == goal_babbling_runs.versions()


def test_bad_arguments_are_refused():
    refused(lambda: goal_babbling_runs.chapter_runs(recompute="yes"), "recompute", "yes",
            "type")
    refused(lambda: goal_babbling_runs.run_chapter(n_seeds=0), "n_seeds", "0", "value")
    refused(lambda: goal_babbling_runs.run_chapter(seed=-1), "seed", "-1", "value")
