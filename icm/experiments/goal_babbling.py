"""Forming actions: the simulated iCub learns to press the buttons itself, by goal
babbling (Rolf, Steil and Gienger 2010) with goals chosen by learning progress
(SAGG-RIAC, Baranes and Oudeyer 2013; IMGEP, Forestier, Mollard and Oudeyer 2017).

The experiment: the environment is `icm.envs.buttons.movements.MovementLab` (a
movement is the arm's 7 final joint targets, rolled out in physics), the agent
`icm.learners.goal_babbling.GoalBabblingAgent`, built from an inverse model
(`icm.learners.sensorimotor`) and a goal choice (`icm.learners.goal_choice`). Three
strategies spend the same budget of rollouts:

- "random_motor": uniform random joint targets within the joint ranges;
- "random_goal": uniform random goals in the goal space, through the inverse model;
- "learning_progress": goals in regions chosen by their progress.

Two remedies that the paper's discussion names can be added to any of them: a body
that grows (`maturation`, after Baranes and Oudeyer 2010: `icm.learners.maturation`)
and a teacher who shows the scripted presses of some buttons first (`demonstrations`,
after Thomaz 2006 and Nguyen and Oudeyer's socially guided intrinsic motivation).

A movement's outcome (`OUTCOME_SPACES`) is where it brought the finger (the lowest
point of the finger at the end of the hold) and, by default, how far each cap went
down. All seeds run at once: rollout k of every seed is stepped in one call of
`mujoco.rollout`, and seed k of a batch is seed k run alone.
"""

import dataclasses
import functools

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.envs.buttons import movements as _movements
from icm.envs.buttons.movements import (  # noqa: F401 (re-exported)
    HOLD_TIME, REACH_TIME, RETRACT_TIME, MovementLab)
from icm.experiments import goal_oriented as _goal_oriented
from icm.experiments._progress import progress_bar
from icm.experiments.results import check_results
from icm.experiments._seeding import check_run_size, run_seeds
from icm.learners import goal_oriented
from icm.learners.goal_babbling import (  # noqa: F401 (N_BOOTSTRAP re-exported)
    N_BOOTSTRAP, GoalBabblingAgent)
from icm.learners.goal_choice import (  # noqa: F401 (re-exported)
    DEFAULT_EPSILON, DEFAULT_WINDOW, MEASURES, RandomGoals, RegionGrid, RegionProgress,
    SplittingRegionProgress)
from icm.learners.maturation import (  # noqa: F401 (re-exported)
    DEFAULT_MATURATION, MATURATIONS, JointRangeMaturation)
from icm.learners.sensorimotor import (  # noqa: F401 (re-exported)
    DEFAULT_EXPLORATION_NOISE, INVERSE_MODELS, NOISE_DISTANCE, make_inverse_model)
from icm.stats import PANEL_RESAMPLES, bootstrap_band, comes_first

STRATEGIES = ("random_motor", "random_goal", "learning_progress")
"""How the next movement is chosen (see the module docstring)."""
DEFAULT_N_ROLLOUTS = 1000
"""Rollouts per run (our choice: the paper has no goal babbling). What the strategies
reach with it is measured in the chapter "Forming actions"."""
OUTCOME_SPACES = ("point", "point_and_depths")
"""What a movement's outcome is: "point", where it brought the finger (3 numbers, m);
"point_and_depths", that and how far each of the five caps went down (5 more, each
times `DEPTH_WEIGHT`)."""
DEFAULT_OUTCOME_SPACE = "point_and_depths"
"""The outcome space of a run unless told otherwise: with the depths, since where the
finger stopped does not tell a press from a touch (a press at a cap's edge lies
farther from the press goal than an untouched cap's top at its centre) nor a clean
press from one that also pushes a neighbour; the chapter measures both."""
DEPTH_WEIGHT = 2.0
"""How much a cap's depth counts in the outcome space "point_and_depths", against the
finger's position: a cap pushed all the way in (1.5 cm) counts as 3 cm. Our choice
(the chapter shows 1, 2 and 3)."""
MAX_DEPTH_WEIGHT = 100.0
"""The largest `depth_weight` a run takes."""
GOAL_LOW = np.array([0.22, -0.375, 0.45])
"""Lower corner of the goal space (m, world frame): the console (x 0.28 to 0.38, y
-0.315 to 0.055, top at 0.485), the table around it (top at 0.45) and the air above."""
GOAL_HIGH = np.array([0.44, 0.115, 0.60])
"""Upper corner of the goal space (m)."""
REGION_GRID = (1, 7, 2)
"""Fixed regions of the goal space for learning progress: cells along x, y and z. The
7 columns along y are 7 cm wide, the buttons' spacing, centred on the five buttons
and one beyond each end; the 2 layers split at z = 0.525 m, 1 cm above the caps: at
the console, and in the air."""
N_CHECKPOINTS = 20
"""Checkpoints of the test error, evenly spread over a run."""
REGION_KINDS = ("fixed", "splitting")
"""Learning progress's regions: the fixed `REGION_GRID`, or regions that split as goals
accumulate (`icm.learners.goal_choice.SplittingRegionProgress`)."""
DEFAULT_INVERSE_MODEL = "nearest_neighbour"
"""The inverse model of a run unless told otherwise (`INVERSE_MODELS`)."""
DEFAULT_MEASURE = "learning_progress"
"""How learning progress measures a region's progress unless told otherwise
(`MEASURES`)."""
DEFAULT_REGIONS = "fixed"
"""Learning progress's regions unless told otherwise (`REGION_KINDS`)."""
DEFAULT_TRIALS = 30
"""Trials of the goal-oriented learner on the formed actions (`run_formed_actions`)."""


