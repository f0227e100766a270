"""The rod-toppling experiment of the paper (section 2.2): a hand on a 5 x 3 grid.

The robot's right hand moves between the cells of a 5 x 3 grid over a table (actions
forward, backward, left, right; a move off the grid leaves the hand where it is). Two
rods stand on the table: the red one is toppled from many (cell, action) pairs, the
blue one from few. An episode ends when a rod topples.

This module holds:

- the rules of the grid (`next_cell`, `ACTIONS`, the start cell) and the topple map,
  measured in physics and stored in assets/rod_topple_map.json (`load_topple_map`,
  `measure_topple_map`),
- the fast tabular environment `RodTable`, which follows the stored map,
- the simulated iCub: `RodsPhysics` (assets/rods.xml with named accessors),
  `RodsTask` (a continuous dm_control task: the action is the 7 arm joint targets; the
  episode ends when a rod tilts past 45 degrees), `load_continuous`, and
  `PhysicsRodTable`, the paper's discrete moves as arm motions on top of it.
"""

import collections
import json

import dm_env
import numpy as np
from dm_env import specs

from icm import _validate
from icm.envs import icub
from icm.envs._common import check_discrete_action, check_seed, dm_control_random

N_COLUMNS, N_ROWS = 5, 3
"""Grid size: columns 0-4 from the robot's left to its right, rows 0-2 from the robot
outwards."""
ACTIONS = ("forward", "backward", "left", "right")
"""Action names by index: forward is away from the robot (row + 1), left is towards
the robot's left (column - 1)."""
_MOVES = {0: (0, 1), 1: (0, -1), 2: (-1, 0), 3: (1, 0)}  # action -> (d column, d row)
ROD_NAMES = ("red", "blue")
"""Order of the rods in the `rods` observation."""
DEFAULT_START_CELL = (0, 0)
"""Episodes start with the hand over the cell nearest the robot on its left."""
DEFAULT_MAX_MOVES = 30
"""An episode without a topple ends after this many moves (a time limit)."""
TOPPLE_TILT = np.deg2rad(45.0)
"""A rod counts as toppled when it tilts further than this from upright."""
TOPPLE_MAP_FILE = "rod_topple_map.json"

HAND_HEIGHT = 0.04
"""Height of the fingertip above the table while it moves (the rods are 7 cm tall).
Where the cells are is read from the model: the marker geoms cell_<column>_<row>."""


def check_cell(name, cell):
    """Returns `cell` as a (column, row) tuple of ints if it is on the grid."""
    allowed = "a (column, row) pair of integers"
    if isinstance(cell, (str, bytes)) or not hasattr(cell, "__len__") or \
            np.ndim(cell) != 1 or len(cell) != 2 or \
            not all(_validate.is_integer(v) for v in cell):
        raise _validate.ArgumentTypeError(f"{name} must be {allowed}, got "
                                          f"{_validate.show(cell)}")
    column, row = (int(v) for v in cell)
    if not (0 <= column < N_COLUMNS and 0 <= row < N_ROWS):
        raise ValueError(f"{name} must be on the {N_COLUMNS} x {N_ROWS} grid (column 0-4, "
                         f"row 0-2), got {cell!r}")
    return column, row


def next_cell(cell, action):
    """The cell the hand ends in after `action` from `cell` (off the grid: stays)."""
    cell = check_cell("cell", cell)
    dc, dr = _MOVES[check_discrete_action(action, len(ACTIONS))]
    column, row = cell[0] + dc, cell[1] + dr
    if 0 <= column < N_COLUMNS and 0 <= row < N_ROWS:
        return column, row
    return tuple(cell)


def observation_spec():
    """The observation spec shared by the tabular and the physics rod environments."""
    return collections.OrderedDict(
        hand=specs.BoundedArray((2,), np.int64, [0, 0], [N_COLUMNS - 1, N_ROWS - 1],
                                name="hand"),
        rods=specs.BoundedArray((2,), np.int64, 0, 1, name="rods"),
    )


def action_spec():
    """Four discrete moves: 0 forward, 1 backward, 2 left, 3 right."""
    return specs.DiscreteArray(len(ACTIONS), dtype=np.int64, name="move")


def load_topple_map():
    """The stored topple map (assets/rod_topple_map.json), as a dict.

    Returns:
      {"standable": set of cells where the hand can rest with both rods standing,
       "topples": {(cell, action): "red" | "blue" | None} for every standable cell}.
    """
    data = json.loads(icub.asset_path(TOPPLE_MAP_FILE).read_text())
    topples = {(tuple(entry["cell"]), entry["action"]): entry["topples"]
               for entry in data["pairs"]}
    return {"standable": {tuple(c) for c in data["standable"]}, "topples": topples}


