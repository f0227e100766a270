"""Interest models for goal babbling: where in a box of goals to set the next goal,
for many agents (rows) at once.

In explauto's terms these are interest models: `sample` proposes goals, `update`
learns from how far the outcomes fell from them. The box is cut into fixed regions (a
grid); the regions' interest is learning progress, measured one of two ways
(`MEASURES`):

- "learning_progress": the paper's interest (section 3.1) applied to each region's
  history of distances between goals and outcomes: minus the least-squares slope of
  the last `window` distances when it is negative, else 0, with the paper's 50%
  share for a region that has only one distance (`icm.learners.interest.InterestTable`);
- "competence_progress": SAGG-RIAC's (Baranes and Oudeyer 2013), as explauto
  measures it: competence is minus the distance, and the interest is the absolute
  difference between the mean competence of the older and the newer half of the last
  `window` goals in the region; getting worse is interesting too.

`RandomGoals` is the baseline: goals uniform in the box.
"""

import numpy as np

from icm import _validate
from icm.learners.interest import InterestTable

DEFAULT_EPSILON = 0.3
"""Share of goals drawn in a region chosen uniformly, the rest in one chosen with
probability proportional to its interest (explauto's default for its discretised
progress). Not in the paper."""
DEFAULT_WINDOW = 10
"""Distances per region in the progress (explauto's window; the paper's is 5, over
tasks, not regions)."""
MEASURES = ("learning_progress", "competence_progress")
"""How a region's interest is measured (see the module docstring)."""


def check_box(low, high):
    """`low` and `high` as float arrays [dims], with high > low in every dimension."""
    low = _validate.finite_array("low", low, ndim=1)
    high = _validate.finite_array("high", high, shape=low.shape)
    if np.any(high <= low):
        raise ValueError(f"high must exceed low in every dimension, got low "
                         f"{_validate.show(low)} and high {_validate.show(high)}")
    return low, high


class RegionGrid:
    """A box of goals cut into a grid of equal regions, numbered as numpy's
    `ravel_multi_index` numbers the cells (the last dimension fastest).

    Args:
      low, high: the box's corners, arrays [dims].
      cells: the number of cells along each dimension, a tuple of integers >= 1.
    """

    def __init__(self, low, high, cells):
        self.low, self.high = check_box(low, high)
        if not isinstance(cells, (tuple, list)) or len(cells) != len(self.low):
            raise ValueError(f"cells must be one count per dimension ({len(self.low)}), "
                             f"got {_validate.show(cells)}")
        self.cells = tuple(_validate.integer_at_least(f"cells[{i}]", c, 1)
                           for i, c in enumerate(cells))
        self.n_regions = int(np.prod(self.cells))

    def bounds(self):
        """The regions' corners, [region, 2, dims] (low, high)."""
        size = (self.high - self.low) / np.array(self.cells)
        out = []
        for index in np.ndindex(*self.cells):
            low = self.low + np.array(index) * size
            out.append((low, low + size))
        return np.array(out)

    def region_of(self, points):
        """The region of each point [..., dims] (points outside the box fall in the
        nearest region), an int array [...]."""
        points = _validate.finite_array("points", points)
        if points.ndim < 1 or points.shape[-1] != len(self.low):
            raise ValueError(f"points must be an array [..., {len(self.low)}], got shape "
                             f"{points.shape}")
        cells = np.array(self.cells)
        index = np.floor((points - self.low) / (self.high - self.low) * cells).astype(np.int64)
        index = np.clip(index, 0, cells - 1)
        return np.ravel_multi_index(tuple(np.moveaxis(index, -1, 0)), self.cells)


class RandomGoals:
    """Random goal babbling: every goal uniform in the box (each row draws from its own
    generator, one number per dimension). Regions only label the goals.

    Args:
      grid: a `RegionGrid`.
      n_rows: agents.
    """

    def __init__(self, grid, n_rows):
        self.grid = _validate.instance("grid", grid, RegionGrid)
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)

    def sample(self, generators):
        """One goal per row: (goals [rows, dims], regions [rows])."""
        goals = np.array([rng.uniform(self.grid.low, self.grid.high) for rng in generators])
        return goals, self.grid.region_of(goals)

    def update(self, regions, distances):
        """Nothing to learn: random goals do not depend on the outcomes."""

    def values(self):
        """Every region's interest: 0."""
        return np.zeros((self.n_rows, self.grid.n_regions))


