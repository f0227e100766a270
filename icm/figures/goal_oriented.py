"""Figures of the goal-oriented chapter: Figure 5 and what the learner practises."""

import numpy as np

from icm.experiments import goal_oriented_results as _goal_oriented
from icm.experiments.goal_oriented_results import GoalOrientedResult
from icm.experiments.results import check_results
from icm.figures._common import (TASK_COLOURS, check_result, check_title, figure_and_axes,
                                 new_figure, plot_mean_band,
                                 series_style)

_MADE_BY = "icm.experiments.run_goal_oriented"


def figure5(result, ax=None, title=None):
    """Figure 5: mean interest in the red and green tasks against trial, 95% bands.

    Args:
      result: a `GoalOrientedResult`.
      ax: draw into this axes instead of a new figure.
      title: the axes title; default says the reading and the number of seeds.

    Returns:
      The `Figure`.
    """
    check_result("result", result, GoalOrientedResult, _MADE_BY)
    check_title(title)
    fig, ax = figure_and_axes(ax)
    for i, task in enumerate(_goal_oriented.TASKS):
        plot_mean_band(ax, result.interest[:, :, i], TASK_COLOURS[task],
                       f"open the {task} box", **series_style(task))
    ax.set_xlabel("trial")
    ax.set_ylabel("interest (mean over seeds)")
    ax.set_xlim(1, result.n_trials)
    ax.set_ylim(bottom=0)
    if title is None:
        title = (f"Interest, reading \"{result.settings['reading']}\", "
                 f"{result.n_seeds} seeds, 95% band")
    ax.set_title(title, fontsize=10)
    ax.legend(frameon=False)
    return fig


def mastery_figure(result):
    """Two panels: the share of seeds that have mastered each task, and how often the
    agent opened each box per trial (mean, 95% band), against trial."""
    check_result("result", result, GoalOrientedResult, _MADE_BY)
    fig, (left, right) = new_figure(width=9.6, height=3.6, ncols=2)
    trials = np.arange(1, result.n_trials + 1)
    for i, task in enumerate(_goal_oriented.TASKS):
        mastered = result.mastery_trial[:, i]
        share = [np.mean((mastered >= 1) & (mastered <= t)) for t in trials]
        style = series_style(task)
        left.step(trials, share, where="post", color=TASK_COLOURS[task], linewidth=2,
                  label=f"{task} task", linestyle=style["linestyle"])
        plot_mean_band(right, result.practice[:, :, i], TASK_COLOURS[task],
                       f"presses opening the {task} box", **style)
    left.set(xlabel="trial", ylabel="share of seeds mastered", ylim=(0, 1.02),
             xlim=(1, result.n_trials))
    left.set_title("When the predictor\nhas learned each task", fontsize=10)
    right.set(xlabel="trial", ylabel="presses per trial (mean)", xlim=(1, result.n_trials))
    right.set_title("What the learner\npractises", fontsize=10)
    # One legend for both panels (their tasks look the same), under them.
    handles, _ = left.get_legend_handles_labels()
    fig.legend(handles, [f"{task} task" for task in _goal_oriented.TASKS],
               loc="outside lower center", ncols=2, frameon=False)
    return fig


def figure5_grid(results):
    """Figure 5 for several results side by side, on a shared interest axis.

    Args:
      results: a dict {panel title: GoalOrientedResult}.
    """
    check_results("results", results, GoalOrientedResult)
    fig, axes = new_figure(width=4.6 * len(results), height=3.6, ncols=len(results),
                            sharey=True)
    for ax, (title, result) in zip(np.atleast_1d(axes), results.items()):
        figure5(result, ax=ax, title=title)
    return fig
