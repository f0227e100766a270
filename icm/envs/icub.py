"""The simulated iCub's right arm: model files, inverse kinematics, and motion.

Shared by the button and rod scenes. The arm is driven only through its 7 position
actuators: a motion interpolates the actuators' targets along a minimum-jerk profile
and lets the physics track them, so the hand moves as the simulated arm moves, never
by setting its position.
"""


import os

import mujoco
import numpy as np
from dm_control import mujoco as dm_mujoco
from dm_control.rl import control
from dm_control.suite import base
from dm_env import specs

from icm import _exact, _system, _validate
from icm.store import ASSETS, asset_path  # noqa: F401 (part of this module's API)
from icm.envs._common import check_time_limit

ARM_JOINTS = ("r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw", "r_elbow",
              "r_wrist_prosup", "r_wrist_pitch", "r_wrist_yaw")
"""The right arm's joints (and their actuators), in the iCub's order."""

POSTURE = np.deg2rad([-25.0, 20.0, 0.0, 95.0, 0.0, -15.0, 0.0])
"""A comfortable arm posture (radians) that inverse kinematics is drawn towards, so
that it picks natural solutions well inside the joint ranges."""

CONTROL_TIMESTEP = 0.02
"""Seconds between two actions of a continuous task (10 physics steps)."""

SUBSTEPS = 10
"""Physics steps between two updates of the actuator targets during a motion."""



def minimum_jerk(fraction):
    """The minimum-jerk profile 10 s^3 - 15 s^4 + 6 s^5, from 0 at s=0 to 1 at s=1."""
    s = np.clip(_validate.finite_array("fraction", fraction), 0.0, 1.0)
    return s * s * s * (10.0 + s * (-15.0 + 6.0 * s))


