"""The command that writes assets/replications.json, the replications of every chapter's
clear verdicts on its fresh root (`icm.chapters.replication`):

    python -m icm.chapters.replicate                 # every chapter
    python -m icm.chapters.replicate curiosity       # those named, the others kept

"Forming actions" reads its fresh seeds' runs (assets/remedies_fresh_runs.json, which
`python -m icm study remedies-replication` writes); "Which curiosity?" runs its six
runs of 200 seeds (under a CPU-minute); "What the result depends on" runs its three
maps on the fresh root (minutes).
"""

import json

from icm import _validate
from icm.chapters import curiosity, forming_actions, robustness
from icm.chapters.replication import REPLICATION_FILE, load_replications
from icm.store import ASSETS, write_text


def runs():
    """{chapter: the function that computes its entry of assets/replications.json}."""
    return {"forming_actions": forming_actions.family.run_replications,
            "curiosity": curiosity.run_replications,
            "robustness": lambda: robustness.maps.run_replication(progress=True)}


def main(argv=None):
    """Computes every chapter's replications (or those of the chapters named as
    arguments, e.g. `python -m icm.chapters.replicate curiosity`) and writes
    assets/replications.json, keeping the other chapters' entries. "Forming actions"
    reads its fresh seeds' runs (assets/remedies_fresh_runs.json, written by `python -m
    icm study remedies-replication`)."""
    import sys

    argv = sys.argv[1:] if argv is None else argv
    computed = runs()
    chosen = list(argv) or list(computed)
    for chapter in chosen:
        _validate.one_of("chapter", chapter, tuple(computed))
    out = load_replications()
    for chapter in chosen:
        out[chapter] = computed[chapter]()
    path = ASSETS / REPLICATION_FILE
    write_text(path, json.dumps(out, indent=1) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