def _standable_cells():
    """The standable cells of the stored map; every cell if no map is stored yet (when
    `python -m icm.envs.rods` measures the first one)."""
    if not (icub.ASSETS / TOPPLE_MAP_FILE).exists():
        return {(c, r) for c in range(N_COLUMNS) for r in range(N_ROWS)}
    return load_topple_map()["standable"]


def topple_counts(topple_map):
    """How many (cell, action) pairs topple each rod: {"red": n, "blue": m}."""
    values = list(topple_map["topples"].values())
    return {name: values.count(name) for name in ROD_NAMES}


class RodEpisodes(dm_env.Environment):
    """The episode rules of the rod experiment, shared by `RodTable` (tabular) and
    `PhysicsRodTable` (simulated iCub), so both follow them by construction.

    An episode starts with the hand over `start_cell` and both rods standing. Each
    action moves the hand to the neighbouring cell (off the grid: it stays). A move
    that topples a rod ends the episode (discount 0.0, a termination) with the rod
    shown toppled; after `max_moves` moves without a topple the episode ends on a time
    limit (discount 1.0). Reward is always 0.0. A step after the end of an episode
    starts a new one.

    Subclasses say how an episode starts (`_start`) and what a move does (`_move`,
    returning the hand's cell and the rods' toppled flags).
    """

    def __init__(self, start_cell, max_moves):
        self.start_cell = check_start_cell(start_cell, _standable_cells())
        self.max_moves = _validate.integer_at_least("max_moves", max_moves, 1)
        self._moves = 0
        self._reset_next_step = True

    def _start(self):
        raise NotImplementedError

    def _move(self, action):
        raise NotImplementedError

    @staticmethod
    def _observation(cell, rods):
        return collections.OrderedDict(hand=np.array(cell, dtype=np.int64),
                                       rods=np.asarray(rods, dtype=np.int64))

    def reset(self):
        """Starts a new episode: the hand over the start cell, both rods standing.

        Returns:
          The FIRST time step.
        """
        self._start()
        self._moves = 0
        self._reset_next_step = False
        return dm_env.restart(self._observation(self.start_cell, [0, 0]))

    def step(self, action):
        """Moves the hand: 0 forward, 1 backward, 2 left, 3 right.

        Returns:
          The time step after the move; after the end of an episode, a new one starts
          instead.

        Raises:
          ValueError: if `action` is not 0-3.
        """
        action = check_discrete_action(action, len(ACTIONS))
        if self._reset_next_step:
            return self.reset()
        cell, rods = self._move(action)
        self._moves += 1
        observation = self._observation(cell, rods)
        if np.any(rods):
            self._reset_next_step = True
            return dm_env.termination(0.0, observation)
        if self._moves >= self.max_moves:
            self._reset_next_step = True
            return dm_env.truncation(0.0, observation, discount=1.0)
        return dm_env.transition(0.0, observation)

    def observation_spec(self):
        """The observation spec: `hand` and `rods` (see `observation_spec()`)."""
        return observation_spec()

    def action_spec(self):
        """The action spec: four moves (see `action_spec()`)."""
        return action_spec()


class RodTable(RodEpisodes):
    """The tabular rod experiment: the grid rules and the stored topple map, no physics.

    The episode rules are those of `RodEpisodes`; whether a move topples a rod is read
    from the topple map measured in physics (assets/rod_topple_map.json).

    Args:
      start_cell: (column, row) where each episode starts; must be a standable cell of
        the map. Default (0, 0), the cell nearest the robot on its left.
      max_moves: moves before an episode without a topple ends (>= 1, default 30).
      seed: None, an integer >= 0 or a `numpy.random.Generator`; accepted for
        symmetry with the other environments (the rules use no randomness).

    Raises:
      ValueError: for a start cell off the grid or where a rod stands, max_moves < 1,
        or (in `step`) an action that is not 0-3.
    """

    def __init__(self, start_cell=DEFAULT_START_CELL, max_moves=DEFAULT_MAX_MOVES, seed=None):
        super().__init__(start_cell, max_moves)
        self._map = load_topple_map()
        self._random = check_seed(seed)
        self._cell = self.start_cell

    def reseed(self, seed):
        """Checks `seed` (the rules use no randomness); the next step starts a new
        episode."""
        self._random = check_seed(seed)
        self._reset_next_step = True

    @property
    def topple_map(self):
        """{(cell, action): "red" | "blue" | None} for the standable cells."""
        return dict(self._map["topples"])

    def _start(self):
        self._cell = self.start_cell

    def _move(self, action):
        toppled = self._map["topples"][(self._cell, action)]
        self._cell = next_cell(self._cell, action)
        rods = [int(toppled == name) for name in ROD_NAMES]
        return self._cell, rods


