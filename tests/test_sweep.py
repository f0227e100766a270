"""Sweeps: a grid times seeds, locally with joblib and on a real Dask LocalCluster."""

import numpy as np
import pandas as pd
import pytest

from icm.experiments import run_goal_oriented, sweep

GRID = {"epsilon": [0.05, 0.3], "window": [3, 6]}


@pytest.fixture(scope="module")
def local():
    return sweep(run_goal_oriented, GRID, n_seeds=4, n_trials=25, seed=2, progress=False)


def test_one_row_per_grid_point_and_seed_with_the_run_numbers(local):
    assert isinstance(local, pd.DataFrame)
    assert len(local) == 4 * 4
    assert {"epsilon", "window", "seed_index", "red_mastery_trial", "green_mastery_trial",
            "mastery_gap", "red_first"} <= set(local.columns)
    # Each row holds exactly what a direct run at that point gives for that seed.
    direct = run_goal_oriented(n_seeds=4, n_trials=25, seed=2, epsilon=0.3, window=6,
                               progress=False)
    rows = local[(local.epsilon == 0.3) & (local.window == 6)].sort_values("seed_index")
    np.testing.assert_array_equal(rows[["red_mastery_trial", "green_mastery_trial"]].to_numpy(),
                                  direct.mastery_trial)


def test_parallel_joblib_gives_the_same_numbers(local):
    parallel = sweep(run_goal_oriented, GRID, n_seeds=4, n_trials=25, seed=2, n_jobs=2,
                     progress=False)
    pd.testing.assert_frame_equal(parallel, local)


def test_dask_local_cluster_gives_the_same_numbers(local):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = sweep(run_goal_oriented, GRID, n_seeds=4, n_trials=25, seed=2,
                        backend="dask", client=client, progress=False)
        assert len(client.scheduler_info()["workers"]) == 2
    pd.testing.assert_frame_equal(on_dask, local)


@pytest.mark.parametrize("kwargs, message", [
    (dict(grid={}), "grid"),
    (dict(grid={"temperature": [1.0]}), "temperature"),
    (dict(grid={"seed": [1, 2]}), "seed"),
    (dict(grid={"epsilon": []}), "non-empty"),
    (dict(grid={"epsilon": 0.1}), "non-empty list"),
    (dict(grid=GRID, n_seeds=0), "n_seeds"),
    (dict(grid=GRID, backend="spark"), "backend"),
    (dict(grid=GRID, n_jobs=0), "n_jobs"),
    (dict(grid={"epsilon": [2.0]}), "epsilon must be"),
])
def test_bad_sweeps_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        sweep(run_goal_oriented, n_trials=2, progress=False, **kwargs)
