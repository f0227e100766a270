"""Seeds for many runs: one root seed gives independent, reproducible seeds per run."""

import numpy as np

from icm import _validate


def run_seeds(seed, n_runs, streams, first=0):
    """Integer seeds [run, stream] for runs first..first+n_runs-1 of a root seed.

    Run i's seeds are those of child i of `numpy.random.SeedSequence(seed)` (as
    `SeedSequence.spawn` numbers them), so they depend only on the root seed and i:
    20 seeds are the first 20 of 100, and run 7 alone (first=7, n_runs=1) is run 7 of
    any larger batch.
    """
    children = [np.random.SeedSequence(seed, spawn_key=(i,)) for i in range(first, first + n_runs)]
    return [[int(s) for s in child.generate_state(streams)] for child in children]


def check_run_size(function, n_seeds, steps, bytes_per_seed_step, bytes_per_seed=0):
    """Raises ValueError if a run of `function` with `n_seeds` seeds of `steps` trials
    or episodes would need more memory than the machine has (see
    `icm._validate.fits_in_memory`)."""
    needed = n_seeds * (steps * bytes_per_seed_step + bytes_per_seed)
    _validate.fits_in_memory(f"{function} with {n_seeds} seeds of {steps} steps", needed)


REPLICATION_ROOTS = {"forming_actions": 9001, "curiosity": 9002, "robustness": 9003}
"""The root seed of each chapter's replications, which rerun its clear verdicts on seeds
no run of it used (`icm.chapters.replication`): none of the studies' roots (100 to
400), the chapters' (0) or the other tests' (below 100) is 9001 or above."""
