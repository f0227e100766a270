"""A heatmap of a sweep: one summary number per pair of settings, averaged over seeds."""

import numpy as np

from icm import _validate
from icm.figures._common import check_title, new_figure


def sweep_heatmap(frame, x, y, value, title=None, colour_label=None):
    """Draws the mean of `value` over seeds for each (`x`, `y`) pair of a sweep.

    Args:
      frame: the DataFrame of `icm.experiments.sweep`.
      x, y: the two grid arguments on the axes.
      value: the per-seed number to average (NaN rows are left out).
      title: axes title.
      colour_label: the colour bar's label (default `value`).

    Returns:
      The `Figure`; every cell is annotated with its mean.

    Raises:
      ValueError: if `frame` is not a sweep's DataFrame or lacks one of the columns.
    """
    import pandas as pd

    _validate.instance("frame", frame, pd.DataFrame,
                       "a pandas DataFrame (from icm.experiments.sweep)")
    for name, column in (("x", x), ("y", y), ("value", value)):
        _validate.text(name, column)
        if column not in frame.columns:
            raise ValueError(f"{name} must be a column of frame ({', '.join(map(str, frame.columns))}), "
                             f"got {column!r}")
    if "seed_index" not in frame.columns:
        raise ValueError("frame must be a sweep's DataFrame, with a seed_index column")
    check_title(title)
    if colour_label is not None:
        _validate.text("colour_label", colour_label)
    table = frame.pivot_table(index=y, columns=x, values=value, aggfunc="mean")
    fig, ax = new_figure(width=6.4, height=4.2)
    image = ax.imshow(table.to_numpy(), origin="lower", cmap="viridis", aspect="auto")
    ax.set_xticks(range(len(table.columns)), [f"{v:g}" for v in table.columns])
    ax.set_yticks(range(len(table.index)), [f"{v:g}" for v in table.index])
    ax.set_xlabel(x.replace("_", " "))
    ax.set_ylabel(y.replace("_", " "))
    middle = np.nanmean(table.to_numpy())
    for (i, j), number in np.ndenumerate(table.to_numpy()):
        ax.text(j, i, f"{number:.1f}", ha="center", va="center", fontsize=8,
                color="white" if number < middle else "black")
    readable = value.replace("_", " ")
    fig.colorbar(image, ax=ax, label=colour_label or readable)
    n_seeds = frame["seed_index"].nunique()
    ax.set_title(title or f"Mean {readable} over {n_seeds} seeds", fontsize=10)
    return fig
