"""The bad inputs of issue 29 (item 5), each refused at the boundary with a ValueError
(an ArgumentTypeError, also a TypeError, for a wrong type) that names the argument and
shows the value, raised inside icm (`sweep`'s are in tests/test_sweep.py)."""

import pathlib

import numpy as np
import pytest

import icm
from icm import _validate, cli
from icm.experiments import babbling_space, coin_rewards, goal_babbling, panel_data
from icm.figures import panel_plots

ICM_DIR = pathlib.Path(icm.__file__).resolve().parent


def refused(call, name, shown, kind):
    """`call` is refused: `kind` "type" (an ArgumentTypeError) or "value" (a ValueError
    that is not a TypeError), the message naming `name` and showing `shown`, raised
    inside icm."""
    with pytest.raises(ValueError) as info:
        call()
    error, message = info.value, str(info.value)
    if kind == "type":
        assert isinstance(error, _validate.ArgumentTypeError), message
    else:
        assert not isinstance(error, TypeError), message
    assert name in message and shown in message, message
    where = pathlib.Path(info.traceback[-1].path).resolve()
    assert ICM_DIR in where.parents, f"raised outside icm, in {where}: {message}"


@pytest.fixture(scope="module")
def babbling():
    return goal_babbling.run_goal_babbling("random_goal", n_seeds=1, n_rollouts=30,
                                           progress=False)


def test_goal_shares_refuses_bools_among_the_edges(babbling):
    refused(lambda: babbling.goal_shares([True, 10]), "edges", "[True, 10]", "type")
    refused(lambda: _validate.integer_array("counts", [3, np.True_]), "counts", "True", "type")
    assert babbling.goal_shares([0, 10, 30]).shape == (2, babbling_space.REGION_GRID[1])


def test_outcome_rewards_refuses_a_call_of_hours_and_says_how_long():
    refused(lambda: coin_rewards.outcome_rewards(n_seeds=2000, n_tries=10**4, progress=False),
            "n_seeds x n_tries", "20,000,000 (about 0.1 hours)", "value")
    refused(lambda: coin_rewards.outcome_rewards(n_seeds=2, n_tries=3, progress="yes"),
            "progress", "yes", "type")
    small = coin_rewards.outcome_rewards(n_seeds=2, n_tries=3, progress=False)
    assert small[("prediction_error", "coin")].shape == (2, 3)


def test_sweep_figure_names_the_missing_key():
    setting, cell = {"epsilon": 0.1, "window": 3}, {"gap": 1.0, "red_first": 0.5}
    refused(lambda: panel_plots.sweep_figure([{"epsilon": 0.1}], [cell]), "settings[0]",
            "window", "value")
    refused(lambda: panel_plots.sweep_figure([setting], [{"red_first": 0.5}]), "cells[0]",
            "gap", "value")
    refused(lambda: panel_plots.sweep_figure([setting], [{**cell, "gap": "x"}]),
            "cells[0]['gap']", "x", "type")
    refused(lambda: panel_plots.sweep_figure([setting], [5]), "cells[0]", "5", "type")
    assert len(panel_plots.sweep_figure([setting], [{**cell, "gap": float("nan")}]).axes) == 4


def test_a_panel_grid_of_an_unknown_panel_is_refused_when_made():
    refused(lambda: panel_data.PanelGrid("nope", (), ()), "name", "'nope'", "value")
    refused(lambda: panel_data.PanelGrid("figure5", ({},), ()), "curves", "0", "value")
    refused(lambda: panel_data.panel_runs("nope", [{}]), "name", "'nope'", "value")


def test_draw_curves_refuses_series_of_another_length_than_x():
    def curves(n):
        return {"x": [1, 2], "xlabel": "trial", "groups": [
            {"title": "a", "ylabel": "b", "series": {"red": (np.zeros(n),) * 3}}]}

    refused(lambda: panel_plots.draw_curves(curves(6)), "curves['groups'][0]['series']['red']",
            "(2), got 6", "value")
    bad_name = curves(2)
    bad_name["groups"][0]["series"] = {"purple": (np.zeros(2),) * 3}
    refused(lambda: panel_plots.draw_curves(bad_name), "series", "'purple'", "value")
    assert len(panel_plots.draw_curves(curves(2)).axes) == 1


def test_an_out_that_is_only_a_suffix_is_explained(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit):
        cli.main(["goal-babbling", "--out", ".png"])
    err = capsys.readouterr().err
    assert "--out must name a file before its suffix (for example figure.png), got .png" in err
    with pytest.raises(SystemExit):
        cli.main(["goal-babbling", "--out", "figure.gif"])
    assert "--out must end in .png, .pdf or .svg, got figure.gif (suffix .gif)" in \
        capsys.readouterr().err
    assert not list(tmp_path.iterdir())
