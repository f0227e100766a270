"""The rod experiment on the simulated iCub.

`RodsPhysics` (assets/rods.xml with named accessors), `RodsTask` (a continuous
dm_control task: the action is the 7 arm joint targets; the episode ends when a rod
tilts past 45 degrees), `load_continuous`, and `PhysicsRodTable`, the paper's discrete
moves as arm motions on top of it; `PhysicsRodTableBatch` runs one table per row for
the batched learners. With `wobbly_rod=True` the scene is assets/rods_wobbly.xml: the
same table plus the wobbly rod, which the task watches (see `RodsTask`).
"""

import collections

import mujoco
import numpy as np
from dm_env import specs

from icm import _exact, _validate
from icm.envs import icub
from icm.envs._common import check_discrete_action, check_seed, dm_control_random
from icm.envs.rods import rules
from icm.envs.rods.rules import (ACTIONS, DEFAULT_MAX_MOVES, DEFAULT_START_CELL, OFF_GRID,
                                     HAND_HEIGHT, N_COLUMNS, N_ROWS, ROD_NAMES, TOPPLE_TILT,
                                     WOBBLY, cell_number,
                                     check_cell, check_start_cell, next_cell, rod_names,
                                     standable_cells)
from icm.envs.rods.twin import RodEpisodes

ROD_GEOMS = [f"{name}_rod" for name in ROD_NAMES]
"""The geoms of the red and the blue rod, in every scene (`ROD_NAMES`' order)."""
_WOBBLY_ROD = f"{WOBBLY}_rod"
WOBBLE_REACH = 0.08
"""The hand passes beside the wobbly rod when its fingertip crosses the line level with
the rod (along the robot's forward axis) within this distance of it sideways (metres).
The grid's nearest column runs 5.5 cm beside the rod, the next one 11 cm; the cells
on either side of the rod are 2.75 cm before and after it (a move overshoots by up
to 2 cm)."""
WOBBLE_PUSH = 20.0
"""The angular speed (radians per second) the task gives a wobbly rod that falls,
tipping it away from the grid."""


class RodsPhysics(icub.ArmPhysics):
    """The rod scene (assets/rods.xml, or assets/rods_wobbly.xml) with named
    accessors."""

    @property
    def rod_names(self):
        """The rods of the scene: red, blue, and the wobbly one if it is there."""
        if getattr(self, "_rod_model", None) is not self.model.ptr:
            self._has_wobbly = mujoco.mj_name2id(self.model.ptr, mujoco.mjtObj.mjOBJ_BODY,
                                                 _WOBBLY_ROD) >= 0
            self._rod_model = self.model.ptr
        return rod_names(self._has_wobbly)

    def rod_bodies(self):
        """The rods' body names, in the order of `rod_names`."""
        return [f"{name}_rod" for name in self.rod_names]

    def rod_tilt(self, name):
        """How far rod `name` ("red", "blue" or "wobbly") leans from upright, in
        radians."""
        name = _validate.one_of("name", name, self.rod_names)
        return float(np.arccos(np.clip(self.named.data.xmat[f"{name}_rod"][8], -1.0, 1.0)))

    def rod_tilts(self):
        """Every rod's tilt (radians), in the order of `rod_names`."""
        return np.array([self.rod_tilt(name) for name in self.rod_names])

    def rods_toppled(self):
        """The `rods` observation read from the physics: 1 where a rod tilts > 45 deg."""
        return (self.rod_tilts() > TOPPLE_TILT).astype(np.int64)

    def rod_positions(self):
        """The rods' centres (world, metres), shape (rods, 3)."""
        return self.named.data.xpos[self.rod_bodies()].copy()

    def cell_centre(self, cell):
        """World position (metres) of the centre of grid cell (column, row), on the table."""
        cell = check_cell("cell", cell)
        return self.named.data.geom_xpos[f"cell_{cell[0]}_{cell[1]}"].copy()

    def hand_cell(self):
        """The grid cell whose centre is nearest the fingertip (in the table's plane)."""
        tip = self.fingertip_position()[:2]
        cells = [(c, r) for r in range(N_ROWS) for c in range(N_COLUMNS)]
        distances = [_exact.norm(self.cell_centre(cell)[:2] - tip) for cell in cells]
        return cells[int(np.argmin(distances))]

    def stand_rods(self):
        """Stands both rods upright at rest where the model places them."""
        for name in self.rod_bodies():
            joint = self.model.name2id(name, "joint")
            start = self.model.jnt_qposadr[joint]
            self.data.qpos[start:start + 7] = self.model.qpos0[start:start + 7]
            self.data.qvel[self.model.jnt_dofadr[joint]:self.model.jnt_dofadr[joint] + 6] = 0


    def hand_beside_wobbly_rod(self):
        """Where the fingertip is with respect to the wobbly rod: (side, near), side
        -1 before the rod's level (nearer the robot) or +1 past it, near True within
        `WOBBLE_REACH` of it sideways. None without a wobbly rod."""
        if WOBBLY not in self.rod_names:
            return None
        tip = self.named.data.site_xpos["fingertip"]
        rod = self.named.data.xpos[_WOBBLY_ROD]
        return (1 if tip[0] > rod[0] else -1), bool(abs(tip[1] - rod[1]) < WOBBLE_REACH)

    def push_wobbly_rod(self):
        """Tips the wobbly rod over, away from the grid (towards the robot's left): the
        task's push when it falls."""
        joint = self.model.name2id(_WOBBLY_ROD, "joint")
        dof = self.model.jnt_dofadr[joint]
        self.data.qvel[dof + 3] = -WOBBLE_PUSH  # about -x: the top moves towards +y