def check_start_cell(start_cell, standable):
    """Returns `start_cell` if it is on the grid and the hand can rest there."""
    cell = check_cell("start_cell", start_cell)
    if cell not in standable:
        raise ValueError(f"start_cell {cell} is where a rod stands or the arm would touch one; "
                         f"allowed: {sorted(standable)}")
    return cell


# --- The simulated iCub ---------------------------------------------------------------

_RODS = [f"{name}_rod" for name in ROD_NAMES]


class RodsPhysics(icub.ArmPhysics):
    """The rod scene (assets/rods.xml) with named accessors."""

    def rod_tilt(self, name):
        """How far rod `name` ("red" or "blue") leans from upright, in radians."""
        name = _validate.one_of("name", name, ROD_NAMES)
        return float(np.arccos(np.clip(self.named.data.xmat[f"{name}_rod"][8], -1.0, 1.0)))

    def rod_tilts(self):
        """Both rods' tilts (radians), red then blue."""
        return np.array([self.rod_tilt(name) for name in ROD_NAMES])

    def rods_toppled(self):
        """The `rods` observation read from the physics: 1 where a rod tilts > 45 deg."""
        return (self.rod_tilts() > TOPPLE_TILT).astype(np.int64)

    def rod_positions(self):
        """Both rods' centres (world, metres), shape (2, 3)."""
        return self.named.data.xpos[_RODS].copy()


    def cell_centre(self, cell):
        """World position (metres) of the centre of grid cell (column, row), on the table."""
        cell = check_cell("cell", cell)
        return self.named.data.geom_xpos[f"cell_{cell[0]}_{cell[1]}"].copy()

    def hand_cell(self):
        """The grid cell whose centre is nearest the fingertip (in the table's plane)."""
        tip = self.fingertip_position()[:2]
        cells = [(c, r) for r in range(N_ROWS) for c in range(N_COLUMNS)]
        distances = [np.linalg.norm(self.cell_centre(cell)[:2] - tip) for cell in cells]
        return cells[int(np.argmin(distances))]

    def stand_rods(self):
        """Stands both rods upright at rest where the model places them."""
        for name in _RODS:
            joint = self.model.name2id(name, "joint")
            start = self.model.jnt_qposadr[joint]
            self.data.qpos[start:start + 7] = self.model.qpos0[start:start + 7]
            self.data.qvel[self.model.jnt_dofadr[joint]:self.model.jnt_dofadr[joint] + 6] = 0


def load_physics():
    """A fresh `RodsPhysics` of assets/rods.xml."""
    return RodsPhysics.from_xml_path(str(icub.asset_path("rods.xml")))


class GridMotions:
    """Arm postures over the grid, from inverse kinematics on the model: `cells[(c, r)]`
    puts the fingertip over a cell's centre at HAND_HEIGHT, `midpoints[(a, b)]` halfway
    between neighbouring cells a and b (so moves follow the grid's lines)."""

    POINTING = (1.0, 0.0, -2.0)
    """The finger is drawn towards pointing forward and down."""

    def __init__(self, physics):
        arm = icub.Arm(physics)
        physics.forward()
        lift = np.array([0.0, 0.0, HAND_HEIGHT])
        self.cells, self.midpoints = {}, {}
        start = None
        for row in range(N_ROWS):
            for column in range(N_COLUMNS):
                target = physics.cell_centre((column, row)) + lift
                start = arm.solve(target, start=start, pointing=self.POINTING)
                self.cells[(column, row)] = start
        for cell, q in self.cells.items():
            for action in range(len(ACTIONS)):
                other = next_cell(cell, action)
                if other != cell and (other, cell) not in self.midpoints:
                    target = (physics.cell_centre(cell) + physics.cell_centre(other)) / 2 + lift
                    mid = arm.solve(target, start=q, pointing=self.POINTING)
                    self.midpoints[(cell, other)] = self.midpoints[(other, cell)] = mid


