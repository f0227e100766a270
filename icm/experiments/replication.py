"""Replication of the chapters' clear verdicts on root seeds that no study, chapter or
test otherwise uses: the roots, the rule, and the stored outcomes.

A verdict the book calls clear is rerun by the tests on its chapter's root of
`REPLICATION_ROOTS` (`remedies_study.replicate`), and the outcome is kept in
assets/replications.json (`python -m icm.experiments.replication` writes it; the tests
rerun it and expect the same numbers). A chapter glues "not replicated" beside a
verdict that did not replicate, rather than dropping it.
"""

import json

from icm import _validate
from icm.store import ASSETS, asset_path
from icm.stats import FAMILY_RATE, paired_p_value

REPLICATION_ROOTS = {"forming_actions": 9001, "curiosity": 9002, "robustness": 9003}
"""The root seed of each chapter's replications: none of the studies' (100 to 400),
the chapters' (0) or the other tests' roots (below 100) is 9001 or above."""
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


def main():
    """Runs every chapter's replications (or those of the chapters named as arguments,
    e.g. `python -m icm.experiments.replication curiosity`) and writes
    assets/replications.json, keeping the other chapters' entries. For "Forming
    actions", its replications are computed from its fresh seeds' runs
    (`remedies_study.FRESH_FILE`, written by `python -m icm study
    remedies-replication`), which it runs first only when that file is missing."""
    import sys

    from icm.experiments import curiosity, remedies_study

    def forming_actions():
        path = ASSETS / remedies_study.FRESH_FILE
        if not path.exists():
            fresh = remedies_study.run_fresh_seeds()
            path.write_text(json.dumps(fresh, separators=(",", ":")) + "\n")
            print(f"wrote {path}")
        return remedies_study.run_replications()

    runs = {"forming_actions": forming_actions, "curiosity": curiosity.run_replications}
    chosen = sys.argv[1:] or list(runs)
    for chapter in chosen:
        _validate.one_of("chapter", chapter, tuple(runs))
    out = load_replications()
    for chapter in chosen:
        out[chapter] = runs[chapter]()
    path = ASSETS / REPLICATION_FILE
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
