"""The reference workload that every time in this project is set beside: `make bench`
(benchmarks/bench.py), the book build's record of execution times
(book/_ext/execute_book.py) and the test suite's record of durations
(tests/conftest.py). This machine's speed varies from hour to hour (by up to 2.5
times, seen here), so a time is read as its ratio to this workload timed in the same
minutes: a ratio moves much less than a time."""

import time

import numpy as np


def reference_workload():
    """The yardstick: 20,000 small numpy operations in a Python loop, the kind of work
    the batched learners do (about 0.02 to 0.09 s here)."""
    a, b = np.linspace(0, 1, 200), np.linspace(1, 2, 200)
    total = 0.0
    for _ in range(20000):
        total += (a * b + a)[3]
    return total


def reference_seconds(repeats=5):
    """The best of `repeats` timings of `reference_workload` (s)."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        reference_workload()
        times.append(time.perf_counter() - start)
    return min(times)