class RodsTask(icub.ArmTask):
    """The rod experiment as a continuous dm_control task.

    Action: target angles of the 7 right-arm joints (radians). Each episode stands both
    rods upright and starts the hand over `start_cell`. The episode ends (discount 0)
    when a rod tilts past 45 degrees. Reward 0.0: the paper's learner pays itself.

    Args:
      start_cell: (column, row) where the hand starts (default (0, 0)); a cell where
        the hand can rest with both rods standing.
      random: None, an integer >= 0 or a `numpy.random.Generator` (unused by the
        rules, kept for dm_control's conventions).
    """

    def __init__(self, start_cell=DEFAULT_START_CELL, random=None):
        self.generator = check_seed(random, "random")
        super().__init__(random=dm_control_random(self.generator))
        self.start_cell = check_start_cell(start_cell, _standable_cells())
        self._motions = None

    def motions(self, physics):
        """The grid postures for this physics (computed once)."""
        if self._motions is None:
            self._motions = GridMotions(physics)
        return self._motions

    def initialize_episode(self, physics):
        physics.stand_rods()
        icub.Arm(physics).place(self.motions(physics).cells[self.start_cell])



    def observation_spec(self, physics):
        return collections.OrderedDict(
            **self.arm_observation_spec(),
            rod_tilts=specs.BoundedArray((2,), np.float64, 0.0, np.pi, name="rod_tilts"),
            rod_positions=specs.Array((6,), np.float64, name="rod_positions"),
        )

    def get_observation(self, physics):
        return collections.OrderedDict(
            arm_joints=physics.arm_joint_positions(),
            fingertip=physics.fingertip_position(),
            rod_tilts=physics.rod_tilts(),
            rod_positions=physics.rod_positions().ravel(),
        )

    def get_reward(self, physics):
        return 0.0

    def get_termination(self, physics):
        if np.any(physics.rod_tilts() > TOPPLE_TILT):
            return 0.0
        return None


def load_continuous(seed=None, time_limit=10.0, **task_kwargs):
    """The continuous rod task: a dm_control `control.Environment`.

    Args:
      seed: None, an integer >= 0 or a `numpy.random.Generator`.
      time_limit: seconds per episode (> 0; float('inf') for no limit).
      **task_kwargs: `RodsTask` arguments (start_cell).
    """
    return icub.continuous_environment(load_physics(), RodsTask(random=seed, **task_kwargs),
                                       time_limit)


class PhysicsRodTable(RodEpisodes):
    """The paper's rod experiment on the simulated iCub, with discrete moves.

    Same action spec, observation spec and episode rules (`RodEpisodes`) as
    `RodTable`. A move drives the arm's actuators along the grid line to the
    neighbouring cell's posture (via the midpoint) at rod height; whatever is in the
    way is pushed by the physics. The physics then runs on until the rods are still,
    or a toppling rod lies on the table. `hand` is the cell nearest the fingertip and
    `rods` is read from the rods' tilts. A move off the grid leaves the hand where it
    is.

    Args:
      start_cell: (column, row) where each episode starts (default (0, 0)).
      max_moves: moves before an episode without a topple ends (>= 1, default 30).
      seed: None, an integer >= 0 or a `numpy.random.Generator` (the rules use no
        randomness).

    Attributes:
      physics: the `RodsPhysics`, to inspect or render.
    """

    SEGMENT_TIME = 0.2
    """Seconds for each half of a move."""
    SETTLE_TIME = 0.3
    """Seconds the physics runs on after a move, at least."""
    FALL_TIME = 1.0
    """Longest wait (seconds) for a tipping rod to come to rest."""

    def __init__(self, start_cell=DEFAULT_START_CELL, max_moves=DEFAULT_MAX_MOVES, seed=None):
        super().__init__(start_cell, max_moves)
        self.task = RodsTask(start_cell=self.start_cell, random=seed)
        self.physics = load_physics()
        self.arm = icub.Arm(self.physics)
        self.motions = self.task.motions(self.physics)
        self._cell = self.start_cell

    def reseed(self, seed):
        """Restarts the task's random generator from `seed` (the rules use none); the
        next step starts a new episode."""
        self.task.generator = check_seed(seed)
        self._reset_next_step = True

    def _start(self):
        """Resets the physics: both rods stood upright, the hand over the start cell."""
        self.task.start_cell = self.start_cell
        with self.physics.reset_context():
            self.task.initialize_episode(self.physics)
        self._cell = self.start_cell

    def _move(self, action):
        rods = self.move(action)
        return self.physics.hand_cell(), rods

    def move(self, action, recorder=None):
        """Runs one move on the physics; returns the rods' toppled flags after it.

        Args:
          action: 0 forward, 1 backward, 2 left, 3 right.
          recorder: optional function of the physics, called after every update of the
            actuators' targets (every 20 ms of simulated time).

        Raises:
          ValueError: if `action` is not 0-3 or `recorder` not a function.
        """
        action = check_discrete_action(action, len(ACTIONS))
        _validate.function("recorder", recorder)
        physics, target = self.physics, next_cell(self._cell, action)

        def record():
            recorder(physics)
            return False

        watch = None if recorder is None else record  # no per-update call unless asked

        if target != self._cell:
            self.arm.move(self.motions.midpoints[(self._cell, target)], self.SEGMENT_TIME, watch)
            self.arm.move(self.motions.cells[target], self.SEGMENT_TIME, watch)
            self._cell = target
        self.arm.hold(self.SETTLE_TIME, watch)
        if np.any(physics.rod_tilts() > np.deg2rad(5.0)):
            # A rod is tipping: let it fall and come to rest before looking.
            speed = lambda: np.abs(physics.named.data.qvel[_RODS]).max()
            self.arm.hold(self.FALL_TIME,
                          monitor=lambda: (watch is not None and watch()) or speed() < 0.05)
        return physics.rods_toppled()