def _grid():
    return RegionGrid(GOAL_LOW, GOAL_HIGH, REGION_GRID)


def region_bounds():
    """The fixed regions' corners, [region, 2, 3] (low, high), numbered x-major as
    `region_of` numbers them."""
    return _grid().bounds()


def region_of(points):
    """The region of each point [..., 3] (points outside the goal space fall in the
    nearest region), an int array [...]."""
    return _grid().region_of(points)


@functools.lru_cache(maxsize=1)
def _geometry():
    geometry = _movements.console_geometry()
    caps, top = geometry["caps"], geometry["console_top"]
    # The console's top between and beside the caps: a row in front of them and one
    # behind (4 cm from their centres), at the midpoints between neighbours and one
    # spacing out from the end buttons (1 cm inside the console's edge); and the
    # midpoints along the caps' own row.
    console = geometry["console_centre"]
    ys = caps[:, 1]
    spacing = abs(ys[1] - ys[0])
    between = (ys[:-1] + ys[1:]) / 2
    row = np.concatenate([[ys[0] + spacing / 2], between, [ys[-1] - spacing / 2]])
    grid = [(console[0] + dx, y, top) for dx in (-0.04, 0.04) for y in row]
    grid += [(console[0], y, top) for y in between]
    press = geometry["pressed_in"]
    return {**geometry, "press_goals": press, "test_goals": np.concatenate([press, grid])}


def console_geometry():
    """The console as the model builds it, for goals and figures: the dict of
    `icm.envs.buttons.movements.console_geometry` plus "press_goals" [5, 3] (each
    cap's top centre pushed all the way in) and "test_goals" [21, 3] (the five press
    goals, then 16 points on the console's top between and beside the caps)."""
    return {key: value.copy() if isinstance(value, np.ndarray) else value
            for key, value in _geometry().items()}


def goal_depths(points):
    """The caps' depths a goal asks for, [..., 5] (m): a finger alone at each point
    [..., 3]. The cap under the point (within a cap's radius of its centre) is
    pushed down to it, clipped to the button's travel; every other cap stays up."""
    points = np.asarray(points, dtype=float)
    geometry = _geometry()
    caps = geometry["caps"]
    across = np.linalg.norm(points[..., None, :2] - caps[:, :2], axis=-1)
    down = np.clip(geometry["cap_top"] - points[..., 2:3], 0.0, geometry["travel"])
    return np.where(across <= geometry["cap_radius"], down, 0.0)


def outcome_vectors(points, depths, outcome_space, depth_weight=DEPTH_WEIGHT):
    """Outcomes in `outcome_space` (`OUTCOME_SPACES`) from where the finger went
    [..., 3] and how far each cap went down [..., 5], the depths times
    `depth_weight`."""
    if outcome_space == "point":
        return np.asarray(points, dtype=float)
    return np.concatenate([points, depth_weight * np.asarray(depths)], axis=-1)


def goal_outcomes(points, outcome_space, depth_weight=DEPTH_WEIGHT):
    """The outcomes goals at `points` [..., 3] ask for, in `outcome_space`: the point,
    and in "point_and_depths" the depths of `goal_depths` (times `depth_weight`)."""
    return outcome_vectors(points, goal_depths(points), outcome_space, depth_weight)


EDGE_SHARE = 0.8
"""How far from a cap's centre towards its edge the press of `press_distances` is, as
a share of the cap's radius."""


