"""The chapters' words for numbers: a share as a percentage that never says "all" or
"none" when it is not (`percent`), the fewest seeds in which something held
(`in_seeds`: a count of the sample or a lower bound, never "every seed"), and a
Markdown table of measures with one column per run (`measures_table`)."""

import math

from icm import _validate

def in_seeds(lowest, n_seeds=None):
    """The fewest seeds in which something held, in words that say no more than the data.

    A sample's 100% is not "every seed" (book/_ext/claim_words.py), so there are two
    forms, neither of which says "every":

    - without `n_seeds`, `lowest` is the lower end of a share's 95% interval, what the
      seeds vouch for (e.g. the lowest over a map's points): "in at least 96.5% of the
      seeds", rounded down so that the sentence stays true. No finite sample vouches
      for every seed, so a lower end of 1 is refused;
    - with `n_seeds`, `lowest` is the share seen in a sample of that many seeds (the
      smallest, over runs of that size), and the words are a count of the sample:
      "in 200 of the 200 seeds", or "in at least 197 of the 200 seeds".

    Args:
      lowest: a share in [0, 1].
      n_seeds: the seeds of the sample (an integer >= 1), or None (see above).

    Raises:
      ValueError: for a share outside [0, 1], a lower end of 1 without `n_seeds`, or a
        share that is not a count of `n_seeds` seeds.
    """
    lowest = _validate.real("lowest", lowest, 0.0, 1.0)
    if n_seeds is not None:
        n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
        held = round(lowest * n_seeds)
        if abs(held - lowest * n_seeds) > 1e-6:
            raise ValueError(f"lowest must be a share of {n_seeds} seeds (a count divided "
                             f"by n_seeds), got {lowest!r}")
        return (f"in {held} of the {n_seeds} seeds" if held == n_seeds else
                f"in at least {held} of the {n_seeds} seeds")
    if lowest == 1:
        raise ValueError("lowest must be the lower end of an interval, below 1 (no sample "
                         "vouches for every seed), got 1; for a share seen, give n_seeds "
                         "(a count: 'in 200 of the 200 seeds')")
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