def load_physics(wobbly_rod=False):
    """A fresh `RodsPhysics` of assets/rods.xml (with `wobbly_rod`, of
    assets/rods_wobbly.xml: the same scene plus the wobbly rod)."""
    scene = "rods_wobbly.xml" if _validate.boolean("wobbly_rod", wobbly_rod) else "rods.xml"
    return RodsPhysics.from_scene(scene)


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

    Action: target angles of the 7 right-arm joints (radians). Each episode stands the
    rods upright and starts the hand over `start_cell`. The episode ends (discount 0)
    when a rod tilts past 45 degrees. Reward 0.0: the paper's learner pays itself.

    With `wobbly_rod` (on `load_physics(wobbly_rod=True)`), the task watches the hand
    after every physics update. Each time the fingertip crosses the line level with
    the wobbly rod close beside it (`RodsPhysics.hand_beside_wobbly_rod`), the task
    draws one number u from its generator; if u < 1/2 it pushes the rod, which falls.
    After `begin_move` (the discrete layer calls it before every move) it draws at
    most once until the next `begin_move`, as `RodTable` draws once per move.

    Args:
      start_cell: (column, row) where the hand starts (default (0, 0)); a cell where
        the hand can rest with both rods standing.
      wobbly_rod: the scene has the wobbly rod (default False).
      random: None, an integer >= 0 or a `numpy.random.Generator` (the wobbly rod's
        draws; without it the rules use no randomness).
    """

    MOTIONS = GridMotions

    def __init__(self, start_cell=DEFAULT_START_CELL, wobbly_rod=False, random=None):
        self.generator = check_seed(random, "random")
        super().__init__(random=dm_control_random(self.generator))
        self.start_cell = check_start_cell(start_cell, standable_cells())
        self.wobbly_rod = _validate.boolean("wobbly_rod", wobbly_rod)
        self.rod_names = rod_names(self.wobbly_rod)
        self.wobble_log = []
        self._side = None  # where the fingertip was at the last update (see update)
        self._once, self._drawn = False, False

    def initialize_episode(self, physics):
        if tuple(physics.rod_names) != self.rod_names:
            raise ValueError(f"the task has the rods {self.rod_names} (wobbly_rod="
                             f"{self.wobbly_rod}) but the scene {tuple(physics.rod_names)}")
        physics.stand_rods()
        icub.Arm(physics).place(self.motions(physics).cells[self.start_cell])
        self.wobble_log = []
        self._side = None
        self._once, self._drawn = False, False

    def begin_move(self):
        """Starts a discrete move: from now on at most one draw, until the next call."""
        self._once, self._drawn = True, False

    def after_step(self, physics):
        self.update(physics)

    def update(self, physics):
        """Watches the hand beside the wobbly rod (nothing without one): on coming
        beside it, draws whether it falls, and if so pushes it."""
        if not self.wobbly_rod:
            return
        side, near = physics.hand_beside_wobbly_rod()
        crossed = self._side is not None and side != self._side and near
        self._side = side
        if crossed and not (self._once and self._drawn):
            self._drawn = True
            falls = self.generator.random() < rules.WOBBLE_TOPPLE_PROBABILITY
            self.wobble_log.append(bool(falls))
            if falls:
                physics.push_wobbly_rod()

    def observation_spec(self, physics):
        n = len(self.rod_names)
        return collections.OrderedDict(
            **self.arm_observation_spec(),
            rod_tilts=specs.BoundedArray((n,), np.float64, 0.0, np.pi, name="rod_tilts"),
            rod_positions=specs.Array((3 * n,), np.float64, name="rod_positions"),
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
      **task_kwargs: `RodsTask` arguments (start_cell, wobbly_rod).
    """
    task = RodsTask(random=check_seed(seed), **task_kwargs)
    return icub.continuous_environment(load_physics(task.wobbly_rod), task, time_limit)


