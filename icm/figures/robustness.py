"""The maps of the robustness chapter: where each of the paper's claims holds, over
every pair of a learner's unpublished settings."""

import textwrap

import matplotlib.colors
import matplotlib.patches
import numpy as np

from icm.chapters.words import percent
from icm.studies.maps import RobustnessResult
from icm.figures._common import Figure, check_result, check_title

_MADE_BY = "icm.studies.robustness.run_robustness"
COLOURMAP = "PuOr"
"""Colour map of the shares: orange below a claim's threshold, purple above it, white
at it."""
MARKS = {"holds": "✓", "unclear": "?", "fails": "✗"}
"""The mark of each verdict in a cell."""
COLUMNS = 2
"""Claims side by side at most (the rest go into further rows)."""


def cell_percent(share):
    """A cell's share in percent, without the sign: whole percents, with a decimal where
    whole percents would show 100 or 0 for a share that is neither (199 seeds of 200:
    "99.5", not "100", which a reader takes for every seed)."""
    return percent(share).rstrip("%")


def _label(value):
    return f"{value:g}" if isinstance(value, float) else str(value)


def robustness_map(result, title=None):
    """Draws, for every pair of a study's settings (rows) and every claim (columns),
    the share of seeds in which the claim held at each grid point.

    Each cell shows the share in percent (`cell_percent`) and a mark: ✓ where the claim holds (the whole
    95% interval of the share is at or above the claim's threshold), ✗ where it fails
    (all below), ? where the interval straddles the threshold. The colour is the
    share, white at the threshold. The outlined cell is the library's default.

    Args:
      result: a `RobustnessResult` (from `icm.studies.robustness.run_robustness`).
      title: the figure's title (default: the study's title and seeds).

    Returns:
      The `Figure`.
    """
    check_result("result", result, RobustnessResult, _MADE_BY)
    check_title(title)
    study = result.study
    pairs, claims = study.pairs(), study.claims
    # At most COLUMNS claims side by side, so that the figure is as wide as the book's
    # text column and its numbers stay readable there; more claims go into further
    # blocks of rows below. Each block: a row of maps per pair, then the colour bars.
    blocks = [claims[k:k + COLUMNS] for k in range(0, len(claims), COLUMNS)]
    columns = min(COLUMNS, len(claims))
    ratios = []
    for k, _ in enumerate(blocks):
        ratios += [1.0] * len(pairs) + [0.07] + ([0.3] if k < len(blocks) - 1 else [])
    width, row_height = 3.0 * columns + 0.85, 2.45
    height = row_height * len(pairs) * len(blocks) + 0.8 * len(blocks) + 1.3
    # Placed by hand, not with `new_figure`'s constrained layout, which costs a second
    # of drawing with this many texts.
    fig = Figure(figsize=(width, height))
    axes = fig.subplots(len(ratios), columns, squeeze=False,
                        gridspec_kw={"height_ratios": ratios})
    fig.subplots_adjust(left=1.75 / width, right=1 - 0.1 / width, bottom=0.45 / height,
                        top=1 - 1.5 / height, wspace=0.08, hspace=0.95)
    row = 0
    for block in blocks:
        for j in range(columns):
            if j >= len(block):
                for i in range(len(pairs) + 1):
                    axes[row + i, j].set_visible(False)
                continue
            if row + len(pairs) + 1 < len(ratios):  # the space between two blocks
                axes[row + len(pairs) + 1, j].set_visible(False)
            claim = block[j]
            norm = matplotlib.colors.TwoSlopeNorm(vmin=0.0, vcenter=claim.threshold, vmax=1.0)
            for i, pair in enumerate(pairs):
                ax = axes[row + i, j]
                image = _draw_pair(ax, result, claim, pair, norm, y_label=j == 0)
                if i == 0:
                    ax.set_title(textwrap.fill(f"{claim.text} (in ≥ {claim.threshold:.0%} "
                                               f"of seeds)", 24), fontsize=12)
            bar = fig.colorbar(image, cax=axes[row + len(pairs), j], orientation="horizontal")
            bar.set_label("share of seeds", fontsize=10, labelpad=1)
            bar.set_ticks([0, claim.threshold, 1], labels=["0", f"{claim.threshold:g}", "1"])
            bar.ax.axvline(claim.threshold, color="black", linewidth=1)
        row += len(pairs) + 2
    fig.suptitle(title or f"{study.title}, {result.n_seeds} seeds per cell\n✓ holds, ✗ fails, "
                          f"? unclear (95% interval)\noutlined: the defaults", fontsize=13,
                 y=1 - 0.08 / height, va="top")
    return fig.describe(_summary(result))


def _summary(result):
    """The map in words: per claim, where it holds, fails or is unclear."""
    sentences = []
    for claim in result.study.claims:
        counts = {"holds": 0, "fails": 0, "unclear": 0}
        for pair in result.study.pairs():
            verdicts = result.pair_table(claim.name, pair)["verdict"]
            for verdict in counts:
                counts[verdict] += int(np.sum(verdicts == verdict))
        total = sum(counts.values())
        sentences.append(f"\"{claim.text}\" holds in {counts['holds']} of {total} cells, "
                         f"fails in {counts['fails']} and is unclear in {counts['unclear']}.")
    return " ".join(sentences)


def _draw_pair(ax, result, claim, pair, norm, y_label=True):
    """One panel: the map of `claim` over `pair` (its vertical axis named if
    `y_label`: a row of maps shares it); returns the image."""
    a, b = (result.study.setting(n) for n in pair)
    table = result.pair_table(claim.name, pair)
    image = ax.imshow(table["share"], origin="lower", cmap=COLOURMAP, norm=norm,
                      aspect="auto")
    ax.set_xticks(range(len(a.values)), [_label(v) for v in a.values], fontsize=9)
    ax.set_yticks(range(len(b.values)), [_label(v) for v in b.values], fontsize=9)
    ax.set_xlabel(textwrap.fill(a.label, 26), fontsize=10)
    if y_label:
        ax.set_ylabel(textwrap.fill(b.label, 20), fontsize=10)
    else:
        ax.tick_params(labelleft=False)
    for (i, j), share in np.ndenumerate(table["share"]):
        strong = abs(norm(share) - 0.5) > 0.35
        ax.text(j, i, f"{cell_percent(share)}\n{MARKS[table['verdict'][i, j]]}", ha="center",
                va="center", fontsize=10, linespacing=1.0,
                color="white" if strong else "black")
    ja, ib = a.values.index(a.default), b.values.index(b.default)
    ax.add_patch(matplotlib.patches.Rectangle((ja - 0.5, ib - 0.5), 1, 1, fill=False,
                                              edgecolor="black", linewidth=2))
    return image
