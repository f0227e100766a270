"""Sensorimotor models for goal babbling: from an outcome the agent wants to the
movement it tries, learned from the (movement, outcome) pairs it has seen.

In explauto's terms (Moulin-Frier, Rouanet and Oudeyer 2014) these are inverse
models. Two, each for many agents at once (rows, one per seed), each row seeing only
its own experience:

- `NearestNeighbourInverse`: the movement whose outcome lies nearest the goal
  (explauto's "nearest_neighbor");
- `LocallyWeightedInverse`: from that movement, one step along a locally weighted
  linear regression (LWLR) of outcomes on movements fitted around it (explauto's
  LWLR forward model, inverted by one damped Gauss-Newton step rather than by its
  L-BFGS-B optimisation).

Both add exploration noise to explore around what they know (`explore`). The paper
gives none of these settings: its actions are scripted.
"""

import numpy as np

from icm import _exact, _validate
from icm._settings import Setting

EXPLORATION_NOISE = Setting(
    default=0.05, label="the inverse model's noise far from a goal, a share of each "
    "joint's range", kind="real", low=0.0, high=1.0, low_open=True,
    source="the paper has no goal babbling: Forestier, Mollard and Oudeyer's 0.05 "
           "(about 5 to 8 degrees)")
"""Standard deviation of the exploration noise, as a share of each joint's range,
while the nearest outcome is `NOISE_DISTANCE` or more from the goal."""
DEFAULT_EXPLORATION_NOISE = EXPLORATION_NOISE.default
NOISE_DISTANCE = 0.05
"""Below this distance (in outcome units: m) between the goal and the nearest outcome,
the noise shrinks in proportion: local exploration gets finer as the goal gets closer,
as in SAGG-RIAC's low-level exploration. Our choice, not the paper's."""
DEFAULT_NEIGHBOURS = 12
"""LWLR: the movements nearest the starting one (in joint space) that the local
linear model is fitted on (explauto's LWLR uses 10; 12 is the 7 joints plus an
intercept, with a few to spare). Not in the paper."""
DEFAULT_KERNEL_WIDTH = 0.1
"""LWLR: width of the Gaussian weights over joint-space distance, each joint measured
as a share of its range (explauto's sigma, 0.1). Not in the paper."""
DEFAULT_MAX_STEP = 0.1
"""LWLR: the largest change of any joint the linear step may make, as a share of its
range: the linear model is trusted only near where it was fitted. Our choice."""
INVERSE_MODELS = ("nearest_neighbour", "lwlr")
"""The inverse models, by name (see `make_inverse_model`)."""
INVERSE_MODEL = Setting(
    default="nearest_neighbour", label="the inverse model: nearest neighbour, or a "
    "locally weighted linear step", kind="choice", choices=INVERSE_MODELS,
    source="the paper has no goal babbling: explauto's two inverse models")
"""Which inverse model (`INVERSE_MODELS`)."""