class Arm:
    """Index bookkeeping, inverse kinematics and motion for the right arm of a Physics.

    Args:
      physics: a dm_control `mujoco.Physics` of a scene that includes icub.xml.
    """

    def __init__(self, physics):
        self.physics = _validate.instance("physics", physics, dm_mujoco.Physics,
                                          "a dm_control Physics of an icm scene")
        model = physics.model
        self.model_ptr, self.data_ptr = model.ptr, physics.data.ptr
        joint_ids = [model.name2id(j, "joint") for j in ARM_JOINTS]
        self.qpos_index = np.array([model.jnt_qposadr[i] for i in joint_ids])
        self.dof_index = np.array([model.jnt_dofadr[i] for i in joint_ids])
        self.actuator_index = np.array([model.name2id(j, "actuator") for j in ARM_JOINTS])
        self.lower, self.upper = model.jnt_range[joint_ids].T.copy()
        self.site_id = model.name2id("fingertip", "site")

    def joint_positions(self):
        """The arm's 7 joint angles (radians)."""
        return self.physics.data.qpos[self.qpos_index].copy()

    def fingertip(self):
        """The fingertip's position in the world (metres)."""
        return self.physics.data.site_xpos[self.site_id].copy()

    def solve(self, target, start=None, posture=POSTURE, pointing=None, tolerance=1e-4,
              iterations=600):
        """Joint angles, within the joint ranges, that put the fingertip at `target`.

        Damped least squares on the fingertip's position Jacobian, each step clamped to
        the joint ranges. Two secondary goals act in the null space of the position
        task, for the first half of the iterations only: turning the finger towards
        `pointing` and drawing the arm towards `posture`. The second half converges on
        the target alone. The physics state is left as it was.

        Args:
          target: (3,) world position for the fingertip.
          start: joint angles to start from (default: `posture`).
          posture: joint angles the solution is drawn towards.
          pointing: optional (3,) world direction for the finger (from the wrist to the
            fingertip), e.g. (0, 0, -1) to press down; None leaves it free.
          tolerance: accepted distance to the target, in metres.
          iterations: maximum number of steps.

        Returns:
          (7,) joint angles in radians.

        Raises:
          RuntimeError: if the target is out of reach within the joint ranges.
        """
        target = _validate.finite_array("target", target, shape=(3,))
        posture = self.check_joints("posture", posture)
        start = posture if start is None else self.check_joints("start", start)
        tolerance = _validate.positive("tolerance", tolerance)
        iterations = _validate.integer_at_least("iterations", iterations, 2)
        if pointing is not None:
            pointing = _validate.finite_array("pointing", pointing, shape=(3,))
            if not _exact.norm(pointing) > 0:
                raise ValueError(f"pointing must be a non-zero direction, got {pointing!r}")
            pointing = pointing / _exact.norm(pointing)
        model, data = self.physics.model, self.physics.data
        saved_qpos = data.qpos.copy()
        q = np.clip(start, self.lower, self.upper)
        jac_pos, jac_rot = np.zeros((3, model.nv)), np.zeros((3, model.nv))
        damping = 1e-4
        try:
            for iteration in range(iterations):
                data.qpos[self.qpos_index] = q
                mujoco.mj_kinematics(model.ptr, data.ptr)
                mujoco.mj_comPos(model.ptr, data.ptr)
                error = target - data.site_xpos[self.site_id]
                settling = iteration >= iterations // 2
                if settling and _exact.norm(error) < tolerance:
                    return q
                mujoco.mj_jacSite(model.ptr, data.ptr, jac_pos, jac_rot, self.site_id)
                jac = jac_pos[:, self.dof_index]
                # A damped pseudo-inverse, jac' (jac jac' + damping I)^-1, by _exact's
                # products and solve: every machine finds the same posture.
                inverse = _exact.solve(_exact.matmul(jac, jac.T) + damping * np.eye(3), jac).T
                step = _exact.matvec(inverse, error)
                secondary = np.zeros(len(q))
                if not settling:
                    secondary += 0.1 * (posture - q)
                    if pointing is not None:
                        finger = -data.site_xmat[self.site_id].reshape(3, 3)[:, 2]
                        secondary += 0.5 * _exact.matvec(jac_rot[:, self.dof_index].T,
                                                         np.cross(finger, pointing))
                step += _exact.matvec(np.eye(len(q)) - _exact.matmul(inverse, jac), secondary)
                scale = min(1.0, 0.2 / (np.abs(step).max() + 1e-12))
                q = np.clip(q + scale * step, self.lower, self.upper)
            raise RuntimeError(f"fingertip target {np.round(target, 3).tolist()} is out of "
                               f"reach (remaining error {_exact.norm(error):.4f} m)")
        finally:
            data.qpos[:] = saved_qpos
            mujoco.mj_kinematics(model.ptr, data.ptr)

    def check_joints(self, name, q):
        """`q` as 7 finite joint angles (radians), else raises ValueError naming `name`."""
        return _validate.finite_array(name, q, shape=(len(ARM_JOINTS),))

    def finger_direction(self, q):
        """The unit vector from the wrist towards the fingertip at joint angles `q`."""
        q = self.check_joints("q", q)
        model, data = self.physics.model, self.physics.data
        saved_qpos = data.qpos.copy()
        data.qpos[self.qpos_index] = q
        mujoco.mj_kinematics(model.ptr, data.ptr)
        direction = -data.site_xmat[self.site_id].reshape(3, 3)[:, 2].copy()
        data.qpos[:] = saved_qpos
        mujoco.mj_kinematics(model.ptr, data.ptr)
        return direction

    def place(self, q):
        """Puts the arm at rest at joint angles `q` with its actuators holding them (for
        the initial state of an episode only; motions go through `move`)."""
        q = self.check_joints("q", q)
        data = self.physics.data
        data.qpos[self.qpos_index] = q
        data.qvel[self.dof_index] = 0.0
        data.ctrl[self.actuator_index] = q

    def move(self, q_target, duration, monitor=None):
        """Moves the arm to joint angles `q_target` in `duration` seconds.

        The actuators' targets follow a minimum-jerk profile from the current targets
        to `q_target`; the physics runs `SUBSTEPS` steps between updates.

        Args:
          q_target: (7,) joint angles (clipped to the joint ranges).
          duration: seconds of simulated time (rounded to whole updates).
          monitor: optional function called after every update; if it returns True
            the motion stops early.

        Returns:
          True if `monitor` stopped the motion, else False.
        """
        goal = np.clip(self.check_joints("q_target", q_target), self.lower, self.upper)
        n_updates = self.n_updates(duration)
        _validate.function("monitor", monitor)
        data = self.physics.data
        ctrl, index = data.ctrl, self.actuator_index
        start = ctrl[index].copy()
        profile = minimum_jerk(np.arange(1, n_updates + 1) / n_updates)
        targets = start + np.outer(profile, goal - start)  # one row per update
        model_ptr, data_ptr = self.model_ptr, self.data_ptr
        for row in targets:
            ctrl[index] = row
            mujoco.mj_step(model_ptr, data_ptr, SUBSTEPS)
            if monitor is not None and monitor():
                return True
        return False

    def n_updates(self, duration):
        """How many updates of the actuators' targets a motion of `duration` seconds
        (> 0) makes: one every `SUBSTEPS` physics steps, at least one."""
        duration = _validate.positive("duration", duration)
        return max(1, int(round(duration / (self.physics.model.opt.timestep * SUBSTEPS))))

    def hold(self, duration, monitor=None):
        """Keeps the current targets for `duration` seconds (see `move`)."""
        return self.move(self.physics.data.ctrl[self.actuator_index].copy(), duration, monitor)


