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

import dataclasses

import numpy as np

from icm import _validate
from icm._settings import Names, Setting
from icm.learners.interest import InterestTable, least_squares_slope

MEASURES = ("learning_progress", "competence_progress")
"""How a region's interest is measured (see the module docstring)."""
EPSILON = Setting(
    default=0.3, label="learning progress: share of goals in a region drawn uniformly",
    kind="real", low=0.0, high=1.0,
    source="the paper has no goal babbling: explauto's default for its discretised "
           "progress; the rest of the goals go to a region drawn with probability "
           "proportional to its interest")
"""Learning progress's share of uniformly drawn regions."""
WINDOW = Setting(
    default=10, label="learning progress: distances per region in the progress",
    kind="integer", low=2,
    source="the paper has no goal babbling: explauto's window (the paper's is 5, over "
           "tasks, not regions)")
"""Distances per region in the progress."""
MEASURE = Setting(
    default="learning_progress", label="learning progress: how a region's progress is "
    "measured (the paper's slope of distances, or SAGG-RIAC's competence progress)",
    kind="choice", choices=MEASURES,
    source="the paper's interest (section 3.1) applied to regions; competence progress "
           "is SAGG-RIAC's (Baranes and Oudeyer 2013)")
"""How learning progress measures a region's progress."""
REGIONS = Setting(
    default="fixed", label="learning progress: fixed regions, or regions that split as "
    "goals accumulate", kind="choice", choices=Names(lambda: tuple(REGION_KINDS)),
    source="the paper has no goal babbling: a fixed grid, or SAGG-RIAC's splitting")
"""Learning progress's regions (`REGION_KINDS`)."""
STRATEGY = Setting(
    default="learning_progress", label="how the next movement is chosen",
    kind="choice", choices=Names(lambda: tuple(STRATEGIES)),
    source="the paper has no goal babbling: the strategies of `STRATEGIES`")
