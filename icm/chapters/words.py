"""The chapters' words for numbers: a share as a percentage that never says "all" or
"none" when it is not (`percent`), the fewest seeds in which something held
(`in_seeds`), and a Markdown table of measures with one column per run
(`measures_table`)."""

import math

from icm import _validate

def in_seeds(lowest):
    """The fewest seeds in which something held, `lowest` a share in [0, 1], in words:
    "in every seed" when it is 1, else "in at least 96.5% of the seeds": the share
    rounded down to one decimal, so that the sentence stays true (and a share below 1
    never reads as 100.0%)."""
    lowest = _validate.real("lowest", lowest, 0.0, 1.0)
    if lowest == 1:
        return "in every seed"
    shown = math.floor(1000 * lowest + 1e-9) / 10  # 1e-9: 0.965 is 964.99... in floats
    return f"in at least {shown:.1f}% of the seeds"


MAX_DECIMALS = 3
"""The most decimals `percent` shows: a share closer to 0 or 1 than that shows as the
nearest percentage at this precision that is not 0% or 100%."""


def percent(share, decimals=0):
    """A share in [0, 1] as a percentage with `decimals` decimals ("73%"), and with more
    where fewer would read as 0% or 100% for a share that is neither: 199 seeds of 200
    are "99.5%", not "100%" (which a reader takes for every seed). NaN gives "n/a".

    Raises:
      ValueError: for a share outside [0, 1], or decimals outside 0 to `MAX_DECIMALS`.
    """
    decimals = _validate.integer_in_range("decimals", decimals, 0, MAX_DECIMALS)
    if _validate.is_real(share) and math.isnan(float(_validate.scalar(share))):
        return "n/a"
    share = _validate.real("share", share, 0.0, 1.0)
    for shown in range(decimals, MAX_DECIMALS + 1):
        text = f"{share:.{shown}%}"
        if share in (0.0, 1.0) or text not in (f"{0:.{shown}%}", f"{1:.{shown}%}"):
            return text
    # Closer to an end than MAX_DECIMALS shows: the nearest value inside, rounded away
    # from that end.
    step = 10 ** (MAX_DECIMALS + 2)
    inside = math.floor(share * step) if share > 0.5 else math.ceil(share * step)
    return f"{100 * inside / step:.{MAX_DECIMALS}f}%"


def measures_table(results, measures):
    """A Markdown table with one column per run and one row per measure: narrow enough
    for a book page however many measures there are.

    Args:
      results: a dict {column label: result}.
      measures: a list of (row label, function of a result giving the cell's text).
    """
    labels = list(results)
    # The first column is named too: a header cell left empty says nothing to a screen
    # reader (axe: empty-table-header).
    lines = ["| measure | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    for name, cell in measures:
        lines.append(f"| {name} | " + " | ".join(cell(r) for r in results.values()) + " |")
    return "\n".join(lines)