def press_distances(button=buttons.DEFAULT_RED_BUTTON):
    """How far three outcomes lie from a button's press goal in each outcome space:
    {outcome space: {"touch at the centre": ..., "press at the edge": ..., "press and
    neighbour": ...}} (m). The touch: the finger on the cap's top above its centre,
    the cap up. The press at the edge: the cap all the way in, the finger
    `EDGE_SHARE` of the way to its edge. The press and neighbour: the finger on the
    cap's centre, the cap and its neighbour (the next button, or the previous one for
    the last) all the way in.

    Args:
      button: the button (0-4).
    """
    button = _validate.integer("button", button, 0, buttons.N_BUTTONS - 1)
    geometry = _geometry()
    goal, travel = geometry["press_goals"][button], geometry["travel"]
    neighbour = button + 1 if button + 1 < buttons.N_BUTTONS else button - 1
    press = travel * np.eye(buttons.N_BUTTONS)[button]
    cases = {"touch at the centre": (goal + [0.0, 0.0, travel], np.zeros(buttons.N_BUTTONS)),
             "press at the edge": (goal + [0.0, EDGE_SHARE * geometry["cap_radius"], 0.0],
                                   press),
             "press and neighbour": (goal, press + travel
                                     * np.eye(buttons.N_BUTTONS)[neighbour])}
    return {space: {name: float(np.linalg.norm(outcome_vectors(point, depths, space)
                                               - goal_outcomes(goal, space)))
                    for name, (point, depths) in cases.items()}
            for space in OUTCOME_SPACES}


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
        columns = _region_columns()
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
        columns = _region_columns()
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


COLUMN_NAMES = ("beyond button 4", "button 4", "button 3", "button 2", "button 1",
                "button 0", "beyond button 0")
"""The columns of regions along y (`REGION_GRID[1]` of them), the robot's right first:
one centred on each button and one beyond each end button."""


def _region_columns():
    """The column (index along y) of every region, [region]."""
    return np.array([index[1] for index in np.ndindex(*REGION_GRID)])


def check_demonstrations(demonstrations):
    """`demonstrations` as a tuple of distinct buttons (0 to 4), in the order shown:
    None or an empty sequence for no teacher.

    Raises:
      ValueError: for a button outside 0..4 or shown twice (an `ArgumentTypeError` for
        what is not a sequence of integers).
    """
    if demonstrations is None:
        return ()
    if isinstance(demonstrations, (str, bytes)) or not isinstance(
            demonstrations, (tuple, list, np.ndarray)):
        raise _validate.ArgumentTypeError(
            f"demonstrations must be a tuple of buttons (0 to {buttons.N_BUTTONS - 1}), "
            f"each shown at most once, got {_validate.show(demonstrations)}")
    if len(demonstrations) == 0:
        return ()
    shown = _validate.integer_array("demonstrations", demonstrations, ndim=1)
    if np.any((shown < 0) | (shown >= buttons.N_BUTTONS)) or len(set(shown.tolist())) \
            != len(shown):
        raise ValueError(f"demonstrations must be buttons 0 to {buttons.N_BUTTONS - 1}, "
                         f"each shown at most once, got {_validate.show(demonstrations)}")
    return tuple(int(b) for b in shown)


def _check_run_arguments(strategy, n_seeds, n_rollouts, seed, progress, exploration_noise,
                         epsilon, window, outcome_space, inverse_model, measure, regions,
                         depth_weight, retract, threads, maturation, demonstrations):
    checked = dict(
        strategy=_validate.one_of("strategy", strategy, STRATEGIES),
        n_seeds=_validate.integer_at_least("n_seeds", n_seeds, 1),
        n_rollouts=_validate.integer_at_least("n_rollouts", n_rollouts, 1),
        seed=_validate.root_seed("seed", seed),
        exploration_noise=_validate.real("exploration_noise", exploration_noise, 0.0, 1.0,
                                         low_open=True),
        epsilon=_validate.in_closed_interval("epsilon", epsilon, 0.0, 1.0),
        window=_validate.integer_at_least("window", window, 2),
        outcome_space=_validate.one_of("outcome_space", outcome_space, OUTCOME_SPACES),
        inverse_model=_validate.one_of("inverse_model", inverse_model, INVERSE_MODELS),
        measure=_validate.one_of("measure", measure, MEASURES),
        regions=_validate.one_of("regions", regions, REGION_KINDS),
        depth_weight=_validate.real("depth_weight", depth_weight, 0.0, MAX_DEPTH_WEIGHT,
                                    low_open=True),
        retract=_validate.boolean("retract", retract),
        maturation=_validate.one_of("maturation", maturation, MATURATIONS),
        demonstrations=check_demonstrations(demonstrations))
    if checked["n_rollouts"] < len(checked["demonstrations"]):
        raise ValueError(f"n_rollouts must be at least the number of demonstrations "
                         f"({len(checked['demonstrations'])}), got {checked['n_rollouts']}")
    _validate.boolean("progress", progress)
    if threads is not None:
        _validate.integer_in_range("threads", threads, 1, _movements.MAX_THREADS)
    n_goals = len(_geometry()["test_goals"])
    # Per rollout: movement, outcome, depths, goal, flags and two distances per test
    # goal; per seed: one rollout's simulated states.
    check_run_size("run_goal_babbling", checked["n_seeds"], checked["n_rollouts"],
                   8 * (7 + 8 + 5 + 3 + 3 + 1 + 2 * n_goals + int(np.prod(REGION_GRID))),
                   bytes_per_seed=150_000)
    return checked


