"""Movements of the simulated iCub's arm over the button console, many at once: each
stepped in C by `mujoco.rollout` from the start of a trial, and what it reached,
measured from the simulated states."""

import numpy as np

from icm import _validate
from icm.envs import buttons

REACH_TIME = 0.4
"""Seconds the arm takes to reach a movement's final joint targets (minimum jerk)."""
HOLD_TIME = 0.15
"""Seconds it keeps them; the outcome is measured at the end of this hold."""
RETRACT_TIME = 0.35
"""Seconds it takes back to the home posture (minimum jerk)."""
FINGER = "r_finger"
"""The geom whose lowest point is the outcome of a movement."""


class MovementLab:
    """The button scene at the start of a trial, and movements performed from there.

    A movement is 7 final joint targets q (radians, within the joint ranges). From
    the start of a trial (arm at home, buttons up, lids shut) the actuators' targets
    go from home to q along a minimum-jerk profile in `REACH_TIME`, stay at q for
    `HOLD_TIME` and return home in `RETRACT_TIME`, updated every 20 ms with 10
    physics steps in between: exactly the targets `icub.Arm.move` gives, so that the
    button console performs the same movement (`press_motions`) step for step.

    `perform` rolls many movements out at once in C (`mujoco.rollout`, on the
    scene's own model) and measures from the simulated states what each reached:

    - the outcome: the lowest point of the finger's surface at the end of the hold,
      where the movement brought the fingertip: on the console's top, on a cap as
      far as it is pushed in, on the table, or in the air (never below the top of
      the console or of a cap under it: see `surface_below`);
    - whether the finger then touches the console or a button;
    - the first button pushed past `buttons.PRESS_DEPTH`, read at every 20 ms
      update as the task reads it (-1 for none), during the reach and the hold
      (and the return, with `retract=True`).

    Args:
      threads: MjData instances for `mujoco.rollout` (its threads), >= 1. The
        results do not depend on it.
    """

    def __init__(self, threads=1):
        import mujoco  # here, not at import: `import icm.experiments` stays quick
        from mujoco import rollout

        from icm.envs import icub

        threads = _validate.integer_at_least("threads", threads, 1)
        self._mujoco, self._rollout, self._icub = mujoco, rollout, icub
        physics = buttons.load_physics()
        task = buttons.ButtonsTask(random=0)
        with physics.reset_context():
            task.initialize_episode(physics)
        self.physics = physics
        model, data = physics.model.ptr, physics.data.ptr
        self.model = model
        arm = icub.Arm(physics)
        self.lower, self.upper = arm.lower.copy(), arm.upper.copy()
        self.home = np.array(task.motions(physics).home)
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
        self.button_qpos = np.array([joint(f"button{b}") for b in range(buttons.N_BUTTONS)])
        geom = lambda name: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, name)
        self.finger = geom(FINGER)
        self.radius, self.half_length = model.geom_size[self.finger][:2]
        self.console_geoms = {geom("console")} | {geom(f"button{b}_cap")
                                                   for b in range(buttons.N_BUTTONS)}
        # The surfaces the finger can rest on: the console's top and each cap's top.
        self.console_geom = geom("console")
        self.cap_geoms = np.array([geom(f"button{b}_cap") for b in range(buttons.N_BUTTONS)])
        # Where qpos sits in a rollout's state vector (time first, then qpos).
        self.qpos_slice = slice(1, 1 + model.nq)
        self.datas = [mujoco.MjData(model) for _ in range(threads)]
        self._scratch = mujoco.MjData(model)

    def check_targets(self, targets):
        """`targets` as an array [movement, 7] of finite joint targets, clipped to the
        joint ranges (ValueError for anything else)."""
        targets = _validate.finite_array("targets", targets)
        if targets.ndim != 2 or targets.shape[1] != len(self.home):
            raise ValueError(f"targets must be an array [movement, {len(self.home)}] "
                             f"of joint targets, got shape {targets.shape}")
        return np.clip(targets, self.lower, self.upper)

    def phases(self, target):
        """The movement to `target` as (joint targets, seconds) pairs, the form the
        button console takes (`press_motions`)."""
        target = self.check_targets(np.asarray(target, dtype=float)[None])[0]
        return ((target, REACH_TIME), (target, HOLD_TIME), (self.home.copy(), RETRACT_TIME))

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
            profile = self._icub.minimum_jerk(np.arange(1, n_updates + 1) / n_updates)
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
          targets: joint targets [movement, 7].
          retract: also simulate the return home. The outcome is measured at the end
            of the hold, so without it (the default) the rollouts stop there, 40% of
            the steps sooner, and "pressed" covers the reach and the hold.

        Returns:
          A dict of arrays: "outcome" [movement, 3] (m), "touched" [movement] (bool),
          "pressed" [movement] (first button pushed past the press depth, -1 for
          none).
        """
        retract = _validate.boolean("retract", retract)
        controls = self.controls(targets)
        if not retract:
            controls = controls[:, :self.outcome_step + 1]
        n = len(controls)
        state, _ = self._rollout.rollout(self.model, self.datas, self.initial_state, controls,
                                         initial_warmstart=self.warmstart)
        qpos = state[:, :, self.qpos_slice]
        outcome = np.empty((n, 3))
        touched = np.zeros(n, dtype=bool)
        for i in range(n):
            outcome[i], touched[i] = self.measure(qpos[i, self.outcome_step])
        # The task reads the buttons after every update (every `substeps` steps).
        depths = -qpos[:, self.substeps - 1::self.substeps][:, :, self.button_qpos]
        return {"outcome": outcome, "touched": touched, "pressed": first_press(depths)}

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

        The outcome is never lower than this: soft contacts let a finger driven hard
        sink a few millimetres into the console, and one swept fast sideways into a
        cap pass into it without pushing it down. Read as a position on the surfaces,
        such a finger is on the console or on an unpressed cap, not in them."""
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
    over = depths > buttons.PRESS_DEPTH
    any_over = over.any(axis=2)
    pressed = np.full(len(depths), -1, dtype=np.int64)
    rows = np.flatnonzero(any_over.any(axis=1))
    if len(rows):
        first_update = np.argmax(any_over[rows], axis=1)
        pressed[rows] = np.argmax(over[rows, first_update], axis=1)
    return pressed