class NearestNeighbourInverse:
    """explauto's nearest-neighbour inverse model, for many agents (rows) at once.

    Each row keeps every (movement, outcome) it has seen. For a goal, `infer` returns
    the movement whose outcome lies nearest the goal (Euclidean distance; the first
    seen among equals); `explore` adds Gaussian noise to each joint: standard
    deviation `exploration_noise` times the joint's range, times min(1, distance
    from that outcome to the goal / `noise_distance`), clipped to the joint ranges.

    Args:
      n_rows: agents.
      capacity: the most pairs a row will see (the arrays are allocated once).
      lower, upper: the joints' ranges, arrays [n_joints].
      n_outcome: the dimension of an outcome.
      exploration_noise: the noise far from the goal, a share of each joint's range,
        in (0, 1].
      noise_distance: the distance below which the noise shrinks, > 0.
    """

    def __init__(self, n_rows, capacity, lower, upper, n_outcome,
                 exploration_noise=DEFAULT_EXPLORATION_NOISE, noise_distance=NOISE_DISTANCE):
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        capacity = _validate.integer_at_least("capacity", capacity, 1)
        self.lower = _validate.finite_array("lower", lower, ndim=1)
        self.upper = _validate.finite_array("upper", upper, shape=self.lower.shape)
        if np.any(self.upper <= self.lower):
            raise ValueError(f"upper must exceed lower in every joint, got lower "
                             f"{_validate.show(self.lower)} and upper {_validate.show(self.upper)}")
        n_outcome = _validate.integer_at_least("n_outcome", n_outcome, 1)
        self.exploration_noise = EXPLORATION_NOISE.check(exploration_noise,
                                                         "exploration_noise")
        self.noise_distance = _validate.positive("noise_distance", noise_distance)
        self.span = self.upper - self.lower
        self.movements = np.zeros((self.n_rows, capacity, len(self.lower)))
        self.outcomes = np.zeros((self.n_rows, capacity, n_outcome))
        self.size = 0

    def update(self, movements, outcomes):
        """Remembers one (movement, outcome) pair per row: `movements` [rows, joints],
        `outcomes` [rows, n_outcome]."""
        if self.size == self.movements.shape[1]:
            raise ValueError(f"the model is full: it was made for {self.size} pairs a row")
        self.movements[:, self.size] = _validate.finite_array(
            "movements", movements, shape=self.movements.shape[::2])
        self.outcomes[:, self.size] = _validate.finite_array(
            "outcomes", outcomes, shape=self.outcomes.shape[::2])
        self.size += 1

    def nearest(self, goals):
        """The pair whose outcome lies nearest each row's goal: (index [rows], distance
        [rows])."""
        if self.size == 0:
            raise ValueError("the model has seen no movement yet")
        goals = _validate.finite_array("goals", goals, shape=self.outcomes.shape[::2])
        squared = ((self.outcomes[:, :self.size] - goals[:, None, :]) ** 2).sum(axis=2)
        index = np.argmin(squared, axis=1)
        return index, np.sqrt(np.take_along_axis(squared, index[:, None], axis=1)[:, 0])

    def infer(self, goals):
        """The movement each row's model gives for its goal, without exploration noise,
        [rows, joints]."""
        index, _ = self.nearest(goals)
        return self._from_nearest(np.asarray(goals, dtype=float), index)

    def _from_nearest(self, goals, index):
        return self.movements[np.arange(self.n_rows), index]

    def explore(self, goals, generators):
        """The movements to try for `goals` [rows, n_outcome]: `infer`'s plus
        exploration noise, each row drawing 7 normal numbers from its own generator
        (`generators[k]`), clipped to the joint ranges."""
        generators = list(generators)
        if len(generators) != self.n_rows:
            raise ValueError(f"generators must be one per row ({self.n_rows}), got "
                             f"{len(generators)}")
        index, distance = self.nearest(goals)
        movements = self._from_nearest(np.asarray(goals, dtype=float), index)
        scale = np.minimum(1.0, distance / self.noise_distance)
        noise = self.exploration_noise * self.span
        out = np.empty_like(movements)
        for k, rng in enumerate(generators):
            out[k] = movements[k] + rng.normal(0.0, noise) * scale[k]
        return np.clip(out, self.lower, self.upper)


