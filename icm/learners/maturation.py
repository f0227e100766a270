"""Maturational constraints for goal babbling: the arm's reachable joint range grows
from around its resting posture to the full range, released by a clock that the
learner's own competence drives, for many agents (rows) at once.

After Baranes and Oudeyer's McSAGG-RIAC (2010), in which a maturational clock, driven
by the learner's competence progress, gradually releases constraints on the body
(joint ranges, noise, resolution of perception). We keep one of them, the joint
range, because it is a constraint of the body and not of the learner (the exploration
noise is the learner's own setting, chosen in the chapter "Forming actions"), and
because it changes where the hand can go, which is what goal babbling explores.
The clock's rule below is ours: the paper has no maturation.
"""

import numpy as np

from icm import _validate
from icm.learners.goal_choice import competence_progress

MATURATIONS = ("none", "joint_range")
"""The maturational constraints a run may have: "none", or "joint_range"
(`JointRangeMaturation`)."""
DEFAULT_MATURATION = "none"
"""A run grows up only when asked."""
DEFAULT_START = 0.5
"""The clock's value at birth: the share of the way from the resting posture to each
joint's limits that the arm can reach (0: only the rest, 1: the full range). Our
choice: about the smallest share from which some random movements touch the console
(`icm.experiments.goal_babbling.touch_shares` measures it)."""
DEFAULT_WINDOW = 40
"""The learner's last goals (all regions together) over which its competence progress
is measured. Our choice: over fewer goals, the progress mostly measures how far apart
successive goals are."""
DEFAULT_PLATEAU = 0.01
"""Competence progress (m, in the outcome space) below which the learner counts as
no longer progressing within its present body, and the clock advances. Our choice."""
DEFAULT_STEP = 0.01
"""How much the clock advances after each goal met on a plateau. Our choice: from
`DEFAULT_START`, the full range after 50 such goals."""


class JointRangeMaturation:
    """A reachable joint range that grows as competence stops progressing, for many
    agents (rows) at once.

    Each row has a clock psi, from `start` up to 1. Its arm may reach, in joint j,
    [home_j - psi (home_j - lower_j), home_j + psi (upper_j - home_j)]: around the
    resting posture at first, the full range at psi = 1. After each goal, `update`
    records the distance between the goal and what the movement reached; once the
    row has `window` of them, its competence progress over the last `window`
    (SAGG-RIAC's, as `icm.learners.goal_choice.competence_progress` measures it:
    abs(mean of the newer half - mean of the older half) of minus the distances) is
    compared with `plateau`: below it, the clock advances by `step`. A learner that
    still progresses within its body keeps it; one that no longer does grows.

    Args:
      n_rows: agents.
      home: the resting posture, an array [joints], within the ranges.
      lower, upper: the full joint ranges, arrays [joints].
      start: the clock at birth, in (0, 1].
      window: goals in the competence progress (>= 2).
      plateau: the progress below which the clock advances (m, >= 0).
      step: how far it advances then, in (0, 1].
    """

    def __init__(self, n_rows, home, lower, upper, start=DEFAULT_START,
                 window=DEFAULT_WINDOW, plateau=DEFAULT_PLATEAU, step=DEFAULT_STEP):
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.lower = _validate.finite_array("lower", lower, ndim=1)
        self.upper = _validate.finite_array("upper", upper, shape=self.lower.shape)
        self.home = _validate.finite_array("home", home, shape=self.lower.shape)
        if np.any(self.upper <= self.lower):
            raise ValueError(f"upper must exceed lower in every joint, got lower "
                             f"{_validate.show(self.lower)} and upper {_validate.show(self.upper)}")
        if np.any((self.home < self.lower) | (self.home > self.upper)):
            raise ValueError(f"home must lie within the joint ranges, got "
                             f"{_validate.show(self.home)}")
        self.start = _validate.real("start", start, 0.0, 1.0, low_open=True)
        self.window = _validate.integer_at_least("window", window, 2)
        self.plateau = _validate.non_negative("plateau", plateau)
        self.step = _validate.real("step", step, 0.0, 1.0, low_open=True)
        self.psi = np.full(self.n_rows, self.start)
        self._competence = np.zeros((self.n_rows, self.window))  # newest last
        self._count = 0

    def bounds(self):
        """Each row's reachable range now: (lower [rows, joints], upper [rows, joints])."""
        psi = self.psi[:, None]
        return (self.home - psi * (self.home - self.lower),
                self.home + psi * (self.upper - self.home))

    def clip(self, movements):
        """`movements` [rows, joints] clipped to each row's reachable range."""
        lower, upper = self.bounds()
        return np.clip(movements, lower, upper)

    def progress(self):
        """Each row's competence progress over its last `window` goals, [rows] (0 before
        it has two)."""
        count = np.full(self.n_rows, self._count)
        return competence_progress(self._competence, count)

    def update(self, distances):
        """Records the distance between each row's goal and what its movement reached,
        [rows] (m, >= 0), and advances the clock of the rows on a plateau."""
        distances = _validate.finite_array("distances", distances, shape=(self.n_rows,))
        if np.any(distances < 0):
            raise ValueError(f"distances must be >= 0, got {_validate.show(distances)}")
        self._competence = np.concatenate([self._competence[:, 1:], -distances[:, None]],
                                          axis=1)
        self._count += 1
        if self._count >= self.window:
            on_plateau = self.progress() < self.plateau
            self.psi = np.where(on_plateau, np.minimum(1.0, self.psi + self.step), self.psi)
