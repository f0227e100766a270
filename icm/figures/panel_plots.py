"""The figures of the interactive panels (Figures 5, 6 and 7 over 100 seeds).

Each draws the numbers of its experiment's `panel_curves`, the same numbers the book's
static (kernel-free) panels precompute, on a fixed layout: a panel redraws on every
slider move, so it is kept quick to draw.
"""

import matplotlib.ticker
import numpy as np

from icm import _validate
from icm.experiments import actor_critic_results, goal_oriented_results, rod_toppling
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
    height = _validate.real("height", height, 0.5, 60.0)
    width_per_group = _validate.real("width_per_group", width_per_group, 0.5, 60.0)
    _validate.text("curves['xlabel']", curves["xlabel"])
    groups = curves["groups"]
    if not isinstance(groups, (list, tuple)) or not groups:
        raise _validate.ArgumentTypeError(f"curves['groups'] must be a non-empty list, got "
                                          f"{_validate.show(groups)}")
    x = _validate.finite_array("curves['x']", curves["x"], ndim=1)
    if len(x) < 1:
        raise ValueError(f"curves['x'] must have at least one point, got "
                         f"{_validate.show(curves['x'])}")
    for i, group in enumerate(groups):
        for key in ("title", "ylabel"):
            _validate.text(f"curves['groups'][{i}][{key!r}]", group.get(key)
                           if isinstance(group, dict) else None)
        series = group.get("series")
        if not isinstance(series, dict):
            raise _validate.ArgumentTypeError(
                f"curves['groups'][{i}]['series'] must be a dict {{name: (mean, low, "
                f"high)}}, got {_validate.show(series)}")
        for name, lines in series.items():
            where = f"curves['groups'][{i}]['series'][{name!r}]"
            if not isinstance(name, str) or name.split()[0] not in SERIES_COLOURS:
                raise ValueError(f"the names of curves['groups'][{i}]['series'] must start "
                                 f"with one of {', '.join(SERIES_COLOURS)}, got "
                                 f"{_validate.show(name)}")
            if not isinstance(lines, (tuple, list)) or len(lines) != 3:
                raise _validate.ArgumentTypeError(
                    f"{where} must be (mean, low, high), got {_validate.show(lines)}")
            for part, line in zip(("mean", "low", "high"), lines):
                line = np.asarray(line)
                if line.ndim != 1 or len(line) != len(x):
                    raise ValueError(
                        f"{where} ({part}) must have one value per point of curves['x'] "
                        f"({len(x)}), got {line.shape[0] if line.ndim == 1 else line.shape}")
    fig = Figure(figsize=(width_per_group * len(groups), height))
    fig.png_dpi, fig.quick_png = 96, True
    axes = fig.subplots(1, len(groups), squeeze=False)[0]
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
        # A fixed place for the title (matplotlib otherwise measures the axes at every
        # drawing to keep it clear of top tick labels, which these axes have none of).
        ax.set_title(group["title"], fontsize=9 if len(group["title"]) > 60 else 10, y=1.0)
        ax.tick_params(labelsize=8)
        ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(5, integer=True))
        ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(4))
        ax.legend(frameon=False, fontsize=8)
    left = 0.72 / (width_per_group * len(groups))
    fig.subplots_adjust(left=left, right=0.98, bottom=0.16, top=0.88,
                        wspace=0.28 if len(groups) > 1 else 0.2)
    return fig


PANEL_LAYOUT = {
    "figure5": {"ylim": None, "width_per_group": 4.6},
    "figure6": {"ylim": (0, np.sqrt(2) + 0.05), "width_per_group": 4.6},
    "figure7": {"ylim": (0, 1.02), "width_per_group": 6.4},
}
"""Each panel's fixed layout: the y range (None: from 0 to the data) and the width."""


def panel_figure(name, curves):
    """Draws the `curves` of panel `name` (a key of `icm.experiments.panel_data.PANELS`) on
    that panel's fixed layout: what the live panels show."""
    layout = PANEL_LAYOUT[_validate.one_of("name", name, tuple(PANEL_LAYOUT))]
    fig = draw_curves(curves, width_per_group=layout["width_per_group"])
    if layout["ylim"] is not None:
        fig.axes[0].set_ylim(*layout["ylim"])
    return fig


