"""The rod experiment on the simulated iCub.

`RodsPhysics` (assets/rods.xml with named accessors), `RodsTask` (a continuous
dm_control task: the action is the 7 arm joint targets; the episode ends when a rod
tilts past 45 degrees), `load_continuous`, and `PhysicsRodTable`, the paper's discrete
moves as arm motions on top of it; `PhysicsRodTableBatch` runs one table per row for
the batched learners.
"""

import collections

import numpy as np
from dm_env import specs

from icm import _validate
from icm.envs import icub
from icm.envs._common import check_discrete_action, check_seed, dm_control_random
from icm.envs.rods.rules import (ACTIONS, DEFAULT_MAX_MOVES, DEFAULT_START_CELL,
                                     HAND_HEIGHT, N_COLUMNS, N_ROWS, ROD_NAMES, TOPPLE_TILT,
                                     cell_number, check_cell, check_start_cell, next_cell,
                                     standable_cells)
from icm.envs.rods.twin import RodEpisodes

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
        self.start_cell = check_start_cell(start_cell, standable_cells())
        self._motions = None

    def motions(self, physics):
        """The grid postures for this physics (computed once per process)."""
        if self._motions is None:
            self._motions = icub.shared_motions(GridMotions, physics)
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


class PhysicsRodTableBatch:
    """One simulated rod table per row, with the interface of `RodTableBatch`, for
    running the batched learners on the physics (row k is a `PhysicsRodTable`, moved
    one row after the other).

    Args:
      n_rows: number of tables.
      start_cell: (column, row) where every episode starts.
    """

    def __init__(self, n_rows, start_cell=DEFAULT_START_CELL):
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.start = cell_number(check_start_cell(start_cell, standable_cells()))
        self.tables = [PhysicsRodTable(start_cell=start_cell, max_moves=10**9)
                       for _ in range(self.n_rows)]

    def new_episodes(self, rows):
        """Stands the rods up and puts the hand over the start cell in `rows`."""
        for row in np.atleast_1d(rows).tolist():
            self.tables[row].reset()

    def move(self, rows, cells, actions):
        """The moves `actions` of the tables `rows` (each is at its cell in `cells`):
        returns (next cells, rods toppled: 0 red, 1 blue, -1 none), read from the
        physics."""
        nxt = np.zeros(len(rows), dtype=np.int64)
        toppled = np.full(len(rows), -1, dtype=np.int64)
        for i, (row, cell, action) in enumerate(zip(np.asarray(rows).tolist(),
                                                    np.asarray(cells).tolist(),
                                                    np.asarray(actions).tolist())):
            table = self.tables[row]
            assert cell_number(table._cell) == cell, "the physics table is elsewhere"
            step = table.step(action)
            nxt[i] = cell_number(tuple(step.observation["hand"].tolist()))
            rods = step.observation["rods"]
            if rods.any():
                toppled[i] = int(np.argmax(rods))
        return nxt, toppled
