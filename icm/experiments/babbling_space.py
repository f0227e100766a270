"""The console as goal babbling sees it: the goal space and its regions, what a
movement's outcome is (where the finger stopped, and how far each cap went down), the
test goals, how far a press must go, and how often random movements of a smaller
reach touch the console (see `icm.experiments.goal_babbling`)."""

import functools

import numpy as np

from icm import _exact, _validate
from icm.envs import buttons
from icm.envs.buttons import movements as _movements
from icm.envs.buttons.movements import MovementLab
from icm.learners import maturation
from icm.learners.goal_choice import RegionGrid

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

def region_grid():
    """The goal space cut into its fixed regions (`REGION_GRID`), a
    `icm.learners.goal_choice.RegionGrid`."""
    return RegionGrid(GOAL_LOW, GOAL_HIGH, REGION_GRID)


def region_bounds():
    """The fixed regions' corners, [region, 2, 3] (low, high), numbered x-major as
    `region_of` numbers them."""
    return region_grid().bounds()


def region_of(points):
    """The region of each point [..., 3] (points outside the goal space fall in the
    nearest region), an int array [...]."""
    return region_grid().region_of(points)


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
    return {space: {name: float(_exact.norm(outcome_vectors(point, depths, space)
                                            - goal_outcomes(goal, space)))
                    for name, (point, depths) in cases.items()}
            for space in OUTCOME_SPACES}


COLUMN_NAMES = ("beyond button 4", "button 4", "button 3", "button 2", "button 1",
                "button 0", "beyond button 0")
"""The columns of regions along y (`REGION_GRID[1]` of them), the robot's right first:
one centred on each button and one beyond each end button."""


def region_columns():
    """The column (index along y) of every region, [region]."""
    return np.array([index[1] for index in np.ndindex(*REGION_GRID)])


RANGE_SHARES = (0.2, 0.3, 0.4, 0.5, 0.7, 1.0)
"""The reachable ranges `touch_shares` measures by default, as shares of the way from
the resting posture to the joints' limits."""


def touch_shares(shares=RANGE_SHARES, n_movements=500, seed=0, threads=None):
    """How often random movements reach the console when the arm's joint range is cut
    down around its resting posture, as a maturing arm's is
    (`icm.learners.maturation.reachable_range`, as `JointRangeMaturation` with psi =
    share): for each share, `n_movements` joint targets uniform in [home - share (home - lower), home
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
        low, high = maturation.reachable_range(lab.home, lab.lower, lab.upper, share)
        done = lab.perform(rng.uniform(low, high, (n_movements, len(lab.home))))
        touched.append(float(done["touched"].mean()))
        pressed.append(float((done["pressed"] >= 0).mean()))
    return {"shares": shares.tolist(), "touched": touched, "pressed": pressed}
