"""Seeds for many runs: one root seed gives independent, reproducible seeds per run."""

import numpy as np


def run_seeds(seed, n_runs, streams):
    """Integer seeds [run, stream] from one root seed (numpy SeedSequence.spawn).

    Run i gets the same seeds whatever n_runs is, so 20 seeds are the first 20 of 100.
    """
    children = np.random.SeedSequence(seed).spawn(n_runs)
    return [[int(s) for s in child.generate_state(streams)] for child in children]