class LocallyWeightedInverse(NearestNeighbourInverse):
    """An inverse model by locally weighted linear regression (LWLR), for many agents.

    For a goal y*, start from the nearest-neighbour answer m0 (whose outcome is
    nearest y*). Fit an affine model y = b + A m on the `neighbours` movements
    nearest m0 (joints measured as shares of their ranges), each weighted by
    exp(-d^2 / (2 `kernel_width`^2)) of its distance d to m0: explauto's LWLR
    forward model. Then take one damped Gauss-Newton step towards the goal,
    m = m0 + (A'A + lambda I)^-1 A' (y* - (b + A m0)), no joint moving more than
    `max_step` of its range, clipped to the ranges. explauto inverts its LWLR by
    L-BFGS-B (up to 50 evaluations, the model refitted at each); one step costs one
    fit per goal.

    Args:
      n_rows, capacity, lower, upper, n_outcome, exploration_noise, noise_distance:
        as `NearestNeighbourInverse`.
      neighbours: movements in the local fit (>= 2).
      kernel_width: width of the weights, a share of the joints' ranges, > 0.
      max_step: the largest change of a joint in the step, a share of its range, > 0.
    """

    DAMPING = 1e-4
    """lambda of the step, in the fit's units (joints as shares of their ranges): it
    keeps the step finite along directions the neighbours do not span."""

    def __init__(self, n_rows, capacity, lower, upper, n_outcome,
                 exploration_noise=DEFAULT_EXPLORATION_NOISE, noise_distance=NOISE_DISTANCE,
                 neighbours=DEFAULT_NEIGHBOURS, kernel_width=DEFAULT_KERNEL_WIDTH,
                 max_step=DEFAULT_MAX_STEP):
        super().__init__(n_rows, capacity, lower, upper, n_outcome, exploration_noise,
                         noise_distance)
        self.neighbours = _validate.integer_at_least("neighbours", neighbours, 2)
        self.kernel_width = _validate.positive("kernel_width", kernel_width)
        self.max_step = _validate.positive("max_step", max_step)

    def _from_nearest(self, goals, index):
        rows = np.arange(self.n_rows)
        start = self.movements[rows, index]
        if self.size < self.neighbours:
            return start
        z = (self.movements[:, :self.size] - start[:, None, :]) / self.span  # [rows, n, j]
        squared = (z ** 2).sum(axis=2)
        near = np.argpartition(squared, self.neighbours - 1, axis=1)[:, :self.neighbours]
        # _exact's exp, products and solve, not NumPy's: theirs round differently on
        # different processors, and a run must be the same on every machine.
        weights = _exact.exp(-np.take_along_axis(squared, near, axis=1)
                             / (2.0 * self.kernel_width ** 2))
        x = np.take_along_axis(z, near[:, :, None], axis=1)  # [rows, k, j]
        x = np.concatenate([np.ones(x.shape[:2] + (1,)), x], axis=2)
        y = np.take_along_axis(self.outcomes[:, :self.size], near[:, :, None], axis=1)
        root = np.sqrt(weights)[:, :, None]
        wx, wy = x * root, y * root
        gram = _exact.matmul(wx.transpose(0, 2, 1), wx) + self.DAMPING * np.eye(x.shape[2])
        # beta [rows, 1 + j, outcome]: the intercept, then dy/dz for each joint
        beta = _exact.solve(gram, _exact.matmul(wx.transpose(0, 2, 1), wy))
        jacobian = beta[:, 1:, :].transpose(0, 2, 1)  # [rows, outcome, j]: dy/dz
        residual = goals - beta[:, 0, :]  # at z = 0, the start
        normal = (_exact.matmul(jacobian.transpose(0, 2, 1), jacobian)
                  + self.DAMPING * np.eye(z.shape[2]))
        step = _exact.solve(normal, _exact.matmul(jacobian.transpose(0, 2, 1),
                                                  residual[:, :, None]))[:, :, 0]
        largest = np.abs(step).max(axis=1, keepdims=True)
        step *= np.minimum(1.0, self.max_step / np.maximum(largest, 1e-300))
        return np.clip(start + step * self.span, self.lower, self.upper)


def make_inverse_model(kind, n_rows, capacity, lower, upper, n_outcome, **settings):
    """An inverse model by name (`INVERSE_MODELS`): "nearest_neighbour" or "lwlr";
    `settings` are its keyword arguments."""
    kind = INVERSE_MODEL.check(kind, "inverse_model")
    cls = NearestNeighbourInverse if kind == "nearest_neighbour" else LocallyWeightedInverse
    return cls(n_rows, capacity, lower, upper, n_outcome, **settings)