class PhysicsRodTable(RodEpisodes):
    """The paper's rod experiment on the simulated iCub, with discrete moves.

    Same action spec, observation spec and episode rules (`RodEpisodes`) as
    `RodTable`. A move drives the arm's actuators along the grid line to the
    neighbouring cell's posture (via the midpoint) at rod height; whatever is in the
    way is pushed by the physics. The physics then runs on until the rods are still,
    or a toppling rod lies on the table. `hand` is the cell nearest the fingertip and
    `rods` is read from the rods' tilts. A move off the grid leaves the hand where it
    is.

    With `wobbly_rod`, the scene has the wobbly rod, which the task watches during
    every move (`RodsTask.update`): its draws come from the task's generator, seeded
    like `RodTable`'s, one per move that passes beside it, so the twins stay in step.

    Args:
      start_cell: (column, row) where each episode starts (default (0, 0)).
      max_moves: moves before an episode without a topple ends (>= 1, default 30;
        None: no limit).
      wobbly_rod: add the wobbly rod (default False).
      seed: None, an integer >= 0 or a `numpy.random.Generator` (the wobbly rod's
        draws; without it the rules use no randomness).
      off_grid: what a move off the grid does: "stay" (default) or "end" (the
        episode ends); see `icm.envs.rods.rules.OFF_GRID`.

    Attributes:
      physics: the `RodsPhysics`, to inspect or render.
    """

    SEGMENT_TIME = 0.2
    """Seconds for each half of a move."""
    SETTLE_TIME = 0.3
    """Seconds the physics runs on after a move, at least."""
    FALL_TIME = 1.0
    """Longest wait (seconds) for a tipping rod to come to rest."""
    TIPPING_TILT = np.deg2rad(5.0)
    """A rod that leans more than this (radians) after the settling time is tipping:
    the physics runs on until the rods are still (or `FALL_TIME`)."""
    REST_SPEED = 0.05
    """The rods are still when no component of their velocities (m/s, rad/s) is
    larger than this."""

    def __init__(self, start_cell=DEFAULT_START_CELL, max_moves=DEFAULT_MAX_MOVES,
                 wobbly_rod=False, seed=None, off_grid=OFF_GRID.default):
        super().__init__(start_cell, max_moves, wobbly_rod, off_grid)
        self.task = RodsTask(start_cell=self.start_cell, wobbly_rod=self.wobbly_rod,
                             random=check_seed(seed))
        self.physics = load_physics(self.wobbly_rod)
        self.arm = icub.Arm(self.physics)
        self.motions = self.task.motions(self.physics)
        self._cell = self.start_cell

    def reseed(self, seed):
        """Restarts the task's random generator from `seed` (used by the wobbly rod
        only); the next step starts a new episode."""
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

        task = self.task
        task.begin_move()

        def record():
            task.update(physics)
            if recorder is not None:
                recorder(physics)
            return False

        # No per-update call unless asked for or needed (the wobbly rod is watched).
        watch = None if recorder is None and not self.wobbly_rod else record

        if target != self._cell:
            self.arm.move(self.motions.midpoints[(self._cell, target)], self.SEGMENT_TIME, watch)
            self.arm.move(self.motions.cells[target], self.SEGMENT_TIME, watch)
            self._cell = target
        self.arm.hold(self.SETTLE_TIME, watch)
        if np.any(physics.rod_tilts() > self.TIPPING_TILT):
            # A rod is tipping: let it fall and come to rest before looking.
            bodies = physics.rod_bodies()
            speed = lambda: np.abs(physics.named.data.qvel[bodies]).max()
            self.arm.hold(self.FALL_TIME, monitor=lambda: (watch is not None and watch())
                          or speed() < self.REST_SPEED)
        return physics.rods_toppled()


class PhysicsRodTableBatch:
    """One simulated rod table per row, with the interface of `RodTableBatch`, for
    running the batched learners on the physics (row k is a `PhysicsRodTable`, moved
    one row after the other).

    Args:
      n_rows: number of tables.
      start_cell: (column, row) where every episode starts.
      wobbly_rod: add the wobbly rod.
      seeds: one seed per row (the wobbly rod's draws; default 0, 1, ...).
    """

    def __init__(self, n_rows, start_cell=DEFAULT_START_CELL, wobbly_rod=False, seeds=None):
        self.n_rows = _validate.integer_at_least("n_rows", n_rows, 1)
        self.start = cell_number(check_start_cell(start_cell, standable_cells()))
        seeds = range(self.n_rows) if seeds is None else seeds
        self.tables = [PhysicsRodTable(start_cell=start_cell, max_moves=None,
                                       wobbly_rod=wobbly_rod, seed=seed)
                       for seed in seeds]

    def new_episodes(self, rows):
        """Stands the rods up and puts the hand over the start cell in `rows`."""
        for row in np.atleast_1d(rows).tolist():
            self.tables[row].reset()

    def move(self, rows, cells, actions):
        """The moves `actions` of the tables `rows` (each is at its cell in `cells`):
        returns (next cells, rods toppled: 0 red, 1 blue, 2 wobbly, -1 none), read
        from the physics."""
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
