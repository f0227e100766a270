"""Movements of the simulated iCub's arm over the button console, many at once: each
stepped in C by `mujoco.rollout` from the start of a trial, and what it did, measured
from the simulated states (where the finger stopped, how far each cap went down).

The environment of goal babbling (`icm.experiments.run_goal_babbling`): a movement is
7 final joint targets; `MovementLab.perform` rolls movements out and measures them.
"""

import functools
import os

import numpy as np

from icm import _validate
from icm.envs import icub
from icm.envs.buttons import physics as _physics
from icm.envs.buttons.rules import N_BUTTONS

REACH_TIME = 0.4
"""Seconds the arm takes to reach a movement's final joint targets (minimum jerk; our
choice, as are the next two: the paper's movements are scripted)."""
HOLD_TIME = 0.15
"""Seconds it keeps them; the finger's position is measured at the end of this hold."""
RETRACT_TIME = 0.35
"""Seconds it takes back to the home posture (minimum jerk)."""
FINGER = "r_finger"
"""The geom whose lowest point is where a movement brought the finger."""


MAX_THREADS = 64
"""The most threads a `MovementLab` takes (each holds a copy of the simulation)."""


def default_threads():
    """The cores this process may run on, at most `MAX_THREADS` (`mujoco.rollout`'s
    threads by default)."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    return max(1, min(cores, MAX_THREADS))


@functools.lru_cache(maxsize=1)
def _geometry():
    physics = _physics.load_physics()
    physics.forward()
    named = physics.named
    console = named.data.geom_xpos["console"].copy()
    half = named.model.geom_size["console"].copy()
    caps = np.array([named.data.geom_xpos[f"button{b}_cap"] for b in range(N_BUTTONS)])
    cap_radius, cap_half = named.model.geom_size["button0_cap"][:2]
    travel = -named.model.jnt_range["button0"][0]
    cap_top = caps[0, 2] + cap_half
    pressed_in = caps.copy()
    pressed_in[:, 2] = cap_top - travel
    return {"console_centre": console, "console_half": half,
            "console_top": float(console[2] + half[2]), "caps": caps,
            "cap_radius": float(cap_radius), "cap_top": float(cap_top),
            "travel": float(travel), "pressed_in": pressed_in}


def console_geometry():
    """The console as the model builds it, read from the simulation: a dict with
    "console_centre", "console_half" (its box, m), "console_top" (z), "caps" [5, 3]
    (the caps' centres), "cap_radius", "cap_top" (z of a cap's top at rest), "travel"
    (how far a button can go down) and "pressed_in" [5, 3] (each cap's top centre
    pushed all the way in)."""
    return {key: value.copy() if isinstance(value, np.ndarray) else value
            for key, value in _geometry().items()}


class MovementLab:
    """The button scene at the start of a trial, and movements performed from there.

    A movement is 7 final joint targets q (radians, within the joint ranges). From
    the start of a trial (arm at home, buttons up, lids shut) the actuators' targets
    go from home to q along a minimum-jerk profile in `REACH_TIME`, stay at q for
    `HOLD_TIME` and return home in `RETRACT_TIME`, updated every 20 ms with 10
    physics steps in between: exactly the targets `icub.Arm.move` gives, so that the
    button console performs the same movement (`press_motions`) step for step.

    `perform` rolls many movements out at once in C (`mujoco.rollout`, on the
    scene's own model, on `threads` threads) and measures from the simulated states
    what each did:

    - "point": the lowest point of the finger's surface at the end of the hold,
      where the movement brought the fingertip: on the console's top, on a cap as
      far as it is pushed in, on the table, or in the air (never below the top of
      the console or of a cap under it: see `surface_below`);
    - "depths": how far each of the five caps went down, the deepest it was at any
      20 ms update of the simulated part of the movement;
    - "touched": whether the finger touches the console or a button at the end of
      the hold;
    - "pressed": the first button pushed past `buttons.PRESS_DEPTH`, read at every
      20 ms update as the task reads it (-1 for none).

    Without `retract=True` the rollouts stop at the end of the hold, 40% of the
    steps sooner, and "depths" and "pressed" cover the reach and the hold.

    `home` is the resting posture, `lower` and `upper` the joint ranges, and
    `press_postures` [button, 7] the scripted press's lowest posture for each button
    (`ButtonMotions.down`, the fingertip 2.5 cm below the cap's top, by inverse
    kinematics): a movement to it presses that button, the teacher's demonstration.

    Args:
      threads: MjData instances for `mujoco.rollout` (its threads), 1 to
        `MAX_THREADS`; default `default_threads()`. The results do not depend on it.
    """

    def __init__(self, threads=None):
        import mujoco  # here, not at import: `import icm.envs.buttons` stays quick
        from mujoco import rollout

        threads = default_threads() if threads is None else \
            _validate.integer_in_range("threads", threads, 1, MAX_THREADS)
        self.threads = threads
        self._mujoco = mujoco
        physics = _physics.load_physics()
        task = _physics.ButtonsTask(random=0)
        with physics.reset_context():
            task.initialize_episode(physics)
        self.physics = physics
        model, data = physics.model.ptr, physics.data.ptr
        self.model = model
        arm = icub.Arm(physics)
        self.lower, self.upper = arm.lower.copy(), arm.upper.copy()
        motions = task.motions(physics)
        self.home = np.array(motions.home)
        self.press_postures = np.array(motions.down)
        self.arm_actuators = arm.actuator_index
        state = mujoco.mjtState.mjSTATE_FULLPHYSICS
        self.initial_state = np.empty(mujoco.mj_stateSize(model, state))
        mujoco.mj_getState(model, data, self.initial_state, state)
        self.initial_ctrl = np.array(data.ctrl)
        self.warmstart = np.zeros(model.nv)
        self.substeps = icub.SUBSTEPS
        self.update_time = model.opt.timestep * icub.SUBSTEPS
        self.n_updates = [max(1, int(round(t / self.update_time)))
                          for t in (REACH_TIME, HOLD_TIME, RETRACT_TIME)]
        self.n_steps = sum(self.n_updates) * self.substeps
        self.outcome_step = (self.n_updates[0] + self.n_updates[1]) * self.substeps - 1
        joint = lambda name: model.jnt_qposadr[mujoco.mj_name2id(
            model, mujoco.mjtObj.mjOBJ_JOINT, name)]
        self.button_qpos = np.array([joint(f"button{b}") for b in range(N_BUTTONS)])
        geom = lambda name: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, name)
        self.finger = geom(FINGER)
        self.radius, self.half_length = model.geom_size[self.finger][:2]
        self.console_geoms = {geom("console")} | {geom(f"button{b}_cap")
                                                   for b in range(N_BUTTONS)}
        # The surfaces the finger can rest on: the console's top and each cap's top.
        self.console_geom = geom("console")
        self.cap_geoms = np.array([geom(f"button{b}_cap") for b in range(N_BUTTONS)])
        # Where qpos sits in a rollout's state vector (time first, then qpos).
        self.qpos_slice = slice(1, 1 + model.nq)
        self.datas = [mujoco.MjData(model) for _ in range(threads)]
        # One pool of threads for the lab's life (starting threads at every call of
        # mujoco.rollout costs more than 10 movements take); none for one thread.
        self._runner = rollout.Rollout(nthread=threads if threads > 1 else 0)
        self._scratch = mujoco.MjData(model)

    def check_targets(self, targets):
        """`targets` as an array [movement, 7] of joint targets, at least one movement,
        each target within its joint's range (up to `icub.ACTION_TOLERANCE`, then
        clipped).

        Raises:
          ValueError: for anything else (an `ArgumentTypeError` for what is not an
            array of real numbers), naming the joint and its range.
        """
        targets = _validate.finite_array("targets", targets)
        if targets.ndim != 2 or targets.shape[1] != len(self.home) or not len(targets):
            raise ValueError(f"targets must be an array [movement, {len(self.home)}] "
                             f"of joint targets, at least one movement, got shape "
                             f"{targets.shape}")
        outside = (targets < self.lower - icub.ACTION_TOLERANCE) \
            | (targets > self.upper + icub.ACTION_TOLERANCE)
        if outside.any():
            row, j = np.argwhere(outside)[0]
            raise ValueError(f"targets must lie within the joints' ranges: joint {j} "
                             f"({icub.ARM_JOINTS[j]}) in [{self.lower[j]:.4f}, "
                             f"{self.upper[j]:.4f}] rad, got {targets[row, j]!r} in row {row}")
        return np.clip(targets, self.lower, self.upper)

    def clip(self, targets):
        """`targets` [..., 7] clipped to the joint ranges (exploration noise may push
        a target past a joint's end; the arm stops there)."""
        return np.clip(targets, self.lower, self.upper)

    def phases(self, target):
        """The movement to `target` (7 joint targets within the ranges) as (joint
        targets, seconds) pairs, the form the button console takes
        (`press_motions`)."""
        target = self.check_targets(np.asarray(target)[None] if np.ndim(target) == 1
                                    else target)
        if len(target) != 1:
            raise ValueError(f"target must be one movement (7 joint targets), got "
                             f"{len(target)}")
        return ((target[0], REACH_TIME), (target[0], HOLD_TIME),
                (self.home.copy(), RETRACT_TIME))

    def controls(self, targets):
        """The controls of every physics step of each movement, [movement, step, nu].

        Each phase is computed as `icub.Arm.move` computes it: from the targets the
        previous phase ended on, start + profile x (goal - start)."""
        targets = self.check_targets(targets)
        n = len(targets)
        start = np.broadcast_to(self.home, targets.shape)
        home = np.broadcast_to(self.home, targets.shape)
        rows = []
        for goal, n_updates in zip((targets, targets, home), self.n_updates):
            profile = icub.minimum_jerk(np.arange(1, n_updates + 1) / n_updates)
            phase = start[:, None, :] + profile[None, :, None] * (goal - start)[:, None, :]
            rows.append(phase)
            start = phase[:, -1]
        arm = np.repeat(np.concatenate(rows, axis=1), self.substeps, axis=1)
        controls = np.broadcast_to(self.initial_ctrl, (n, self.n_steps, len(self.initial_ctrl)))
        controls = controls.copy()
        controls[:, :, self.arm_actuators] = arm
        return controls

    def perform(self, targets, retract=False):
        """Performs the movements to `targets` [movement, 7], each from the start of a
        trial, in C.

        Args:
          targets: joint targets [movement, 7], within the joint ranges.
          retract: also simulate the return home (see the class docstring).

        Returns:
          A dict of arrays: "point" [movement, 3] (m), "depths" [movement, 5] (m),
          "touched" [movement] (bool), "pressed" [movement] (first button pushed past
          the press depth, -1 for none).
        """
        retract = _validate.boolean("retract", retract)
        n = len(self.check_targets(targets))
        steps = self.n_steps if retract else self.outcome_step + 1
        _validate.fits_in_memory(f"perform with {n} movements",
                                 8 * n * steps * (len(self.initial_ctrl) + len(self.initial_state)))
        controls = self.controls(targets)
        if not retract:
            controls = controls[:, :self.outcome_step + 1]
        n = len(controls)
        state, _ = self._runner.rollout(self.model, self.datas, self.initial_state, controls,
                                        initial_warmstart=self.warmstart)
        qpos = state[:, :, self.qpos_slice]
        point = np.empty((n, 3))
        touched = np.zeros(n, dtype=bool)
        for i in range(n):
            point[i], touched[i] = self.measure(qpos[i, self.outcome_step])
        # The task reads the buttons after every update (every `substeps` steps).
        depths = -qpos[:, self.substeps - 1::self.substeps][:, :, self.button_qpos]
        return {"point": point, "depths": np.maximum(depths.max(axis=1), 0.0),
                "touched": touched, "pressed": first_press(depths)}

    def measure(self, qpos):
        """(lowest point of the finger's surface (3,), whether the finger touches the
        console or a button) at joint positions `qpos` (the whole scene's)."""
        model, data, mujoco = self.model, self._scratch, self._mujoco
        data.qpos[:] = qpos
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
        point = lowest_capsule_point(data.geom_xpos[self.finger],
                                     data.geom_xmat[self.finger].reshape(3, 3)[:, 2],
                                     self.radius, self.half_length)
        point[2] = max(point[2], self.surface_below(point))
        pairs = data.contact.geom[:data.ncon]
        touched = any((a == self.finger and b in self.console_geoms)
                      or (b == self.finger and a in self.console_geoms) for a, b in pairs)
        return point, touched

    def surface_below(self, point):
        """The height of the top surface under `point` in the scene as last computed
        (the console's top, or a cap's top as far as it is pushed in), -inf where
        there is none.

        The finger's point is never lower than this: soft contacts let a finger driven
        hard sink a few millimetres into the console, and one swept fast sideways
        into a cap pass into it without pushing it down. Read as a position on the
        surfaces, such a finger is on the console or on an unpressed cap, not in
        them."""
        data, model = self._scratch, self.model
        top = -np.inf
        centre = data.geom_xpos[self.console_geom]
        half = model.geom_size[self.console_geom]
        if np.all(np.abs(point[:2] - centre[:2]) <= half[:2]):
            top = centre[2] + half[2]
        for cap in self.cap_geoms:
            radius, half_height = model.geom_size[cap][:2]
            if np.hypot(*(point[:2] - data.geom_xpos[cap][:2])) <= radius:
                top = max(top, data.geom_xpos[cap][2] + half_height)
        return top


def lowest_capsule_point(centre, axis, radius, half_length):
    """The lowest point (smallest z) of a capsule's surface: below the lower end of
    its axis segment, one radius down."""
    ends = (centre + half_length * axis, centre - half_length * axis)
    low = ends[0] if ends[0][2] <= ends[1][2] else ends[1]
    return low - np.array([0.0, 0.0, radius])


def first_press(depths):
    """The first button whose depth passes `buttons.PRESS_DEPTH` in each row of
    `depths` [movement, update, button] (the lowest-numbered among those that pass at
    the same update), -1 where none does."""
    over = depths > _physics.PRESS_DEPTH
    any_over = over.any(axis=2)
    pressed = np.full(len(depths), -1, dtype=np.int64)
    rows = np.flatnonzero(any_over.any(axis=1))
    if len(rows):
        first_update = np.argmax(any_over[rows], axis=1)
        pressed[rows] = np.argmax(over[rows, first_update], axis=1)
    return pressed
