"""Figures and widget panels draw what the results hold."""

import matplotlib.figure
import numpy as np
import pytest

import icm
from icm import figures


@pytest.fixture(scope="module")
def small_run():
    return icm.experiments.run_goal_oriented(n_seeds=12, n_trials=25, seed=3)


def test_figure5_draws_the_mean_interest_of_each_task_with_a_band(small_run):
    fig = figures.figure5(small_run)
    assert isinstance(fig, matplotlib.figure.Figure)
    ax = fig.axes[0]
    lines = [l for l in ax.get_lines() if l.get_label().startswith("open the")]
    assert [l.get_label() for l in lines] == ["open the red box", "open the green box"]
    for i, line in enumerate(lines):
        assert np.allclose(line.get_ydata(), small_run.interest[:, :, i].mean(axis=0))
        assert np.array_equal(line.get_xdata(), np.arange(1, 26))
    assert len(ax.collections) == 2  # one confidence band per task
    assert fig._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"


def test_band_contains_the_mean_and_shrinks_with_more_seeds():
    values = np.random.default_rng(0).normal(size=(400, 3))
    mean, low, high = icm.stats.mean_band(values[:20])
    assert np.all(low < mean) and np.all(mean < high)
    _, low_many, high_many = icm.stats.mean_band(values)
    assert np.all(high_many - low_many < high - low)


def test_first_from_which_finds_where_a_condition_holds_for_good():
    condition = np.array([[0, 1, 0, 1, 1], [1, 1, 1, 1, 1], [1, 1, 1, 1, 0]], dtype=bool)
    assert icm.stats.first_from_which(condition).tolist() == [3, 0, -1]


def test_diagrams_and_console_figures_draw():
    assert figures.figure2().axes
    assert len(figures.outcome_table_figure().axes[0].patches) == 20


def test_comes_first_handles_never():
    first = np.array([2, 5, -1, 3, 4])
    second = np.array([4, 5, 3, -1, -1])
    assert icm.stats.comes_first(first, second).tolist() == [True, False, False, True, True]
    assert not icm.stats.comes_first(-1, -1)