def checkpoints_of(n_rollouts):
    """The rollouts (counted from 1) after which the test error is measured: up to
    `N_CHECKPOINTS` evenly spread, the last at `n_rollouts`, none at 0."""
    n_rollouts = _validate.integer_at_least("n_rollouts", n_rollouts, 1)
    spread = np.linspace(0, n_rollouts, N_CHECKPOINTS + 1)[1:].round().astype(np.int64)
    return np.unique(np.maximum(spread, 1))


def run_goal_babbling(strategy="learning_progress", n_seeds=5, n_rollouts=DEFAULT_N_ROLLOUTS,
                      seed=0, progress=True, exploration_noise=DEFAULT_EXPLORATION_NOISE,
                      epsilon=DEFAULT_EPSILON, window=DEFAULT_WINDOW,
                      outcome_space=DEFAULT_OUTCOME_SPACE, inverse_model=DEFAULT_INVERSE_MODEL,
                      measure=DEFAULT_MEASURE, regions=DEFAULT_REGIONS,
                      depth_weight=DEPTH_WEIGHT, retract=False, threads=None,
                      maturation=DEFAULT_MATURATION, demonstrations=(), first_run=0):
    """Runs goal babbling on the simulated iCub, all seeds at once.

    Every rollout is a movement performed in physics from the start of a trial
    (`mujoco.rollout`, in C). The goal strategies start with `N_BOOTSTRAP` random
    motor commands; then each rollout has a goal, drawn uniformly in the goal space
    ("random_goal") or in a region chosen by its progress ("learning_progress": with
    probability `epsilon` a region drawn uniformly, otherwise one drawn with
    probability proportional to its interest, uniformly while every interest is 0),
    and the inverse model gives a movement for it, plus exploration noise (see
    `icm.learners.sensorimotor`).

    With `maturation="joint_range"` the arm grows up: it reaches a range of joint
    angles around its resting posture that grows as its competence stops progressing
    (`icm.learners.maturation.JointRangeMaturation`, with its defaults). With
    `demonstrations`, a teacher first moves the arm to the scripted press's lowest
    posture of each button listed, one rollout each, counted in `n_rollouts`: the
    movement and what it did enter the inverse model's memory, and the robot then
    babbles as without a teacher (see `icm.learners.goal_babbling`).

    At the end, each seed's movement whose outcome lies nearest each button's press
    goal is run on the physics console, the button lit red.

    Args:
      strategy: one of `STRATEGIES`.
      n_seeds: independent runs (>= 1).
      n_rollouts: movements per run (>= 1).
      seed: the root seed: an integer >= 0, a `numpy.random.Generator` or None; run
        i's seeds depend only on it and i (kept in `settings["seed"]`).
      progress: show a progress bar over the rollouts when the run lasts over a
        second.
      exploration_noise: the noise's standard deviation as a share of each joint's
        range, far from the goal, in (0, 1].
      epsilon: learning progress's share of uniformly drawn regions, in [0, 1].
      window: distances per region in the progress (>= 2).
      outcome_space: one of `OUTCOME_SPACES`.
      inverse_model: one of `icm.learners.sensorimotor.INVERSE_MODELS`.
      measure: how learning progress measures a region's progress, one of
        `icm.learners.goal_choice.MEASURES`.
      regions: learning progress's regions, one of `REGION_KINDS`.
      depth_weight: how much a cap's depth counts in "point_and_depths", in (0,
        `MAX_DEPTH_WEIGHT`].
      retract: also simulate each movement's return home while babbling (the depths
        then cover it too); the outcome is read at the end of the hold either way.
      threads: threads stepping the rollouts, 1 to `movements.MAX_THREADS` (None:
        the cores this process may use). The results do not depend on it.
      maturation: one of `MATURATIONS` ("none" or "joint_range").
      demonstrations: the buttons the teacher shows, in order, each at most once (a
        tuple of integers 0 to 4; empty or None: no teacher).
      first_run: the index of the first run (>= 0): the seeds are runs first_run to
        first_run + n_seeds - 1 of the root seed, so that a large study can be run in
        pieces (run 7 alone is run 7 of any larger batch; kept in
        `settings["first_run"]`).

    Returns:
      A `GoalBabblingResult`.

    Raises:
      ValueError: for any argument outside its allowed range, or a run too large for
        this machine's memory.
    """
    settings = _check_run_arguments(strategy, n_seeds, n_rollouts, seed, progress,
                                    exploration_noise, epsilon, window, outcome_space,
                                    inverse_model, measure, regions, depth_weight,
                                    retract, threads, maturation, demonstrations)
    settings["first_run"] = _validate.integer_at_least("first_run", first_run, 0)
    lab = MovementLab(threads)
    seeds = run_seeds(settings["seed"], n_seeds, 2, first=settings["first_run"])
    arrays = _babble(settings, lab, [s[0] for s in seeds], progress)
    geometry = _geometry()
    outcomes, movements = arrays["outcomes"], arrays["movements"]
    space = settings["outcome_space"]
    checkpoints = checkpoints_of(n_rollouts)
    test_goals = geometry["test_goals"]
    weight = settings["depth_weight"]
    reached = outcome_vectors(outcomes, arrays["depths"], space, weight)
    wanted = goal_outcomes(test_goals, space, weight)
    distance = np.sqrt(((reached[:, :, None, :] - wanted[None, None]) ** 2).sum(axis=3))
    best = np.minimum.accumulate(distance, axis=1)  # [seed, rollout, goal]
    test_error = best[:, checkpoints - 1].mean(axis=2)
    to_press = distance[:, :, :buttons.N_BUTTONS].argmin(axis=1)  # [seed, button]
    press_movements = np.take_along_axis(movements, to_press[:, :, None], axis=1)
    press_outcomes = np.take_along_axis(outcomes, to_press[:, :, None], axis=1)
    buttons_pressed = _press_each_button(lab, press_movements, [s[1] for s in seeds])
    return GoalBabblingResult(settings, checkpoints, test_goals.copy(), test_error,
                              buttons_pressed, press_movements, press_outcomes, movements,
                              outcomes, arrays["depths"], arrays["touched"],
                              arrays["pressed"], arrays["goals"], arrays["regions"],
                              arrays["interest"], arrays["maturity"])