def describe_arm(physics):
    """A Markdown table of the right arm's joints: order, range and actuator gain."""
    lines = ["| # | joint | range (degrees) | actuator gain kp (N m / rad) |",
             "|---|---|---|---|"]
    for i, name in enumerate(ARM_JOINTS, start=1):
        low, high = np.rad2deg(physics.named.model.jnt_range[name])
        kp = physics.named.model.actuator_gainprm[name][0]
        lines.append(f"| {i} | {name} | {low:.1f} to {high:.1f} | {kp:g} |")
    return "\n".join(lines)


def body_dimensions(physics):
    """The robot's dimensions that the book names, read from the model: a dict with
    "torso_lean" (the torso's fixed forward lean, degrees), "upper_arm" and "forearm"
    (the right arm's lengths, metres: shoulder to elbow, elbow to wrist), and
    "arm_joints" (the right arm's joints)."""
    model = physics.model
    w, _, y, _ = model.body("torso").quat  # a rotation about the y axis alone
    return {"torso_lean": float(np.rad2deg(2 * np.arctan2(y, w))),
            "upper_arm": float(np.linalg.norm(model.body("r_forearm").pos)),
            "forearm": float(np.linalg.norm(model.body("r_hand").pos)),
            "arm_joints": len(ARM_JOINTS)}


_COMPILED = {}
"""{path: ((its modification time, size), its compiled model)}: `_compiled_scene`'s."""


def _compiled_scene(path):
    """The model compiled from the MJCF file `path`, compiled once per process (until the
    file changes). Callers get a copy each (`MjModel.copy`, MuJoCo's mj_copyModel: the
    same numbers as compiling again), since a physics may change its model (the
    buttons' lights change the caps' materials). A new physics of the buttons took 12.7
    ms, 8 of them compiling the XML, and 4.7 ms from the compiled model (measured
    2026-12-03); the goal-babbling runs build hundreds."""
    stat = os.stat(path)
    key = (stat.st_mtime_ns, stat.st_size)
    cached = _COMPILED.get(path)
    if cached is None or cached[0] != key:
        cached = _COMPILED[path] = (key, dm_mujoco.wrapper.MjModel.from_xml_path(path))
    return cached[1]


class ArmPhysics(dm_mujoco.Physics):
    """A dm_control Physics of a scene with the iCub: accessors for its right arm."""

    @classmethod
    def from_scene(cls, scene):
        """A fresh physics of the MJCF file `scene` of `assets/`.

        Raises:
          RuntimeError: when the simulation cannot be built because the system lacks
            Mesa's EGL (dm_control loads its renderer as it builds a physics), with
            the command that installs it.
        """
        try:
            return cls.from_model(_compiled_scene(str(asset_path(scene))).copy())
        except (AttributeError, ImportError, RuntimeError) as error:
            problem = _system.missing_rendering() \
                if os.environ.get("MUJOCO_GL", "egl") == "egl" else None
            if problem is None:
                raise
            raise RuntimeError(f"the simulated iCub cannot be built: {problem}") from error

    def fingertip_position(self):
        """The fingertip site's world position (metres)."""
        return self.named.data.site_xpos["fingertip"].copy()

    def arm_joint_positions(self):
        """The 7 right-arm joint angles (radians), in the iCub's order."""
        return self.named.data.qpos[list(ARM_JOINTS)].copy()