"""The goal-choice strategy (`STRATEGIES`)."""
DEFAULT_EPSILON = EPSILON.default
DEFAULT_WINDOW = WINDOW.default


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
        """Nothing to learn: random goals do not depend on the outcomes (the arguments
        are checked as `RegionProgress.update` checks them)."""
        check_update(regions, distances, self.n_rows, self.grid.n_regions)

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
      measure: one of `MEASURES` (see `MEASURE`).
      epsilon: share of uniformly chosen regions (see `EPSILON`).
      window: distances per region in the progress (see `WINDOW`).
    """

    def __init__(self, grid, n_rows, measure="learning_progress", epsilon=DEFAULT_EPSILON,
                 window=DEFAULT_WINDOW):
        self.grid = _validate.instance("grid", grid, RegionGrid)
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.measure = MEASURE.check(measure, "measure")
        self.epsilon = EPSILON.check(epsilon, "epsilon")
        self.window = WINDOW.check(window, "window")
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
        regions, distances = check_update(regions, distances, self.n_rows,
                                          self.grid.n_regions)
        if self.measure == "learning_progress":
            self._table.record(None, regions, distances)
            return
        rows = np.arange(self.n_rows)
        history = self._competence[rows, regions]
        history = np.concatenate([history[:, 1:], -distances[:, None]], axis=1)
        self._competence[rows, regions] = history
        count = self._count[rows, regions] + 1
        self._count[rows, regions] = count
        self._progress[rows, regions] = competence_progress(history, count)


def competence_progress(history, count):
    """SAGG-RIAC's progress of each row of `history` [rows, window] (competences,
    newest last), of which the last `count[r]` are real: abs(mean of the newer half -
    mean of the older half) over the last min(count, window); 0 with fewer than 2
    (explauto's "abs_deriv_smooth": the older half is the first n // 2)."""
    window = history.shape[1]
    n = np.minimum(count, window)
    position = np.arange(window)[None, :] - (window - n)[:, None]  # 0 = oldest real one
    real = position >= 0
    older = real & (position < (n // 2)[:, None])
    newer = real & ~older
    mean = lambda mask: (history * mask).sum(axis=1) / np.maximum(mask.sum(axis=1), 1)
    return np.where(n >= 2, np.abs(mean(newer) - mean(older)), 0.0)


def check_update(regions, distances, n_rows, n_regions):
    """`regions` (one region index per row, in 0..n_regions-1) and `distances` (one
    finite distance >= 0 per row), checked, as int and float arrays."""
    regions = _validate.integer_array("regions", regions, ndim=1)
    if len(regions) != n_rows or np.any((regions < 0) | (regions >= n_regions)):
        raise ValueError(f"regions must be one region in 0..{n_regions - 1} per row "
                         f"({n_rows}), got {_validate.show(regions)}")
    distances = _validate.finite_array("distances", distances, shape=(n_rows,))
    if np.any(distances < 0):
        raise ValueError(f"distances must be >= 0, got {_validate.show(distances)}")
    return regions, distances


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


DEFAULT_MAX_GOALS = 100
"""Splitting regions: a region holding more goals than this splits in two (explauto's
SAGG-RIAC tree, `max_points_per_region`). Not in the paper."""


class SplittingRegionProgress:
    """Goals chosen by progress over regions that split as goals accumulate, SAGG-RIAC's
    way (Baranes and Oudeyer 2013), for many agents (rows) at once.

    Each row starts from the whole box as one region. When a region holds more than
    `max_goals` goals it splits in two across one dimension (x, then y, then z, then
    x again down the tree) at the midpoint between two of its goals' coordinates
    that maximises n_low x n_high x abs(interest_low - interest_high), explauto's
    "best_interest_diff" for a region that just passed its limit: each half keeps
    the goals (and distances) that fall in it. A region's interest is measured by
    `measure` over its last `window` goals: "learning_progress", max(-slope, 0) of
    its distances (0 with fewer than 2; unlike the fixed regions, no new-region
    share), or "competence_progress" (`competence_progress`). Regions are chosen as
    `RegionProgress` chooses them (two numbers, then one per dimension for the goal).

    The region numbers reported (`sample`'s second result) are those of the fixed
    `grid`, for comparison with the other interest models; `values` gives each fixed
    region the interest of the region that holds its centre.

    Args:
      grid: a `RegionGrid` (its box is the goal space).
      n_rows: agents.
      measure: one of `MEASURES`.
      epsilon: share of uniformly chosen regions, in [0, 1].
      window: goals per region in the progress (>= 2).
      max_goals: goals a region may hold before it splits (> window).
    """

    def __init__(self, grid, n_rows, measure="learning_progress", epsilon=DEFAULT_EPSILON,
                 window=DEFAULT_WINDOW, max_goals=DEFAULT_MAX_GOALS):
        self.grid = _validate.instance("grid", grid, RegionGrid)
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.measure = MEASURE.check(measure, "measure")
        self.epsilon = EPSILON.check(epsilon, "epsilon")
        self.window = WINDOW.check(window, "window")
        self.max_goals = _validate.integer_at_least("max_goals", max_goals, self.window + 1)
        self._centres = grid.bounds().mean(axis=1)
        box = np.stack([grid.low, grid.high])
        # Per row: the regions' corners, split dimension, goals and distances, interest.
        self.bounds = [[box.copy()] for _ in range(self.n_rows)]
        self.split_dims = [[0] for _ in range(self.n_rows)]
        self.members = [[[]] for _ in range(self.n_rows)]  # [(goal, distance)] per region
        self.interests = [[0.0] for _ in range(self.n_rows)]
        self._chosen = np.zeros(self.n_rows, dtype=np.int64)
        self._goals = None

    def n_regions(self):
        """The number of regions of each row, [rows]."""
        return np.array([len(b) for b in self.bounds])

    def values(self):
        """Each fixed region's interest: that of the row's region holding its centre,
        [rows, fixed regions]."""
        out = np.zeros((self.n_rows, len(self._centres)))
        for k in range(self.n_rows):
            out[k] = np.array(self.interests[k])[self._leaf_of(k, self._centres)]
        return out

    def _leaf_of(self, k, points):
        bounds = np.array(self.bounds[k])  # [regions, 2, dims]
        inside = np.all((points[:, None, :] >= bounds[None, :, 0])
                        & (points[:, None, :] <= bounds[None, :, 1]), axis=2)
        return np.argmax(inside, axis=1)

    def sample(self, generators):
        """One goal per row: (goals [rows, dims], fixed regions [rows])."""
        goals = np.empty((self.n_rows, len(self.grid.low)))
        for k, rng in enumerate(generators):
            leaf = choose_region(np.array(self.interests[k]), self.epsilon, rng)
            self._chosen[k] = leaf
            goals[k] = rng.uniform(*self.bounds[k][leaf])
        self._goals = goals
        return goals, self.grid.region_of(goals)

    def update(self, regions, distances):
        """Records the distance between each row's last goal and what its movement
        reached (`regions`, the fixed ones, are not needed: the row knows its region)."""
        if self._goals is None:
            raise ValueError("update must follow sample: no goal has been proposed yet")
        _, distances = check_update(regions, distances, self.n_rows, self.grid.n_regions)
        for k in range(self.n_rows):
            leaf = self._chosen[k]
            self.members[k][leaf].append((self._goals[k].copy(), float(distances[k])))
            if len(self.members[k][leaf]) > self.max_goals:
                self._split(k, leaf)
            else:
                self.interests[k][leaf] = self._interest(self.members[k][leaf])

    def _interest(self, members):
        distances = np.array([d for _, d in members[-self.window:]])
        if len(distances) < 2:
            return 0.0
        if self.measure == "learning_progress":
            return max(0.0, -least_squares_slope(distances))
        return float(competence_progress(-distances[None, :], np.array([len(distances)]))[0])

    def _split(self, k, leaf):
        members, dim = self.members[k][leaf], self.split_dims[k][leaf]
        coordinate = np.array([goal[dim] for goal, _ in members])
        values = np.unique(coordinate)
        best, best_fitness = None, -1.0
        for cut in (values[:-1] + values[1:]) / 2:
            low = [m for m, c in zip(members, coordinate) if c <= cut]
            high = [m for m, c in zip(members, coordinate) if c > cut]
            fitness = len(low) * len(high) * abs(self._interest(low) - self._interest(high))
            if fitness > best_fitness:
                best, best_fitness = cut, fitness
        if best is None:  # every goal at one coordinate: nothing to split on
            self.interests[k][leaf] = self._interest(members)
            return
        bounds = self.bounds[k][leaf]
        low_bounds, high_bounds = bounds.copy(), bounds.copy()
        low_bounds[1, dim] = high_bounds[0, dim] = best
        low = [m for m, c in zip(members, coordinate) if c <= best]
        high = [m for m, c in zip(members, coordinate) if c > best]
        following = (dim + 1) % len(self.grid.low)
        self.bounds[k][leaf], self.members[k][leaf] = low_bounds, low
        self.split_dims[k][leaf] = following
        self.interests[k][leaf] = self._interest(low)
        self.bounds[k].append(high_bounds)
        self.members[k].append(high)
        self.split_dims[k].append(following)
        self.interests[k].append(self._interest(high))


REGION_KINDS = {"fixed": RegionProgress, "splitting": SplittingRegionProgress}
"""Learning progress's regions: a fixed grid, or regions that split as goals
accumulate (the class of each)."""


@dataclasses.dataclass(frozen=True)
class GoalStrategy:
    """One way to choose what to babble next, as `goal_strategy` registers it.

    Attributes:
      name: its name, the `strategy=` of `icm.experiments.run_goal_babbling`.
      label: what the book calls it.
      make: a function (grid, n_rows, measure, epsilon, window, regions) returning the
        rows' goal choice (`sample`, `update`, `values`), or None for movements drawn
        at random with no goal (random motor babbling).
      by_interest: whether its goals follow the regions' interest (whose values a run
        keeps after each rollout).
    """

    name: str
    label: str
    make: object
    by_interest: bool


STRATEGIES = {}
"""The goal-choice strategies by name, in the order they are registered
(`goal_strategy`): `make_goal_choice`, the goal-babbling runs, their settings and
the command line read it."""


def goal_strategy(name, label, by_interest=False):
    """Registers the decorated function as the goal-choice strategy `name` (see
    `GoalStrategy`), where it is defined.

    Args:
      name: the strategy's name (new).
      label: what the book calls it.
      by_interest: whether its goals follow the regions' interest.

    Raises:
      ValueError: for a name registered already.
    """
    name = _validate.text("name", name)
    if name in STRATEGIES:
        raise ValueError(f"name must be new, got {name!r}: registered already")

    def register(make):
        STRATEGIES[name] = GoalStrategy(name, _validate.text("label", label),
                                        _validate.function("make", make, allow_none=False),
                                        _validate.boolean("by_interest", by_interest))
        return make
    return register


@goal_strategy("random_motor", "random motor babbling")
def _random_motor(grid, n_rows, measure, epsilon, window, regions):
    return None  # no goals: each movement drawn at random


@goal_strategy("random_goal", "random goal babbling")
def _random_goal(grid, n_rows, measure, epsilon, window, regions):
    return RandomGoals(grid, n_rows)


@goal_strategy("learning_progress", "goals by learning progress", by_interest=True)
def _learning_progress(grid, n_rows, measure, epsilon, window, regions):
    return REGION_KINDS[regions](grid, n_rows, measure, epsilon, window)


def make_goal_choice(strategy, grid, n_rows, measure=MEASURE.default, epsilon=EPSILON.default,
                     window=WINDOW.default, regions=REGIONS.default):
    """The goal choice of a registered strategy for `n_rows` agents.

    Args:
      strategy: a name in `STRATEGIES`.
      grid: a `RegionGrid`.
      n_rows: agents (>= 1).
      measure, epsilon, window: the progress's (see `RegionProgress`).
      regions: one of `REGION_KINDS`.

    Returns:
      The rows' goal choice, or None (random motor babbling).

    Raises:
      ValueError: for a strategy or regions not registered.
    """
    strategy = STRATEGY.check(strategy, "strategy")
    regions = REGIONS.check(regions, "regions")
    return STRATEGIES[strategy].make(grid, n_rows, measure, epsilon, window, regions)