def _babble(settings, lab, seeds, progress):
    """The rollouts of a run, all seeds at once (one generator per seed, from `seeds`):
    a dict of the arrays `GoalBabblingResult` keeps per rollout."""
    strategy, n_rollouts = settings["strategy"], settings["n_rollouts"]
    n_seeds, space = len(seeds), settings["outcome_space"]
    weight, retract = settings["depth_weight"], settings["retract"]
    n_outcome = 3 if space == "point" else 3 + buttons.N_BUTTONS
    grid = _grid()
    model = make_inverse_model(settings["inverse_model"], n_seeds, n_rollouts, lab.lower,
                               lab.upper, n_outcome,
                               exploration_noise=settings["exploration_noise"])
    if strategy == "random_motor":
        choice = None
    elif strategy == "random_goal":
        choice = RandomGoals(grid, n_seeds)
    else:
        kind = RegionProgress if settings["regions"] == "fixed" else SplittingRegionProgress
        choice = kind(grid, n_seeds, settings["measure"], settings["epsilon"],
                      settings["window"])
    maturation = None if settings["maturation"] == "none" else \
        JointRangeMaturation(n_seeds, lab.home, lab.lower, lab.upper)
    shown = lab.press_postures[list(settings["demonstrations"])]
    agent = GoalBabblingAgent(model, choice, [np.random.default_rng(s) for s in seeds],
                              lambda goals: goal_outcomes(goals, space, weight),
                              maturation=maturation, demonstrations=shown)
    movements = np.zeros((n_seeds, n_rollouts, 7))
    outcomes = np.zeros((n_seeds, n_rollouts, 3))
    depths = np.zeros((n_seeds, n_rollouts, buttons.N_BUTTONS))
    touched = np.zeros((n_seeds, n_rollouts), dtype=bool)
    pressed = np.zeros((n_seeds, n_rollouts), dtype=np.int64)
    goals = np.full((n_seeds, n_rollouts, 3), np.nan)
    regions = np.full((n_seeds, n_rollouts), -1, dtype=np.int64)
    interest_log = np.zeros((n_seeds, n_rollouts, grid.n_regions))
    maturity = np.ones((n_seeds, n_rollouts))
    for i in progress_bar(range(n_rollouts), n_rollouts,
                          f"goal babbling ({strategy}, {n_seeds} seeds at once)", progress,
                          unit="rollout"):
        targets, goal, region = agent.produce()
        done = lab.perform(targets, retract)
        agent.perceive(targets, outcome_vectors(done["point"], done["depths"], space, weight))
        movements[:, i], outcomes[:, i], depths[:, i] = targets, done["point"], done["depths"]
        touched[:, i], pressed[:, i] = done["touched"], done["pressed"]
        if goal is not None:
            goals[:, i], regions[:, i] = goal, region
            if strategy == "learning_progress":
                interest_log[:, i] = choice.values()
        if maturation is not None:
            maturity[:, i] = maturation.psi
    return {"movements": movements, "outcomes": outcomes, "depths": depths,
            "touched": touched, "pressed": pressed, "goals": goals, "regions": regions,
            "interest": interest_log, "maturity": maturity}