class ArmTask(base.Task):
    """A dm_control task whose action is the 7 right-arm joint targets (radians),
    tracked by the arm's position actuators."""

    MOTIONS = None
    """The class of the scene's postures (e.g. `ButtonMotions`), set by each task."""

    def motions(self, physics):
        """The scene's postures (`shared_motions`: computed once per scene and process)."""
        return shared_motions(self.MOTIONS, physics)

    def before_step(self, action, physics):
        lower, upper = physics.named.model.actuator_ctrlrange[list(ARM_JOINTS)].T
        physics.named.data.ctrl[list(ARM_JOINTS)] = check_arm_action(action, lower, upper)

    def action_spec(self, physics):
        lower, upper = physics.named.model.actuator_ctrlrange[list(ARM_JOINTS)].T
        return specs.BoundedArray((len(ARM_JOINTS),), np.float64, lower, upper,
                                  name="arm_joint_targets")

    @staticmethod
    def arm_observation_spec():
        """Specs of the arm's observations: joint angles and fingertip position."""
        return {"arm_joints": specs.Array((len(ARM_JOINTS),), np.float64, name="arm_joints"),
                "fingertip": specs.Array((3,), np.float64, name="fingertip")}


ACTION_TOLERANCE = 1e-6
"""How far (radians) an arm action may stray outside the action spec and still be
accepted (and clipped): rounding, not a different command."""


def check_arm_action(action, lower, upper):
    """The 7 joint targets of a continuous action, checked and clipped to [lower, upper].

    Raises:
      ValueError: for an action that is not 7 finite numbers, or a target outside its
        joint's range (by more than `ACTION_TOLERANCE`), naming the joint.
    """
    targets = _validate.finite_array("action", action, shape=(len(ARM_JOINTS),))
    outside = (targets < lower - ACTION_TOLERANCE) | (targets > upper + ACTION_TOLERANCE)
    if outside.any():
        j = int(np.flatnonzero(outside)[0])
        raise ValueError(f"action[{j}], the {ARM_JOINTS[j]} target, must be within the "
                         f"action spec [{lower[j]:.4f}, {upper[j]:.4f}] rad, got "
                         f"{targets[j]!r}")
    return np.clip(targets, lower, upper)


def continuous_environment(physics, task, time_limit):
    """A dm_control `control.Environment` for an arm task: one action every
    `CONTROL_TIMESTEP` seconds, episodes of `time_limit` seconds (> 0; infinity for
    no limit)."""
    time_limit = check_time_limit(time_limit)
    return control.Environment(physics, task, time_limit=time_limit,
                               control_timestep=CONTROL_TIMESTEP)


_MOTIONS = {}


def shared_motions(kind, physics):
    """The postures `kind(physics)` computes (inverse kinematics, once per scene and
    process): every environment of a scene shares them, their arrays read-only.

    Args:
      kind: a class whose instances hold postures of a scene (e.g. `ButtonMotions`).
      physics: a physics of that scene; its model must be the scene's, unchanged.
    """
    key = (kind, physics.model.nq, physics.model.nbody, physics.model.ngeom,
           physics.model.body_pos.tobytes(), physics.model.geom_size.tobytes())
    if key not in _MOTIONS:
        scratch = physics.copy(share_model=True)
        with scratch.reset_context():  # the scene at rest, whatever state `physics` is in
            pass
        motions = kind(scratch)
        for value in vars(motions).values():
            for array in (value.values() if isinstance(value, dict) else
                          value if isinstance(value, list) else [value]):
                if isinstance(array, np.ndarray):
                    array.flags.writeable = False
        _MOTIONS[key] = motions
    return _MOTIONS[key]
