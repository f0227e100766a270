"""Random numbers for many runs at once: one stream of uniform numbers per row.

A batched learner or environment advances many independent runs (rows) together, but
each run must draw exactly the numbers it would draw alone, so that run k of a batch
equals run k run by itself, and equals the per-run reference classes seed for seed.
`Streams` keeps one `numpy.random.Generator` per row and hands out its uniform numbers
in order, a few at a time, from a buffer refilled by whole chunks (a Generator's
`random(n)` gives the same numbers as n calls of `random()`). The buffer starts small
and grows sixteenfold at each refill up to its chunk, so that a short run does not draw
thousands of numbers it never uses.
"""

import numpy as np


GENERATOR_BYTES = 1000
"""An upper bound on the memory of one row's `numpy.random.Generator` and its share of
the bookkeeping (measured: 450 to 900 bytes)."""


def _max_chunk(n_rows, chunk=None):
    """The most numbers a `Streams` of `n_rows` rows buffers per row."""
    return int(chunk or max(16, min(4096, (1 << 23) // max(n_rows, 1))))


def memory_bound(n_rows, draws_per_row, chunk=None, k=1):
    """An upper bound on the bytes a `Streams(seeds, chunk)` of `n_rows` rows holds at
    its largest, when no row draws more than `draws_per_row` numbers in all, `k` at a
    time: the generators, and the buffer at the largest length those draws can make it
    grow to together with the buffer before it (both are held while it grows).

    The buffer grows (for every row) when a row needs more numbers than it holds;
    after growing to each length, a row has kept fewer than `k` of its unused numbers,
    so a row has had at least the sum of the lengths so far, less k - 1 per growth,
    when the buffer must grow again.
    """
    largest = _max_chunk(n_rows, chunk)
    lengths = [min(Streams.FIRST_CHUNK, largest)]
    while lengths[-1] < largest and \
            draws_per_row > sum(lengths) - (k - 1) * (len(lengths) - 1):
        lengths.append(min(largest, 16 * lengths[-1]))
    held = lengths[-1] + (lengths[-2] if len(lengths) > 1 else 0)
    return n_rows * (GENERATOR_BYTES + 8 * held + 8)


class Streams:
    """Per-row streams of uniform numbers in [0, 1).

    Args:
      seeds: one integer seed (or Generator) per row.
      chunk: the most numbers buffered per row (at most 4096, fewer for large batches:
        the buffer stays under 64 MB). The buffer starts at `FIRST_CHUNK` numbers a row
        (or `chunk` if smaller) and grows to `chunk`; code that reads `buffer` itself
        reads it again after each `refill`.
    """

    FIRST_CHUNK = 64

    def __init__(self, seeds, chunk=None):
        self.generators = [s if isinstance(s, np.random.Generator) else np.random.default_rng(s)
                           for s in seeds]
        n = len(self.generators)
        self.max_chunk = _max_chunk(n, chunk)
        self.chunk = min(self.FIRST_CHUNK, self.max_chunk)
        self.buffer = np.empty((n, self.chunk))
        for row, generator in enumerate(self.generators):
            self.buffer[row] = generator.random(self.chunk)
        self.cursor = np.zeros(n, dtype=np.int64)
        self._aligned = 0  # while every row has drawn alike: their common cursor; else None

    def __len__(self):
        return len(self.generators)

    def refill(self, rows, k):
        """Makes room for `k` more numbers in each of `rows` that needs it (for code
        that reads `buffer` and moves `cursor` itself)."""
        self._aligned = None
        self._refill(np.asarray(rows, dtype=np.int64), k)

    def _refill(self, rows, k):
        """Makes room for k more numbers in each of `rows` (those that need it)."""
        short = rows[self.cursor[rows] + k > self.chunk]
        while len(short) and self.chunk < self.max_chunk:  # grow: every row moves over
            self._grow()
            short = rows[self.cursor[rows] + k > self.chunk]
        for row in short.tolist():
            used = int(self.cursor[row])
            rest = self.buffer[row, used:].copy()
            self.buffer[row, :len(rest)] = rest
            self.buffer[row, len(rest):] = self.generators[row].random(used)
            self.cursor[row] = 0

    def _grow(self):
        """A buffer sixteen times longer (at most `max_chunk`): every row keeps its unused
        numbers, then draws the next ones; every cursor is back at 0."""
        chunk = min(self.max_chunk, 16 * self.chunk)
        buffer = np.empty((len(self.generators), chunk))
        for row, generator in enumerate(self.generators):
            rest = self.buffer[row, int(self.cursor[row]):]
            buffer[row, :len(rest)] = rest
            buffer[row, len(rest):] = generator.random(chunk - len(rest))
        self.buffer, self.chunk = buffer, chunk
        self.cursor[:] = 0

    def draw(self, rows=None, k=1):
        """The next `k` numbers of each row in `rows` (default: every row), an array
        [len(rows), k]; each row's cursor moves on by k. The array may be a view of the
        buffer: use it before the next draw, or copy it."""
        if k > self.max_chunk:
            raise ValueError(f"k must be at most the chunk {self.max_chunk}, got {k}")
        if rows is None and self._aligned is not None:  # every row alike: a slice
            start = self._aligned
            if start + k > self.chunk:
                self._refill(np.arange(len(self.generators)), k)
                start = 0
            self._aligned = start + k
            self.cursor[:] = self._aligned
            return self.buffer[:, start:start + k]
        self._aligned = None
        if rows is None:
            rows = np.arange(len(self.generators))
        self._refill(rows, k)
        columns = self.cursor[rows][:, None] + np.arange(k)
        out = self.buffer[rows[:, None], columns]
        self.cursor[rows] += k
        return out
