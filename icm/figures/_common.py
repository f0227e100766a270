"""Shared pieces of the figures: a Figure that displays itself, colours, mean bands."""

import io

import matplotlib.figure
import numpy as np

from icm import stats

TASK_COLOURS = {"red": "#d62728", "green": "#2ca02c"}


class Figure(matplotlib.figure.Figure):
    """A matplotlib Figure that Jupyter displays as a PNG without pyplot's help."""

    def _repr_png_(self):
        buffer = io.BytesIO()
        self.savefig(buffer, format="png", dpi=110)
        return buffer.getvalue()


def new_figure(width=6.4, height=3.8, ncols=1, nrows=1, **kwargs):
    """A new `Figure` (constrained layout) and its axes, as `Figure.subplots` returns them."""
    fig = Figure(figsize=(width, height), layout="constrained")
    axes = fig.subplots(nrows, ncols, **kwargs)
    return fig, axes


def plot_mean_band(ax, values, colour, label, x=None, per_seed=False):
    """Draws the mean over seeds of `values` [seed, time] with its 95% band on `ax`."""
    values = np.asarray(values, dtype=float)
    x = np.arange(1, values.shape[1] + 1) if x is None else x
    if per_seed:
        for row in values:
            ax.plot(x, row, color=colour, alpha=0.08, linewidth=0.6)
    mean, low, high = stats.mean_band(values)
    ax.fill_between(x, low, high, color=colour, alpha=0.25, linewidth=0)
    ax.plot(x, mean, color=colour, linewidth=2, label=label)
