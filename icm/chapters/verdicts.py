"""The chapters' paired verdicts, in one place: two arms run on the same seeds, set side
by side as the arm minus the baseline, seed by seed (`differences`), a chapter's
comparisons decided together (`decide`: Holm's correction over the whole family, as
`icm.stats.corrected_verdicts` applies it), and the words of each verdict (`phrase`,
with `replication_words` for what its replication on fresh seeds found).

A verdict is "clear" only when the comparison survives the correction
(CONTRIBUTING, "One rule for clear"); every other difference reads "no clear
difference" (`NO_CLEAR_DIFFERENCE`), whatever its sign.
"""

import numpy as np

from icm import _validate
from icm.chapters.words import percent
from icm.stats import bootstrap_band, corrected_verdicts, paired_gaps

NO_CLEAR_DIFFERENCE = "no clear difference"
"""The words of a verdict that is not clear."""


def differences(arm, baseline, events=False):
    """The arm minus the baseline, seed by seed: two runs' per-seed values (the same
    seeds, in the same order), as floats.

    Args:
      arm, baseline: one value per seed each.
      events: the values are event numbers (a trial or an episode from 1, -1 for
        never): compare them on the seeds where both events happened
        (`icm.stats.paired_gaps`; negative where the arm's came sooner).

    Raises:
      ValueError: for values that are not one per seed each, of the same seeds.
    """
    if events:
        return paired_gaps(arm, baseline)
    arm = _validate.finite_array("arm", arm, ndim=1)
    baseline = _validate.finite_array("baseline", baseline, ndim=1)
    if arm.shape != baseline.shape:
        raise ValueError(f"arm and baseline must hold one value per seed each, of the same "
                         f"seeds, got {len(arm)} and {len(baseline)}")
    return arm - baseline


def band(values, resamples=1000):
    """(mean, low, high): the mean of per-seed `values` with its 95% percentile-bootstrap
    band (`icm.stats.bootstrap_band`, `resamples` resamples, seed 0), floats."""
    mean, low, high = bootstrap_band(np.asarray(values, dtype=float)[:, None],
                                     resamples=resamples)
    return float(mean[0]), float(low[0]), float(high[0])


def decide(family, resamples=1000):
    """A chapter's family of paired comparisons, decided together: for each, the mean
    difference with its 95% bootstrap band (`band`), its raw and Holm-corrected
    p-values, whether it is clear, the seeds compared and the family's size.

    Args:
      family: {name: per-seed differences (`differences`)}, every comparison the
        chapter calls clear or not.
      resamples: the bands' bootstrap resamples.

    Returns:
      {name: {"mean", "low", "high", "p", "p_holm", "clear", "n_seeds", "n_family"}}, in
      the family's order.
    """
    corrected = corrected_verdicts(family)
    out = {}
    for name, found in corrected.items():
        mean, low, high = band(family[name], resamples)
        out[name] = {"mean": mean, "low": low, "high": high, "p": found["p"],
                     "p_holm": found["p_holm"], "clear": found["clear"],
                     "n_seeds": len(family[name]), "n_family": found["n_family"]}
    return out


def phrase(mean, clear, lower, higher, unclear=NO_CLEAR_DIFFERENCE, clearly=True,
           bound=None, replication=None):
    """The words of one paired verdict: when it is clear (and its mean not 0), what the
    arm did, `lower` (its values below the baseline's: the mean difference below 0) or
    `higher`, after "clearly " unless `clearly` is False (the phrase says it itself);
    otherwise `unclear`. Then `bound` in brackets (e.g. "learning progress at the
    ceiling"), and, for a clear verdict, ", " and `replication` (what a rerun on fresh
    seeds found, `replication_words`).

    Examples: `phrase(-2.1, True, "sooner", "later")` is "clearly sooner";
    `phrase(0.3, False, "better", "worse")` is "no clear difference".
    """
    said = clear and mean != 0
    words = (("clearly " if clearly else "") + (lower if mean < 0 else higher)) if said \
        else unclear
    if bound:
        words += f" ({bound})"
    if said and replication:
        words += ", " + replication
    return words


def replication_words(replication, detail=True):
    """The words of a replication beside its verdict, from a stored replication
    (`icm.chapters.replication.replicated`, with "n_seeds" and, where computed,
    "power"): with `detail`, "replicated on 40 fresh seeds (power 97%)" or "not
    replicated on 40 fresh seeds, which detect an effect of this size 93% of the time"
    (a replication kept without its power says only its seeds); without, "not
    replicated on a fresh root", or None when it replicated."""
    if not detail:
        return None if replication["replicated"] else "not replicated on a fresh root"
    n, power = replication["n_seeds"], replication.get("power")
    # A simulated power of 1 is an estimate, not a certainty.
    shown = None if power is None else ("over 99%" if power > 0.99 else percent(power))
    if replication["replicated"]:
        return (f"replicated on {n} fresh seeds"
                + ("" if power is None else f" (power {shown})"))
    return (f"not replicated on {n} fresh seeds"
            + ("" if power is None else f", which detect an effect of this size "
                                        f"{shown} of the time"))
