"""The maps of the robustness chapter: where each of the paper's claims holds, over
every pair of a learner's unpublished settings."""

import matplotlib.colors
import matplotlib.patches
import numpy as np

from icm.experiments.robustness import RobustnessResult
from icm.figures._common import Figure, check_result, check_title

_MADE_BY = "icm.experiments.robustness.run_robustness"
COLOURMAP = "PuOr"
"""Colour map of the shares: orange below a claim's threshold, purple above it, white
at it."""
MARKS = {"holds": "✓", "unclear": "?", "fails": "✗"}
"""The mark of each verdict in a cell."""


def _label(value):
    return f"{value:g}" if isinstance(value, float) else str(value)


def robustness_map(result, title=None):
    """Draws, for every pair of a study's settings (rows) and every claim (columns),
    the share of seeds in which the claim held at each grid point.

    Each cell shows the share in percent and a mark: ✓ where the claim holds (the whole
    95% interval of the share is at or above the claim's threshold), ✗ where it fails
    (all below), ? where the interval straddles the threshold. The colour is the
    share, white at the threshold. The outlined cell is the library's default.

    Args:
      result: a `RobustnessResult` (from `icm.experiments.robustness.run_robustness`).
      title: the figure's title (default: the study's title and seeds).

    Returns:
      The `Figure`.
    """
    check_result("result", result, RobustnessResult, _MADE_BY)
    check_title(title)
    study = result.study
    pairs, claims = study.pairs(), study.claims
    height = 2.6 * len(pairs) + 1.9
    width = 3.6 * len(claims) + 0.9
    # Placed by hand, not with `new_figure`'s constrained layout, which costs a second
    # of drawing with this many texts.
    fig = Figure(figsize=(width, height))
    axes = fig.subplots(len(pairs) + 1, len(claims), squeeze=False,
                        gridspec_kw={"height_ratios": [1.0] * len(pairs) + [0.06]})
    fig.subplots_adjust(left=1.15 / width, right=1 - 0.15 / width, bottom=0.55 / height,
                        top=1 - 1.5 / height, wspace=0.5, hspace=0.6)
    for j, claim in enumerate(claims):
        norm = matplotlib.colors.TwoSlopeNorm(vmin=0.0, vcenter=claim.threshold, vmax=1.0)
        for i, pair in enumerate(pairs):
            ax = axes[i, j]
            image = _draw_pair(ax, result, claim, pair, norm)
            if i == 0:
                ax.set_title(f"{claim.text}\n(in ≥ {claim.threshold:.0%} of seeds)",
                             fontsize=12)
        bar = fig.colorbar(image, cax=axes[-1, j], orientation="horizontal")
        bar.set_label("share of seeds", fontsize=10, labelpad=1)
        bar.ax.tick_params(labelsize=9)
        bar.ax.axvline(claim.threshold, color="black", linewidth=1)
    fig.suptitle(title or f"{study.title}, {result.n_seeds} seeds per cell\n✓ holds, ✗ fails, "
                          f"? unclear (95% interval); outlined: the defaults", fontsize=13,
                 y=1 - 0.1 / height, va="top")
    return fig


def _draw_pair(ax, result, claim, pair, norm):
    """One panel: the map of `claim` over `pair`; returns the image."""
    a, b = (result.study.setting(n) for n in pair)
    table = result.pair_table(claim.name, pair)
    image = ax.imshow(table["share"], origin="lower", cmap=COLOURMAP, norm=norm,
                      aspect="auto")
    ax.set_xticks(range(len(a.values)), [_label(v) for v in a.values], fontsize=9)
    ax.set_yticks(range(len(b.values)), [_label(v) for v in b.values], fontsize=9)
    ax.set_xlabel(a.label, fontsize=10)
    ax.set_ylabel(b.label, fontsize=10)
    for (i, j), share in np.ndenumerate(table["share"]):
        strong = abs(norm(share) - 0.5) > 0.35
        ax.text(j, i, f"{100 * share:.0f}{MARKS[table['verdict'][i, j]]}", ha="center",
                va="center", fontsize=10, color="white" if strong else "black")
    ja, ib = a.values.index(a.default), b.values.index(b.default)
    ax.add_patch(matplotlib.patches.Rectangle((ja - 0.5, ib - 0.5), 1, 1, fill=False,
                                              edgecolor="black", linewidth=2))
    return image