class RegionProgress:
    """Goals chosen by progress over fixed regions, for many agents (rows) at once.

    Each row, for each goal, draws two uniform numbers u, v: if u < `epsilon`, or
    while every interest is 0, the region is floor(v n_regions); otherwise the one
    whose share of the cumulated interest v falls in (probability proportional to its
    interest). Then the goal is uniform in that region (one number per dimension).

    Args:
      grid: a `RegionGrid`.
      n_rows: agents.
      measure: one of `MEASURES`.
      epsilon: share of uniformly chosen regions, in [0, 1].
      window: distances per region in the progress (>= 2).
    """

    def __init__(self, grid, n_rows, measure="learning_progress", epsilon=DEFAULT_EPSILON,
                 window=DEFAULT_WINDOW):
        self.grid = _validate.instance("grid", grid, RegionGrid)
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.measure = _validate.one_of("measure", measure, MEASURES)
        self.epsilon = _validate.in_closed_interval("epsilon", epsilon, 0.0, 1.0)
        self.window = _validate.integer_at_least("window", window, 2)
        self._bounds = grid.bounds()
        n_regions = grid.n_regions
        if self.measure == "learning_progress":
            self._table = InterestTable(self.n_rows, n_regions, "learning_progress",
                                        window=self.window)
        else:
            self._competence = np.zeros((self.n_rows, n_regions, self.window))  # newest last
            self._count = np.zeros((self.n_rows, n_regions), dtype=np.int64)
            self._progress = np.zeros((self.n_rows, n_regions))

    def values(self):
        """The interest of every region, [rows, regions]."""
        if self.measure == "learning_progress":
            return self._table.values()
        return self._progress

    def sample(self, generators):
        """One goal per row: (goals [rows, dims], regions [rows])."""
        values = self.values()
        regions = np.empty(self.n_rows, dtype=np.int64)
        goals = np.empty((self.n_rows, len(self.grid.low)))
        for k, rng in enumerate(generators):
            regions[k] = choose_region(values[k], self.epsilon, rng)
            goals[k] = rng.uniform(*self._bounds[regions[k]])
        return goals, regions

    def update(self, regions, distances):
        """Records the distance between each row's goal (in `regions[k]`) and what its
        movement reached."""
        if self.measure == "learning_progress":
            self._table.record(None, regions, distances)
            return
        rows = np.arange(self.n_rows)
        history = self._competence[rows, regions]
        history = np.concatenate([history[:, 1:], -np.asarray(distances)[:, None]], axis=1)
        self._competence[rows, regions] = history
        count = self._count[rows, regions] + 1
        self._count[rows, regions] = count
        self._progress[rows, regions] = competence_progress(history, count)


def competence_progress(history, count):
    """SAGG-RIAC's progress of each row of `history` [rows, window] (competences,
    newest last), of which the last `count[r]` are real: |mean of the newer half -
    mean of the older half| over the last min(count, window); 0 with fewer than 2
    (explauto's "abs_deriv_smooth": the older half is the first n // 2)."""
    window = history.shape[1]
    n = np.minimum(count, window)
    position = np.arange(window)[None, :] - (window - n)[:, None]  # 0 = oldest real one
    real = position >= 0
    older = real & (position < (n // 2)[:, None])
    newer = real & ~older
    mean = lambda mask: (history * mask).sum(axis=1) / np.maximum(mask.sum(axis=1), 1)
    return np.where(n >= 2, np.abs(mean(newer) - mean(older)), 0.0)


def choose_region(values, epsilon, rng):
    """A region: uniformly with probability `epsilon` (or while every interest is 0),
    else with probability proportional to its interest. Draws two numbers from
    `rng`."""
    explore, draw = rng.random(2)
    total = values.sum()
    if explore < epsilon or not total > 0:
        return min(int(draw * len(values)), len(values) - 1)
    return min(int(np.searchsorted(np.cumsum(values), draw * total, side="right")),
               len(values) - 1)
