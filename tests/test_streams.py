"""The per-row random streams of the batched learners: each row hands out exactly the
numbers its own Generator gives, in order, whichever rows draw and however the buffer
grows and refills."""

import numpy as np
import pytest

from icm._streams import Streams

SEEDS = [1, 2, 3]


def alone(seed, n):
    return np.random.default_rng(seed).random(n)


def test_every_row_draws_its_own_generator_in_order_while_all_rows_draw_together():
    streams = Streams(SEEDS)
    drawn = np.concatenate([streams.draw(k=3).copy() for _ in range(3000)], axis=1)
    assert streams.chunk == streams.max_chunk  # the buffer grew to full size, then refilled
    for row, seed in enumerate(SEEDS):
        np.testing.assert_array_equal(drawn[row], alone(seed, 9000))


def test_rows_that_draw_apart_still_get_their_own_numbers_in_order():
    streams, choose = Streams(SEEDS, chunk=512), np.random.default_rng(0)
    got = [[] for _ in SEEDS]
    for _ in range(4000):
        rows = np.flatnonzero(choose.random(len(SEEDS)) < 0.5)
        k = int(choose.integers(1, 4))
        for row, numbers in zip(rows, streams.draw(rows, k=k)):
            got[row].extend(numbers)
        if choose.random() < 0.1:
            streams.draw(k=1)[:, 0].tolist()  # now and then every row at once
            for row in range(len(SEEDS)):
                got[row].append(streams.buffer[row, streams.cursor[row] - 1])
    for row, seed in enumerate(SEEDS):
        assert len(got[row]) > 600
        np.testing.assert_array_equal(got[row], alone(seed, len(got[row])))


def test_a_short_run_does_not_fill_the_whole_buffer():
    streams = Streams(SEEDS)
    assert streams.buffer.shape == (3, Streams.FIRST_CHUNK)
    assert streams.max_chunk == 4096


def test_more_numbers_than_the_chunk_at_once_is_refused():
    with pytest.raises(ValueError, match="k must be at most the chunk 16, got 17"):
        Streams(SEEDS, chunk=16).draw(k=17)