def presses_formed(result, rollouts):
    """Whether each seed had formed a press for each button after `rollouts` rollouts:
    the movement among its first n rollouts whose outcome lies nearest the button's
    press goal, tested on the physics console as at the end of a run (so that at
    n = `n_rollouts` it is `buttons_pressed`).

    Args:
      result: a `GoalBabblingResult`.
      rollouts: increasing whole rollout counts in 1..n_rollouts.

    Returns:
      A bool array [len(rollouts), seed, button].
    """
    _validate.instance("result", result, GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    rollouts = _validate.integer_array("rollouts", rollouts, ndim=1)
    if not len(rollouts) or np.any(np.diff(rollouts) <= 0) or rollouts[0] < 1 \
            or rollouts[-1] > result.n_rollouts:
        raise ValueError(f"rollouts must be increasing rollout counts in 1.."
                         f"{result.n_rollouts}, got {_validate.show(rollouts)}")
    settings = result.settings
    space, weight = settings["outcome_space"], settings["depth_weight"]
    reached = outcome_vectors(result.outcomes, result.depths, space, weight)
    wanted = goal_outcomes(_geometry()["press_goals"], space, weight)
    distance = np.sqrt(((reached[:, :, None, :] - wanted[None, None]) ** 2).sum(axis=3))
    seeds = [s[1] for s in run_seeds(settings["seed"], result.n_seeds, 2,
                                     first=settings.get("first_run", 0))]
    lab = MovementLab(1)
    out = np.zeros((len(rollouts), result.n_seeds, buttons.N_BUTTONS), dtype=bool)
    for i, n in enumerate(rollouts):
        nearest = distance[:, :n].argmin(axis=1)  # [seed, button]
        movements = np.take_along_axis(result.movements, nearest[:, :, None], axis=1)
        out[i] = _press_each_button(lab, movements, seeds)
    return out


RANGE_SHARES = (0.2, 0.3, 0.4, 0.5, 0.7, 1.0)
"""The reachable ranges `touch_shares` measures by default, as shares of the way from
the resting posture to the joints' limits."""


def touch_shares(shares=RANGE_SHARES, n_movements=500, seed=0, threads=None):
    """How often random movements reach the console when the arm's joint range is cut
    down around its resting posture, as a maturing arm's is
    (`icm.learners.maturation.JointRangeMaturation` with psi = share): for each
    share, `n_movements` joint targets uniform in [home - share (home - lower), home
    + share (upper - home)] are performed, and the share of them that end with the
    finger on the console or a cap is returned, with the share that pressed a button.

    Args:
      shares: increasing shares of the range in (0, 1].
      n_movements: random movements per share (>= 1).
      seed: the seed of the movements (an integer >= 0, a Generator or None).
      threads: as in `run_goal_babbling`.

    Returns:
      A dict {"shares": [...], "touched": [...], "pressed": [...]}, one value per share.
    """
    given, shares = shares, _validate.finite_array("shares", shares, ndim=1)
    if not len(shares) or np.any(np.diff(shares) <= 0) or shares[0] <= 0 or shares[-1] > 1:
        raise ValueError(f"shares must be increasing shares in (0, 1], got "
                         f"{_validate.show(given)}")
    n_movements = _validate.integer_at_least("n_movements", n_movements, 1)
    rng = np.random.default_rng(_validate.root_seed("seed", seed))
    if threads is not None:
        _validate.integer_in_range("threads", threads, 1, _movements.MAX_THREADS)
    lab = MovementLab(threads)
    touched, pressed = [], []
    for share in shares:
        low = lab.home - share * (lab.home - lab.lower)
        high = lab.home + share * (lab.upper - lab.home)
        done = lab.perform(rng.uniform(low, high, (n_movements, len(lab.home))))
        touched.append(float(done["touched"].mean()))
        pressed.append(float((done["pressed"] >= 0).mean()))
    return {"shares": shares.tolist(), "touched": touched, "pressed": pressed}


PRESS_FAILURES = ("formed", "not pushed in far enough", "off the cap",
                  "a neighbour pushed too", "a neighbour pushed instead", "other")
"""What became of the movement formed for each button (`press_failures`), by code."""


def press_failures(result):
    """What became of the movement formed for each button: a code into
    `PRESS_FAILURES` per [seed, button].

    "formed" where `buttons_pressed` holds. Otherwise the movement is rolled out again
    with its return home and read: "a neighbour pushed too" if the button and
    another went past the press depth, "a neighbour pushed instead" if only another
    did, "not pushed in far enough" if none did and the finger ended over the cap
    (within its radius of its centre), "off the cap" if none did and it ended
    elsewhere, and "other" if the button alone was pushed yet the red box alone did
    not open.

    Args:
      result: a `GoalBabblingResult`.
    """
    _validate.instance("result", result, GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    geometry = _geometry()
    lab = MovementLab(1)
    n_seeds = result.n_seeds
    done = lab.perform(result.press_movements.reshape(-1, 7), retract=True)
    over = done["depths"].reshape(n_seeds, buttons.N_BUTTONS, buttons.N_BUTTONS) \
        > buttons.PRESS_DEPTH  # [seed, movement for button, button pushed]
    across = np.linalg.norm(result.press_outcomes[..., :2] - geometry["caps"][:, :2], axis=2)
    codes = np.full((n_seeds, buttons.N_BUTTONS), PRESS_FAILURES.index("other"))
    for b in range(buttons.N_BUTTONS):
        own, others = over[:, b, b], np.delete(over[:, b], b, axis=1).any(axis=1)
        on_cap = across[:, b] <= geometry["cap_radius"]
        codes[own & others, b] = PRESS_FAILURES.index("a neighbour pushed too")
        codes[~own & others, b] = PRESS_FAILURES.index("a neighbour pushed instead")
        codes[~own & ~others & on_cap, b] = PRESS_FAILURES.index("not pushed in far enough")
        codes[~own & ~others & ~on_cap, b] = PRESS_FAILURES.index("off the cap")
    codes[result.buttons_pressed] = PRESS_FAILURES.index("formed")
    return codes


def _press_each_button(lab, press_movements, seeds):
    """[seed, button]: whether the movement for each button, run on a physics console
    where that button is lit red (one console per button), presses that button and
    no other, and opens the red box only."""
    n_seeds = len(press_movements)
    out = np.zeros((n_seeds, buttons.N_BUTTONS), dtype=bool)
    check = buttons.physics.check_press_motions
    for button in range(buttons.N_BUTTONS):
        console = buttons.PhysicsButtonConsole(red_button=button)
        for k in range(n_seeds):
            console.press_motions = check([lab.phases(m) for m in press_movements[k]])
            console.reseed(seeds[k])
            console.reset()
            boxes = console.press(button)
            out[k, button] = (set(console.task.press_log) == {button}
                              and boxes.tolist() == [1, 0])
    return out


@dataclasses.dataclass(frozen=True)
class FormedActionsResult:
    """What `run_formed_actions` measured.

    Attributes:
      settings: the arguments of the run, as a dict.
      learner: the goal-oriented learner's `GoalOrientedResult` on the console whose
        five actions are the formed movements.
      as_scripted: the share of the learner's presses whose effect (which box
        opened) is what the scripted press of the same button gives in that layout.
      n_presses: the presses the learner made, over all seeds.
      as_scripted_per_seed: [seed], that share in each seed's presses (every seed
        makes the same number of presses).
    """

    settings: dict
    learner: _goal_oriented.GoalOrientedResult
    as_scripted: float
    n_presses: int
    as_scripted_per_seed: np.ndarray

    def red_first_fraction(self):
        """Share of seeds in which red is mastered strictly before green (see
        `GoalOrientedResult.red_first_fraction`)."""
        return self.learner.red_first_fraction()

    def red_first(self):
        """[seed], whether red is mastered strictly before green in each seed."""
        mastery = self.learner.mastery_trial
        return comes_first(mastery[:, 0], mastery[:, 1])


class _Recorder:
    """The physics console batch, keeping every (layout, action, effect)."""

    def __init__(self, env):
        self.env, self.log = env, []
        self.n_actions, self.red_button = env.n_actions, env.red_button
        self.effects = env.effects

    def __len__(self):
        return len(self.env)

    def new_trials(self):
        self.layout = self.env.new_trials()
        return self.layout

    def press(self, actions):
        effects = self.env.press(actions)
        self.log.append((self.layout.copy(), np.asarray(actions).copy(), effects.copy()))
        return effects


def run_formed_actions(babbling, n_trials=DEFAULT_TRIALS, seed=0, progress=True,
                       first_run=0):
    """Runs the paper's goal-oriented learner on the physics console, with the movements
    the robot formed by goal babbling as its five press actions.

    Row k of the learner uses seed k's learned movements (`press_movements`) and the
    seeds `run_goal_oriented(n_seeds, n_trials, seed=seed)` gives its run k, so the two
    can be compared seed by seed. The learner keeps its defaults (the paper's).

    Args:
      babbling: a `GoalBabblingResult`.
      n_trials: trials per run (>= 1).
      seed: the root seed of the learner's runs (as in `run_goal_oriented`).
      progress: show a progress bar over the trials.
      first_run: the index of the learner's first run (>= 0): row k uses run
        first_run + k of `seed` (pass the babbling's own `first_run` to keep the
        seed-by-seed pairing of a run made in pieces).

    Returns:
      A `FormedActionsResult`.

    Raises:
      ValueError: for a bad argument.
    """
    _validate.instance("babbling", babbling, GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    _validate.boolean("progress", progress)
    settings = _goal_oriented._check_run_arguments(
        babbling.n_seeds, n_trials, buttons.DEFAULT_PRESSES_PER_TRIAL,
        buttons.DEFAULT_RED_BUTTON, False, True, seed, goal_oriented.GoalOrientedSettings())
    settings["formed_by"] = babbling.strategy
    settings["first_run"] = _validate.integer_at_least("first_run", first_run, 0)
    seeds = run_seeds(settings["seed"], babbling.n_seeds, 2, first=settings["first_run"])
    lab = MovementLab()
    motions = [[lab.phases(m) for m in movements] for movements in babbling.press_movements]
    red = buttons.DEFAULT_RED_BUTTON
    env = _Recorder(buttons.PhysicsButtonConsoleBatch(
        [s[0] for s in seeds], red, buttons.DEFAULT_PRESSES_PER_TRIAL, press_motions=motions))
    agent = goal_oriented.GoalOrientedBatch(
        [s[1] for s in seeds], np.array(buttons.layouts(red)), env.effects, env.n_actions)
    learner = _goal_oriented._play(settings, env, agent, n_trials,
                                   buttons.DEFAULT_PRESSES_PER_TRIAL, red, progress)
    table = buttons.outcome_table(red)
    matches = np.array([table[layout, actions] == effects
                        for layout, actions, effects in env.log])  # [press, seed]
    return FormedActionsResult(settings, learner, float(np.mean(matches)), int(np.size(matches)),
                               matches.mean(axis=0))


def comparison_table(results):
    """A Markdown table of the three strategies' numbers, one row per run.

    Args:
      results: a dict {row label: GoalBabblingResult}.
    """
    check_results("results", results, GoalBabblingResult)
    lines = ["| strategy | seeds | rollouts | test error at the end, cm (95% band) "
             "| buttons pressed (of 5) | seeds pressing all 5 | rollouts that pressed a button |",
             "|---|---|---|---|---|---|---|"]
    for label, result in results.items():
        s = result.summary()
        lines.append(f"| {label} | {result.n_seeds} | {result.n_rollouts} "
                     f"| {100 * s['test_error']:.1f} ({100 * s['test_error_low']:.1f} to "
                     f"{100 * s['test_error_high']:.1f}) | {s['buttons_pressed']:.1f} "
                     f"| {s['all_pressed_share']:.0%} | {s['press_share']:.1%} |")
    return "\n".join(lines)
