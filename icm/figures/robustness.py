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
    """A cell's share in percent, without the sign, with one decimal ("48.5", "99.5",
    "100.0"): a share of 200 or 1,000 seeds is a multiple of 0.5% or 0.1%, so one
    decimal shows it exactly, and "100.0" only where every seed of the sample held
    (more decimals where one would round a share that is not 1 to 100.0:
    `results.percent`)."""
    return percent(share, 1).rstrip("%")


def _label(value):
    return f"{value:g}" if isinstance(value, float) else str(value)


KEY = ("How to read a cell: the share of the seeds in which the claim held, in "
       "percent (the share seen), and a verdict from that share's 95% interval: ✓ "
       "holds (the whole interval at or above the claim's threshold), ✗ fails (all "
       "below), ? unclear. A share just above the threshold can be unclear: its "
       "interval reaches below. Purple: above the threshold; orange: below; white: at "
       "it. Outlined: the defaults.")
"""The key a map draws where a row of its maps leaves a place free (three claims in
two columns), followed by `KEY_MORE_SETTINGS` for a learner with more than two
settings."""
KEY_MORE_SETTINGS = "Each row of maps changes two settings, the others at their defaults."
"""What the key adds for a learner with more than two settings (a map per pair)."""


def robustness_map(result, title=None):
    """Draws, for every pair of a study's settings (rows) and every claim (columns),
    the share of seeds in which the claim held at each grid point.

    Each cell shows the share seen in percent (`cell_percent`) and a mark: ✓ where the
    claim holds (the whole 95% interval of the share is at or above the claim's
    threshold), ✗ where it fails (all below), ? where the interval straddles the
    threshold. The colour is the share, white at the threshold, and its colour bar is in
    percent as the cells are. The outlined cell is the library's default. Where a block
    of claims leaves a column free, the map draws its key there (`KEY`).

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
    # blocks below, the key (`KEY`) in the place a block leaves free. Each block: the
    # claims' titles, a row of maps per pair, then the colour bars. Placed by hand, in
    # inches (not with `new_figure`'s constrained layout, which costs a second of
    # drawing with this many texts).
    blocks = [claims[k:k + COLUMNS] for k in range(0, len(claims), COLUMNS)]
    columns = min(COLUMNS, len(claims))
    left, right, gap, column_width = 1.75, 0.1, 0.2, 2.4
    top, heading, panel, below, bar, bar_below, bottom = 1.0, 0.85, 1.45, 1.0, 0.15, 0.55, 0.1
    block_height = heading + len(pairs) * (panel + below) + bar + bar_below
    width = left + columns * column_width + (columns - 1) * gap + right
    height = top + len(blocks) * block_height + bottom
    fig = Figure(figsize=(width, height))

    def axes_at(column, y_top, h):
        """New axes in `column`, from `y_top` inches below the figure's top, `h` high."""
        x = left + column * (column_width + gap)
        return fig.add_axes([x / width, 1 - (y_top + h) / height, column_width / width,
                             h / height])

    for k, block in enumerate(blocks):
        y = top + k * block_height
        for j in range(columns):
            if j >= len(block):
                x = left + j * (column_width + gap) + 0.15
                key = KEY + (" " + KEY_MORE_SETTINGS if len(study.settings) > 2 else "")
                fig.text(x / width, 1 - y / height, textwrap.fill(key, 30), ha="left",
                         va="top", fontsize=10.5, linespacing=1.25)
                continue
            claim = block[j]
            norm = matplotlib.colors.TwoSlopeNorm(vmin=0.0, vcenter=claim.threshold, vmax=1.0)
            for i, pair in enumerate(pairs):
                ax = axes_at(j, y + heading + i * (panel + below), panel)
                image = _draw_pair(ax, result, claim, pair, norm, y_label=j == 0)
                if i == 0:
                    ax.set_title(textwrap.fill(f"{claim.text} (needs ≥ "
                                               f"{claim.threshold:.0%} of seeds)", 24),
                                 fontsize=12)
            cax = axes_at(j, y + heading + len(pairs) * (panel + below), bar)
            colour_bar = fig.colorbar(image, cax=cax, orientation="horizontal")
            colour_bar.set_label("share of seeds, %", fontsize=10, labelpad=1)
            colour_bar.set_ticks([0, claim.threshold, 1],
                                 labels=["0", f"{100 * claim.threshold:g}", "100"])
            # The ends' labels inside the bar's ends, so that two bars side by side do
            # not read as one number ("100" and "0" as "1000").
            first, *_, last = cax.get_xticklabels()
            first.set_horizontalalignment("left")
            last.set_horizontalalignment("right")
            cax.axvline(claim.threshold, color="black", linewidth=1)
    fig.suptitle(title or f"{textwrap.fill(study.title, 56)}\n{result.n_seeds:,} seeds per cell; "
                          f"outlined: the defaults\n✓ holds, ✗ fails, ? unclear (95% "
                          f"interval)", fontsize=13, y=1 - 0.08 / height, va="top")
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
