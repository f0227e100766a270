"""Shared pieces of the figures: a Figure that displays itself, colours, mean bands."""

import io

import matplotlib.axes
import matplotlib.figure
import numpy as np

from icm import _validate, stats

TASK_COLOURS = {"red": "#d62728", "green": "#2ca02c"}


class Figure(matplotlib.figure.Figure):
    """A matplotlib Figure that Jupyter displays as a PNG without pyplot's help.

    `png_dpi` sets its resolution; `quick_png` trades file size for speed (light
    compression), for figures that are redrawn on every slider move."""

    png_dpi = 110
    quick_png = False

    def _repr_png_(self):
        buffer = io.BytesIO()
        options = {"pil_kwargs": {"compress_level": 1}} if self.quick_png else {}
        self.savefig(buffer, format="png", dpi=self.png_dpi, **options)
        return buffer.getvalue()


def check_result(name, result, cls, made_by):
    """Returns `result` if it is a `cls`, else raises an ArgumentTypeError that says
    which function makes one (`made_by`)."""
    return _validate.instance(name, result, cls, f"a {cls.__name__} (from {made_by})")


def check_axes(ax):
    """Returns `ax` if it is None or a matplotlib Axes, else raises."""
    if ax is not None:
        _validate.instance("ax", ax, matplotlib.axes.Axes, "None or a matplotlib Axes")
    return ax


def check_title(title):
    """Returns `title` if it is None or a string, else raises."""
    if title is not None:
        _validate.text("title", title)
    return title


def new_figure(width=6.4, height=3.8, ncols=1, nrows=1, **kwargs):
    """A new `Figure` (constrained layout) and its axes, as `Figure.subplots` returns them."""
    width = _validate.real("width", width, 0.5, 60.0)
    height = _validate.real("height", height, 0.5, 60.0)
    ncols = _validate.integer("ncols", ncols, 1, 50)
    nrows = _validate.integer("nrows", nrows, 1, 50)
    fig = Figure(figsize=(width, height), layout="constrained")
    axes = fig.subplots(nrows, ncols, **kwargs)
    return fig, axes


LINESTYLES = ("-", "--", ":", "-.")
"""The line styles `plot_mean_band` draws a mean with."""


def plot_mean_band(ax, values, colour, label, x=None, per_seed=False, linestyle="-"):
    """Draws the mean over seeds of `values` [seed, time] with its 95% band on `ax`: a
    percentile bootstrap (`icm.stats.bootstrap_band`), which stays within the range the
    values can take (an error's band never dips below zero). `x` defaults to 1, 2, ...;
    `per_seed` also draws every seed's curve faintly; `linestyle` is the mean's."""
    _validate.instance("ax", ax, matplotlib.axes.Axes, "a matplotlib Axes")
    values = _validate.finite_array("values", values, ndim=2)
    linestyle = _validate.one_of("linestyle", linestyle, LINESTYLES)
    x = np.arange(1, values.shape[1] + 1) if x is None else \
        _validate.finite_array("x", x, shape=(values.shape[1],))
    if per_seed:
        for row in values:
            ax.plot(x, row, color=colour, alpha=0.08, linewidth=0.6)
    mean, low, high = stats.bootstrap_band(values, resamples=stats.PANEL_RESAMPLES)
    ax.fill_between(x, low, high, color=colour, alpha=0.25, linewidth=0)
    ax.plot(x, mean, color=colour, linewidth=2, linestyle=linestyle, label=label)
