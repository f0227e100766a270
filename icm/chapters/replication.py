"""Replication of the chapters' clear verdicts on root seeds that no study, chapter or
test otherwise uses (`icm.experiments.seeding.REPLICATION_ROOTS`): the rule
(`replicated`), and the stored outcomes (`load_replications`).

A verdict the book calls clear is rerun on its chapter's fresh root
(`icm.chapters.forming_actions.family.run_replications`, `icm.chapters.curiosity.
run_replications`, `icm.chapters.robustness.maps.run_replication`), and the outcome is kept
in assets/replications.json: `python -m icm.chapters.replicate` writes it (every
chapter, or those named: `python -m icm.chapters.replicate curiosity`), the one writer
of that file; the tests rerun it and expect the same numbers. A chapter glues "not
replicated" beside a verdict that did not replicate, rather than dropping it.
"""

import json

from icm import _validate
from icm.stats import FAMILY_RATE, paired_p_value
from icm.store import asset_path

REPLICATION_FILE = "replications.json"
"""The file in assets/ that holds the replications' outcomes."""


def replicated(differences, direction, seed=0):
    """The outcome of one replication: the per-seed differences on the fresh root, their
    one-sided sign-flip p-value (`paired_p_value`) in the study's `direction` ("less"
    or "greater"), and whether it is below `FAMILY_RATE`. A dict {"mean", "p",
    "replicated"}."""
    direction = _validate.one_of("direction", direction, ("less", "greater"))
    p = paired_p_value(differences, seed, alternative=direction)
    return {"mean": float(sum(differences) / len(differences)), "p": p,
            "replicated": bool(p < FAMILY_RATE)}


def load_replications():
    """{chapter: {"root", "n_seeds", "verdicts": {name: `replicated` dict}}}, read from
    assets/replications.json ({} when it does not exist yet)."""
    try:
        return json.loads(asset_path(REPLICATION_FILE).read_text())
    except FileNotFoundError:
        return {}