def arm_touches_a_rod(physics):
    """True if any part of the arm is in contact with a rod."""
    _validate.instance("physics", physics, RodsPhysics)
    rods = {physics.model.name2id(name, "geom") for name in _RODS}
    robot = {physics.model.name2id(name, "body")
             for name in ("r_upper_arm", "r_forearm", "r_hand")}
    for contact in physics.data.contact[:physics.data.ncon]:
        bodies = {physics.model.geom_bodyid[contact.geom1], physics.model.geom_bodyid[contact.geom2]}
        if {contact.geom1, contact.geom2} & rods and bodies & robot:
            return True
    return False


def measure_pair(env, cell, action):
    """Runs one move from `cell` on fresh standing rods, in physics.

    Returns:
      A dict: "topples" ("red", "blue" or None), "hand" (the cell it ends over), and
      "disturbance" (the largest displacement, in metres, of a rod that did not topple:
      a nudge that would make later moves depend on history).
    """
    _validate.instance("env", env, PhysicsRodTable)
    cell = check_cell("cell", cell)
    action = check_discrete_action(action, len(ACTIONS))
    env.start_cell = cell  # any cell: the map is what is being measured
    env.reset()
    before = env.physics.rod_positions()
    step = env.step(action)
    rods = step.observation["rods"]
    if rods.all():
        raise RuntimeError(f"the move {ACTIONS[action]} from {cell} topples both rods: the "
                           "rules (and the tabular twin) allow one; move the rods apart")
    moved = np.linalg.norm(env.physics.rod_positions() - before, axis=1)
    standing = rods == 0
    return {"topples": ROD_NAMES[int(np.argmax(rods))] if rods.any() else None,
            "hand": tuple(int(v) for v in step.observation["hand"]),
            "disturbance": float(moved[standing].max()) if standing.any() else 0.0}


def measure_topple_map(cells=None):
    """Measures which (cell, action) pairs topple which rod, by running each in physics.

    A cell is *standable* if the arm, placed over it, touches no rod. Every action from
    every standable cell (or from `cells`, if given) is run on fresh upright rods.

    Returns:
      {"standable": sorted list of cells, "pairs": [{"cell", "action", "topples",
      "hand", "disturbance"}, ...]}.
    """
    if cells is not None:
        if isinstance(cells, (str, bytes)) or not hasattr(cells, "__iter__"):
            raise _validate.ArgumentTypeError(
                f"cells must be None or a list of (column, row) cells, got {cells!r}")
        cells = [check_cell("cells[i]", cell) for cell in cells]
    env = PhysicsRodTable(max_moves=1)
    standable = []
    for row in range(N_ROWS):
        for column in range(N_COLUMNS):
            env.start_cell = (column, row)
            env.reset()
            if not arm_touches_a_rod(env.physics):
                standable.append((column, row))
    pairs = []
    for cell in (standable if cells is None else cells):
        for action in range(len(ACTIONS)):
            result = measure_pair(env, cell, action)
            pairs.append({"cell": list(cell), "action": action, **result,
                          "hand": list(result["hand"])})
    return {"standable": [list(c) for c in standable], "pairs": pairs}


def main():
    """Measures the topple map in physics and writes assets/rod_topple_map.json."""
    measured = measure_topple_map()
    path = icub.ASSETS / TOPPLE_MAP_FILE
    lines = ",\n  ".join(json.dumps(pair) for pair in measured["pairs"])
    path.write_text('{"standable": ' + json.dumps(measured["standable"]) +
                    ',\n "pairs": [\n  ' + lines + "\n ]\n}\n")
    counts = collections.Counter(p["topples"] for p in measured["pairs"])
    print(f"wrote {path}: {len(measured['pairs'])} pairs from {len(measured['standable'])} "
          f"standable cells; red {counts['red']}, blue {counts['blue']}")


if __name__ == "__main__":
    main()
