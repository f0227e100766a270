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
from icm._settings import Setting, Settings, setting, settings_class
from icm.learners.goal_choice import competence_progress

MATURATIONS = ("none", "joint_range")
"""The maturational constraints a run may have: "none", or "joint_range"
(`JointRangeMaturation`)."""
MATURATION = Setting(
    default="none", label="grow up: the arm's reachable joint range grows from around "
    "its resting posture as its competence stops progressing", kind="choice",
    choices=MATURATIONS,
    source="the paper has no maturation: McSAGG's maturational clock (Baranes and "
           "Oudeyer 2011), on the joints' range; a run grows up only when asked")
"""Which maturational constraint a run has (`MATURATIONS`)."""
DEFAULT_MATURATION = MATURATION.default


@settings_class
class MaturationSettings(Settings):
    """The maturational clock's settings (`JointRangeMaturation`): where it starts, the
    goals its progress is measured over, the plateau below which it advances and by
    how much. Each is a `icm._settings.Setting` (see `MaturationSettings.specs()`)."""

    start: float = setting(
        default=0.5, label="the clock at birth: the share of the way from the resting "
        "posture to each joint's limits the arm can reach", kind="real", low=0.0, high=1.0,
        low_open=True, per_row=False,
        source="our choice: about the smallest share from which some random movements "
               "touch the console (`icm.experiments.goal_babbling.touch_shares` measures "
               "it)")
    window: int = setting(
        default=40, label="the last goals (all regions together) over which competence "
        "progress is measured", kind="integer", low=2, per_row=False,
        source="our choice: over fewer goals, the progress mostly measures how far apart "
               "successive goals are")
    plateau: float = setting(
        default=0.01, label="competence progress (m) below which the clock advances",
        kind="real", low=0.0, per_row=False,
        source="our choice: below it the learner counts as no longer progressing within "
               "its present body")
    step: float = setting(
        default=0.01, label="how much the clock advances after each goal met on a plateau",
        kind="real", low=0.0, high=1.0, low_open=True, per_row=False,
        source="our choice: from the start, the full range after 50 such goals")


DEFAULT_START = MaturationSettings.spec("start").default
DEFAULT_WINDOW = MaturationSettings.spec("window").default
DEFAULT_PLATEAU = MaturationSettings.spec("plateau").default
DEFAULT_STEP = MaturationSettings.spec("step").default


def reachable_range(home, lower, upper, share):
    """The joint range an arm grown to `share` of its range reaches around its resting
    posture: (home - share (home - lower), home + share (upper - home)). `share` is a
    number in (0, 1] or an array that broadcasts against the joints (one per row)."""
    return home - share * (home - lower), home + share * (upper - home)


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
        specs = MaturationSettings.specs()
        self.start = specs["start"].check(start, "start")
        self.window = specs["window"].check(window, "window")
        self.plateau = specs["plateau"].check(plateau, "plateau")
        self.step = specs["step"].check(step, "step")
        self.psi = np.full(self.n_rows, self.start)
        self._competence = np.zeros((self.n_rows, self.window))  # newest last
        self._count = 0

    @classmethod
    def from_settings(cls, n_rows, home, lower, upper, settings=None):
        """The clock of `settings` (a `MaturationSettings`; default the library's).

        Args:
          n_rows, home, lower, upper: as the constructor's.
          settings: a `MaturationSettings`, or None.

        Returns:
          A `JointRangeMaturation`.
        """
        settings = MaturationSettings() if settings is None else _validate.instance(
            "settings", settings, MaturationSettings)
        return cls(n_rows, home, lower, upper, **settings.as_dict())

    def bounds(self):
        """Each row's reachable range now: (lower [rows, joints], upper [rows, joints])."""
        return reachable_range(self.home, self.lower, self.upper, self.psi[:, None])

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
