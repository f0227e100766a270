"""The figures of the interactive panels (Figures 5, 6 and 7 over 100 seeds).

Each draws the numbers of its experiment's `panel_curves`, the same numbers the book's
static (kernel-free) panels precompute, on a fixed layout: a panel redraws on every
slider move, so it is kept quick to draw.
"""

import matplotlib.ticker
import numpy as np

from icm import _validate
from icm.experiments import actor_critic, goal_oriented, rod_toppling
from icm.figures._common import TASK_COLOURS, Figure

SERIES_COLOURS = {"red": TASK_COLOURS["red"], "green": TASK_COLOURS["green"],
                  "blue": "#1f5fcc"}
"""Colour of each series of the panels (the tasks and the rods, by name)."""


def draw_curves(curves, height=3.2, width_per_group=4.6):
    """A figure of `panel_curves` numbers: one axes per group, a line and a band per
    series, on a fixed layout.

    Args:
      curves: as an experiment's `panel_curves` returns them.
      height: figure height (inches).
      width_per_group: width of each group's axes (inches).
    """
    if not isinstance(curves, dict) or not {"x", "xlabel", "groups"} <= set(curves):
        raise _validate.ArgumentTypeError(f"curves must be the dict of a panel_curves "
                                          f"function, got {_validate.show(curves)}")
    groups = curves["groups"]
    fig = Figure(figsize=(width_per_group * len(groups), height))
    fig.png_dpi, fig.quick_png = 96, True
    axes = fig.subplots(1, len(groups), squeeze=False)[0]
    x = curves["x"]
    for ax, group in zip(axes, groups):
        for name, (mean, low, high) in group["series"].items():
            colour = SERIES_COLOURS[name.split()[0]]
            dashed = name.endswith("toppled")
            ax.fill_between(x, low, high, color=colour, alpha=0.12 if dashed else 0.25,
                            linewidth=0)
            ax.plot(x, mean, color=colour, linewidth=1.6 if dashed else 2,
                    linestyle="--" if dashed else "-", label=name)
        ax.set_xlim(x[0], x[-1])
        ax.set_ylim(bottom=0)
        ax.set_xlabel(curves["xlabel"], fontsize=9)
        ax.set_ylabel(group["ylabel"], fontsize=9)
        ax.set_title(group["title"], fontsize=9 if len(group["title"]) > 60 else 10)
        ax.tick_params(labelsize=8)
        ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(5, integer=True))
        ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(4))
        ax.legend(frameon=False, fontsize=8)
    left = 0.72 / (width_per_group * len(groups))
    fig.subplots_adjust(left=left, right=0.98, bottom=0.16, top=0.88,
                        wspace=0.28 if len(groups) > 1 else 0.2)
    return fig


def figure5_panel_figure(result):
    """The Figure 5 panel: mean interest in each task with its 95% band."""
    return draw_curves(goal_oriented.panel_curves(result))


def figure6_panel_figure(result):
    """The Figure 6 panel: mean prediction error on each task with its 95% band."""
    curves = actor_critic.panel_curves(result)
    fig = draw_curves(curves)
    fig.axes[0].set_ylim(0, np.sqrt(2) + 0.05)
    return fig


def figure7_panel_figure(result):
    """The Figure 7 panel: what is left to learn about each rod, and which rod the
    robot topples, per episode, means over the seeds with their 95% bands."""
    fig = draw_curves(rod_toppling.panel_curves(result), width_per_group=6.4)
    fig.axes[0].set_ylim(0, 1.02)
    return fig
