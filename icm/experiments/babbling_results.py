"""What a goal-babbling run measured (`GoalBabblingResult`) and its readings (see
`icm.experiments.goal_babbling`)."""

import dataclasses

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.experiments.babbling_space import COLUMN_NAMES, REGION_GRID, region_columns
from icm.stats import PANEL_RESAMPLES, bootstrap_band

@dataclasses.dataclass(frozen=True)
class GoalBabblingResult:
    """What `run_goal_babbling` measured. Rollouts are counted from 1 in
    `checkpoints`; the rollout axis of the arrays holds rollout 1 at index 0.

    Attributes:
      settings: the arguments of the run, as a dict.
      checkpoints: [checkpoint], the rollouts done at each checkpoint (>= 1).
      test_goals: [goal, 3], the fixed test goals (m): the five press goals, then
        points on the console's top (`console_geometry`).
      test_error: [seed, checkpoint], the mean distance, in the run's outcome space,
        between the test goals and the nearest outcomes reached so far (what the
        inverse model reaches for them with no exploration noise: the nearest
        outcome's movement, which the deterministic physics reproduces exactly).
      buttons_pressed: [seed, button], whether the learned movement for the button
        (the one whose outcome lies nearest its press goal) presses it, and only it,
        in a trial on the physics console where it is lit red, and opens the red box
        only.
      press_movements: [seed, button, 7], those learned movements (joint targets).
      press_outcomes: [seed, button, 3], where each of them brought the finger.
      movements: [seed, rollout, 7], the joint targets of every rollout.
      outcomes: [seed, rollout, 3], where each rollout brought the finger's lowest
        point at the end of its hold (m).
      depths: [seed, rollout, 5], how far each cap went down during the rollout's
        reach and hold (and return home, with `retract`) (m).
      touched: [seed, rollout], whether the finger then touched the console.
      pressed: [seed, rollout], the first button pushed past the press depth in the
        rollout, -1 for none.
      goals: [seed, rollout, 3], the goal of each rollout (NaN for random motor
        commands).
      regions: [seed, rollout], the region of each goal (-1 for none).
      interest: [seed, rollout, region], the interest (progress) of each region
        after each rollout (learning_progress only; zeros otherwise).
      maturity: [seed, rollout], the maturational clock after each rollout: the share
        of the way from the resting posture to the joints' limits that the arm could
        reach (1 throughout without maturation).

    The first `n_demonstrations` rollouts are the teacher's demonstrations
    (`settings["demonstrations"]`, the buttons shown, in order), the same in every
    seed.
    """

    settings: dict
    checkpoints: np.ndarray
    test_goals: np.ndarray
    test_error: np.ndarray
    buttons_pressed: np.ndarray
    press_movements: np.ndarray
    press_outcomes: np.ndarray
    movements: np.ndarray
    outcomes: np.ndarray
    depths: np.ndarray
    touched: np.ndarray
    pressed: np.ndarray
    goals: np.ndarray
    regions: np.ndarray
    interest: np.ndarray
    maturity: np.ndarray

    @property
    def n_seeds(self):
        return self.test_error.shape[0]

    @property
    def n_rollouts(self):
        return self.outcomes.shape[1]

    @property
    def strategy(self):
        return self.settings["strategy"]

    @property
    def n_demonstrations(self):
        """The teacher's demonstrations at the start of the run (0 without a teacher)."""
        return len(self.settings.get("demonstrations", ()))

    def first_presses(self):
        """The robot's first own press of each button: [seed, button], the rollout
        (counted from 1, demonstrations included in the count) of the first rollout
        that is not a demonstration in which that button, and no other, went down
        past the press depth (`buttons.PRESS_DEPTH`); -1 where none did."""
        over = self.depths > buttons.PRESS_DEPTH  # [seed, rollout, button]
        clean = over & (over.sum(axis=2, keepdims=True) == 1)
        clean[:, :self.n_demonstrations] = False
        return np.where(clean.any(axis=1), clean.argmax(axis=1) + 1, -1)

    def median_first_presses(self):
        """The median over seeds of `first_presses`, [button] (`median_first_press`)."""
        return median_first_press(self.first_presses(), self.n_rollouts)

    def final_test_error(self):
        """The test error at the end of each seed's run, [seed] (m)."""
        return self.test_error[:, -1].copy()

    def summary(self):
        """The numbers the book quotes, as a dict: the final test error (mean over
        seeds and its 95% band, in m), the buttons pressed (mean number of the 5,
        and the share of seeds that press all 5), the share of rollouts that touched
        the console and that pressed a button."""
        mean, low, high = bootstrap_band(self.final_test_error()[:, None],
                                         resamples=PANEL_RESAMPLES)
        return {"test_error": float(mean[0]), "test_error_low": float(low[0]),
                "test_error_high": float(high[0]),
                "buttons_pressed": float(self.buttons_pressed.sum(axis=1).mean()),
                "all_pressed_share": float(self.buttons_pressed.all(axis=1).mean()),
                "touched_share": float(self.touched.mean()),
                "press_share": float((self.pressed >= 0).mean())}

    def seed_summaries(self):
        """One dict per seed: its final test error (m), the number of buttons its
        learned movements press, and its share of rollouts that pressed a button."""
        return [{"test_error": float(error), "buttons_pressed": int(pressed.sum()),
                 "press_share": float((presses >= 0).mean())}
                for error, pressed, presses in zip(self.final_test_error(),
                                                   self.buttons_pressed, self.pressed)]

    def goal_shares(self, edges):
        """The share of goals in each column of regions (along y, `REGION_GRID[1]` of
        them, the robot's right first) between rollout edges, over all seeds:
        [stretch, column]; rollouts without a goal are left out (a stretch with none
        has shares 0).

        Args:
          edges: increasing whole rollout counts from 0 to `n_rollouts`, e.g.
            [0, 100, 200].

        Raises:
          ValueError: for edges that are not whole numbers (an `ArgumentTypeError`
            for bools or text), not increasing, fewer than 2, or outside 0..n_rollouts.
        """
        edges = _validate.integer_array("edges", edges, ndim=1)
        if len(edges) < 2 or np.any(np.diff(edges) <= 0) or edges[0] < 0 \
                or edges[-1] > self.n_rollouts:
            raise ValueError(f"edges must be at least 2 increasing rollout counts in 0.."
                             f"{self.n_rollouts}, got {_validate.show(edges)}")
        columns = region_columns()
        shares = np.zeros((len(edges) - 1, REGION_GRID[1]))
        for i, (start, stop) in enumerate(zip(edges[:-1], edges[1:])):
            regions = self.regions[:, start:stop]
            chosen = regions[regions >= 0]
            if len(chosen):
                shares[i] = np.bincount(columns[chosen], minlength=REGION_GRID[1]) / len(chosen)
        return shares

    def interest_peaks(self):
        """The rollout (counted from 1) at which the mean interest of each column of
        regions peaks, as a dict {column name: rollout} (`COLUMN_NAMES`; 0 for a
        column never interesting)."""
        interest = self.column_interest()
        return {name: int(np.argmax(interest[:, c]) + 1) if interest[:, c].any() else 0
                for c, name in enumerate(COLUMN_NAMES)}

    def column_interest(self):
        """The interest of each column of regions (summed over its regions) after each
        rollout, mean over seeds: [rollout, column], the robot's right first."""
        columns = region_columns()
        out = np.zeros((self.n_rollouts, REGION_GRID[1]))
        mean = self.interest.mean(axis=0)
        for column in range(REGION_GRID[1]):
            out[:, column] = mean[:, columns == column].sum(axis=1)
        return out


def median_first_press(first, n_rollouts):
    """The median over seeds (the first axis) of first-press rollouts `first` [seed,
    ...] (from 1, -1 for never), a seed that never pressed counted as pressing after
    all `n_rollouts`: a float array [...], NaN where more than half never pressed."""
    first = np.asarray(first)
    never = n_rollouts + 1
    median = np.median(np.where(first < 0, never, first), axis=0)
    return np.where(median >= never, np.nan, median)


