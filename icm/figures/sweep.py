"""A heatmap of a sweep: one summary number per pair of settings, averaged over seeds."""

import numpy as np

from icm.figures._common import new_figure


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
    """
    table = frame.pivot_table(index=y, columns=x, values=value, aggfunc="mean")
    fig, ax = new_figure(width=6.4, height=4.2)
    image = ax.imshow(table.to_numpy(), origin="lower", cmap="viridis", aspect="auto")
    ax.set_xticks(range(len(table.columns)), [f"{v:g}" for v in table.columns])
    ax.set_yticks(range(len(table.index)), [f"{v:g}" for v in table.index])
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    middle = np.nanmean(table.to_numpy())
    for (i, j), number in np.ndenumerate(table.to_numpy()):
        ax.text(j, i, f"{number:.1f}", ha="center", va="center", fontsize=8,
                color="white" if number < middle else "black")
    fig.colorbar(image, ax=ax, label=colour_label or value)
    n_seeds = frame["seed_index"].nunique()
    ax.set_title(title or f"mean {value} over {n_seeds} seeds", fontsize=10)
    return fig