def figure5_panel_figure(result):
    """The Figure 5 panel: mean interest in each task with its 95% band."""
    return panel_figure("figure5", goal_oriented_results.panel_curves(result))


def figure6_panel_figure(result):
    """The Figure 6 panel: mean prediction error on each task with its 95% band."""
    return panel_figure("figure6", actor_critic_results.panel_curves(result))


def figure7_panel_figure(result):
    """The Figure 7 panel: what is left to learn about each rod, and which rod the
    robot topples, per episode, means over the seeds with their 95% bands."""
    return panel_figure("figure7", rod_toppling.panel_curves(result))


def sweep_figure(settings, cells):
    """The epsilon x window sweep as two heatmaps: the mean mastery gap (green - red,
    trials) and the share of seeds that master red first, per (epsilon, window).

    Args:
      settings: the grid's settings (dicts with at least epsilon and window), one per
        cell.
      cells: for each setting, its `icm.experiments.panel_data.sweep_cell` numbers.
    """
    if not isinstance(settings, (list, tuple)) or not isinstance(cells, (list, tuple)) \
            or len(settings) != len(cells) or not settings:
        raise _validate.ArgumentTypeError(
            f"settings and cells must be lists of the same non-zero length, got "
            f"{_validate.show(settings)} and {_validate.show(cells)}")
    for i, (setting, cell) in enumerate(zip(settings, cells)):
        for name, value, keys in (("settings", setting, ("epsilon", "window")),
                                  ("cells", cell, ("gap", "red_first"))):
            if not isinstance(value, dict):
                raise _validate.ArgumentTypeError(
                    f"{name}[{i}] must be a dict with {' and '.join(keys)}, got "
                    f"{_validate.show(value)}")
            missing = [k for k in keys if k not in value]
            if missing:
                raise ValueError(f"{name}[{i}] must have {' and '.join(keys)}; it lacks "
                                 f"{', '.join(missing)}: {_validate.show(value)}")
            for k in keys:  # a cell's numbers may be NaN (no seed mastered both)
                if not _validate.is_real(value[k]):
                    raise _validate.ArgumentTypeError(
                        f"{name}[{i}][{k!r}] must be a number, got {_validate.show(value[k])}")
    epsilons = sorted({s["epsilon"] for s in settings})
    windows = sorted({s["window"] for s in settings})
    fig = Figure(figsize=(9.6, 3.8))
    fig.png_dpi, fig.quick_png = 96, True
    axes = fig.subplots(1, 2)
    for ax, (field, title, fmt) in zip(axes, (
            ("gap", "Mean mastery gap (green - red, trials)", "{:.1f}"),
            ("red_first", "Share of seeds mastering red first", "{:.0%}"))):
        table = np.full((len(windows), len(epsilons)), np.nan)
        for s, c in zip(settings, cells):
            table[windows.index(s["window"]), epsilons.index(s["epsilon"])] = c[field]
        image = ax.imshow(table, origin="lower", cmap="viridis", aspect="auto",
                          vmin=0 if field == "red_first" else None,
                          vmax=1 if field == "red_first" else None)
        ax.set_xticks(range(len(epsilons)), [f"{v:g}" for v in epsilons])
        ax.set_yticks(range(len(windows)), [f"{v:g}" for v in windows])
        ax.set_xlabel("epsilon")
        ax.set_ylabel("window k")
        ax.set_title(title, fontsize=10)
        low, high = image.get_clim()
        for (i, j), number in np.ndenumerate(table):
            ax.text(j, i, fmt.format(number), ha="center", va="center", fontsize=8,
                    color="white" if number < (low + high) / 2 else "black")
        fig.colorbar(image, ax=ax)
    fig.subplots_adjust(left=0.07, right=0.97, bottom=0.14, top=0.9, wspace=0.25)
    return fig
