"""The button experiment on the simulated iCub.

`ButtonsPhysics` (the MJCF scene assets/buttons.xml with named accessors), `ButtonsTask`
(a continuous dm_control task: the action is the 7 arm joint targets; a button pressed
past `PRESS_DEPTH` opens the lid of its light's colour), `load_continuous`, and
`PhysicsButtonConsole`, the paper's discrete actions as motor primitives on top of the
same task; `PhysicsButtonConsoleBatch` runs one console per row for the batched
learners. With `noisy_button=True` the scene is assets/buttons_noisy.xml: the same
console plus a sixth button (action 5, `NOISY_BUTTON`), pressed by contact like the
others, whose outcome the task draws from its random state (`rules.noisy_effect`).
"""

import collections
import functools

import mujoco
import numpy as np
from dm_env import specs

from icm import _validate
from icm.envs import icub
from icm.envs._common import check_discrete_action, check_seed, dm_control_random
from icm.envs.buttons.rules import (ALL_EFFECTS, BOX_NAMES, DEFAULT_PRESSES_PER_TRIAL,
                                        DEFAULT_RED_BUTTON, GREEN, GREEN_BOX,
                                        N_BUTTONS, NOISY_BUTTON, OFF, RED, RED_BOX,
                                        check_lights, check_red_button,
                                        check_rewarded_box, draw_green, effect_index,
                                        extrinsic_reward, green_candidates, lights_for,
                                        n_actions, noisy_effect)
from icm.envs.buttons.twin import ButtonTrials

PRESS_DEPTH = 0.008
"""A press counts when a button's slide joint goes deeper than this (metres; the
buttons travel 15 mm)."""
LID_OPEN_ANGLE = np.deg2rad(100.0)
"""Where the task drives a lid that opens."""
BOX_OPEN_ANGLE = np.deg2rad(30.0)
"""A box counts as open in the observations when its lid is open at least this much."""
LID_OPEN_TIME = 2.0
"""Seconds a lid stays open in the continuous task before the task shuts it again."""
_LIGHT_MATERIALS = {OFF: "light_off", RED: "red", GREEN: "green"}
_BUTTON_JOINTS = [f"button{b}" for b in range(N_BUTTONS + 1)]  # button5: the noisy one
_LIDS = [f"{name}_lid" for name in BOX_NAMES]


class ButtonsPhysics(icub.ArmPhysics):
    """The button scene (assets/buttons.xml) with named accessors.

    The accessors that the press primitive calls every 20 ms of simulated time use
    indices looked up once from the names, which keeps the primitive's cost close to
    that of the physics steps themselves.
    """

    def _indices(self):
        """Looks the names up once (again if the model changed); also keeps the raw
        MuJoCo data (`raw`), whose arrays are quicker to read than dm_control's."""
        if getattr(self, "_cached_model", None) is not self.model.ptr:
            model = self.model
            joint = lambda name: model.jnt_qposadr[model.name2id(name, "joint")]
            present = [name for name in _BUTTON_JOINTS  # button5 only with the noisy button
                       if mujoco.mj_name2id(model.ptr, mujoco.mjtObj.mjOBJ_JOINT, name) >= 0]
            self._button_qpos = np.array([joint(name) for name in present])
            self._lid_qpos = np.array([joint(name) for name in _LIDS])
            self._lid_ctrl = np.array([model.name2id(name, "actuator") for name in _LIDS])
            self._cached_model = model.ptr
        if getattr(self, "_raw_data", None) is not self.data.ptr:
            self._raw_data = self.data.ptr
        return self

    @property
    def n_buttons(self):
        """Buttons in the scene: 5, or 6 with the noisy button."""
        return len(self._indices()._button_qpos)

    def button_depths(self):
        """How far each button is pushed in (metres, 0 at rest), shape (n_buttons,).

        The depth is 0.0 minus the joint's position, not its negation: a button at
        rest (position 0.0) then reads 0.0, where -0.0 would print as "-0." in an
        observation."""
        return 0.0 - self.data.qpos[self._indices()._button_qpos]

    def button_depth(self, button):
        """How far button `button` (0-4, or 5 the noisy one) is pushed in, in metres."""
        button = _validate.integer("button", button, 0, self.n_buttons - 1)
        return 0.0 - float(self.named.data.qpos[_BUTTON_JOINTS[button]][0])

    def lid_angles(self):
        """The red and green lids' opening angles (radians), shape (2,)."""
        return self.data.qpos[self._indices()._lid_qpos]

    def boxes_open(self):
        """The `boxes` observation read from the lids: 1 where a lid is open >= 30 deg."""
        return (self.lid_angles() >= BOX_OPEN_ANGLE).astype(np.int64)

    def set_lid_targets(self, red, green):
        """Commands the lid actuators (radians)."""
        self._set_lid_targets(_validate.real("red", red), _validate.real("green", green))

    def _set_lid_targets(self, red, green):
        ctrl = self.data.ctrl
        index = self._indices()._lid_ctrl
        ctrl[index[0]], ctrl[index[1]] = red, green

    def set_lights(self, lights):
        """Lights the button caps: 0 off, 1 red, 2 green (changes their material)."""
        for b, light in enumerate(check_lights(lights)):
            self.named.model.geom_matid[f"button{b}_cap"] = self.model.name2id(
                _LIGHT_MATERIALS[int(light)], "material")


def load_physics(noisy_button=False):
    """A fresh `ButtonsPhysics` of assets/buttons.xml (or, with `noisy_button`, of
    assets/buttons_noisy.xml: the same scene plus the noisy button)."""
    scene = "buttons_noisy.xml" if _validate.boolean("noisy_button", noisy_button) \
        else "buttons.xml"
    return ButtonsPhysics.from_scene(scene)


class ButtonMotions:
    """The arm postures of the press primitive, from inverse kinematics on the model
    (solved once per posture, not per physics step).

    home: the hand resting above the table, in front of the console; above[b]: the
    fingertip 6 cm above button b's cap; down[b]: the fingertip 2.5 cm below the cap's
    top (the button stops it before: the push is what moves the button).
    """

    HOME = (0.26, -0.17, 0.60)
    ABOVE = 0.06
    DOWN = -0.025

    def __init__(self, physics):
        arm = icub.Arm(physics)
        self.home = arm.solve(self.HOME)
        self.above, self.down = [], []
        for b in range(physics.n_buttons):
            cap = physics.named.data.geom_xpos[f"button{b}_cap"].copy()
            top = cap[2] + physics.named.model.geom_size[f"button{b}_cap"][1]
            self.above.append(arm.solve([cap[0], cap[1], top + self.ABOVE], start=self.home))
            self.down.append(arm.solve([cap[0], cap[1], top + self.DOWN], start=self.above[b]))


class ButtonsTask(icub.ArmTask):
    """The button experiment as a continuous dm_control task.

    Action: target angles of the 7 right-arm joints (radians), tracked by the position
    actuators. Each episode lights one red and one green button (the red one fixed,
    the green one drawn from the task's generator) and starts with the arm at home,
    buttons up and lids shut. After every physics update the task checks the buttons:
    one pushed deeper than `PRESS_DEPTH` opens the lid of its light's colour, which
    shuts again `lid_open_time` seconds later. Reward 0.0, or 1.0 while `rewarded_box`
    is open.

    With `noisy_button`, the scene has a sixth button (5), never lit: a press of it
    (detected the same way) draws one number u from the task's generator and opens the
    red box (u < 1/3), the green box (u < 2/3) or nothing (`rules.noisy_effect`), as
    `ButtonConsole` does; the physics must be `load_physics(noisy_button=True)`.

    Args:
      red_button: index of the red button (default 2).
      rewarded_box: None, "red" or "green".
      lid_open_time: seconds a lid stays open (> 0).
      noisy_button: the scene has the noisy button (default False).
      random: None, an integer >= 0 or a `numpy.random.Generator`: draws the layouts,
        one number per episode, and the noisy button's outcomes, one per press, as
        `ButtonConsole` does.
    """

    MOTIONS = ButtonMotions

    def __init__(self, red_button=DEFAULT_RED_BUTTON, rewarded_box=None,
                 lid_open_time=LID_OPEN_TIME, noisy_button=False, random=None):
        self.generator = check_seed(random, "random")
        super().__init__(random=dm_control_random(self.generator))
        self.red_button = check_red_button(red_button)
        self.rewarded_box = check_rewarded_box(rewarded_box)
        self.lid_open_time = _validate.positive("lid_open_time", lid_open_time)
        self.noisy_button = _validate.boolean("noisy_button", noisy_button)
        self.n_buttons = n_actions(self.noisy_button)
        self.lights = None
        self.press_log = []
        self.deepest = np.zeros(self.n_buttons)
        self._down = np.zeros(self.n_buttons, dtype=bool)
        self._lid_opened_at = [None, None]
        self._lid_targets = (0.0, 0.0)

    def initialize_episode(self, physics):
        if physics.n_buttons != self.n_buttons:
            raise ValueError(f"the task has {self.n_buttons} buttons (noisy_button="
                             f"{self.noisy_button}) but the scene {physics.n_buttons}")
        green = draw_green(self.generator, self.red_button)
        self.lights = lights_for(self.red_button, green)
        physics.set_lights(self.lights)
        physics.data.qpos[physics._indices()._button_qpos] = 0.0
        physics.named.data.qpos[_LIDS] = 0.0
        physics._set_lid_targets(0.0, 0.0)
        self._lid_targets = (0.0, 0.0)
        icub.Arm(physics).place(self.motions(physics).home)
        self._down[:] = False
        self._lid_opened_at = [None, None]
        self.clear_log()

    def clear_log(self):
        """Forgets the presses and depths seen so far (`press_log`, `deepest`)."""
        self.press_log = []
        self.deepest = np.zeros(self.n_buttons)

    def after_step(self, physics):
        self.update(physics)

    def update(self, physics):
        """Detects new presses and opens or shuts the lids (called after physics steps,
        at every update of the arm's targets: kept to a few array operations)."""
        indices = physics._indices()
        raw = indices._raw_data
        depths = -raw.qpos.take(indices._button_qpos)
        np.maximum(self.deepest, depths, out=self.deepest)
        now = raw.time
        # Most updates see no button past the press depth and none held down: then
        # nothing below changes (a shortcut for speed, the same outcome).
        if depths.max() > PRESS_DEPTH or self._down.any():
            self._detect_presses(depths, now)
        opened = self._lid_opened_at
        if opened[0] is None and opened[1] is None:
            targets = (0.0, 0.0)
        else:
            targets = tuple(LID_OPEN_ANGLE if at is not None and now - at < self.lid_open_time
                            else 0.0 for at in opened)
        if targets != self._lid_targets:
            physics._set_lid_targets(*targets)
            self._lid_targets = targets

    def _detect_presses(self, depths, now):
        """Logs the buttons that went down past the press depth since the last update
        and opens the lid of a lit one; a button counts again once it has risen back
        above half the depth."""
        pressed = depths > PRESS_DEPTH
        new = pressed & ~self._down
        if new.any():
            for b in np.flatnonzero(new):
                self.press_log.append(int(b))
                if b == NOISY_BUTTON:  # its outcome: one draw from the task's generator
                    effect = noisy_effect(self.generator.random())
                    box = {RED_BOX: 0, GREEN_BOX: 1}.get(effect)
                else:
                    light = self.lights[b]
                    box = None if light == OFF else 0 if light == RED else 1
                if box is not None:
                    self._lid_opened_at[box] = now
            self._down |= pressed
        if self._down.any():
            self._down &= depths >= PRESS_DEPTH / 2

    def shut_lids(self, physics):
        """Commands both lids shut now (the discrete layer does this before a press)."""
        self._lid_opened_at = [None, None]
        physics._set_lid_targets(0.0, 0.0)
        self._lid_targets = (0.0, 0.0)

    def observation_spec(self, physics):
        return collections.OrderedDict(
            **self.arm_observation_spec(),
            button_depths=specs.Array((self.n_buttons,), np.float64, name="button_depths"),
            lights=specs.BoundedArray((N_BUTTONS,), np.float64, OFF, GREEN, name="lights"),
            lid_angles=specs.Array((2,), np.float64, name="lid_angles"),
        )

    def get_observation(self, physics):
        return collections.OrderedDict(
            arm_joints=physics.arm_joint_positions(),
            fingertip=physics.fingertip_position(),
            button_depths=physics.button_depths(),
            lights=self.lights.astype(np.float64),
            lid_angles=physics.lid_angles(),
        )

    def get_reward(self, physics):
        return extrinsic_reward(physics.boxes_open(), self.rewarded_box)


def load_continuous(seed=None, time_limit=10.0, **task_kwargs):
    """The continuous button task: a dm_control `control.Environment`.

    Args:
      seed: None, an integer >= 0 or a `numpy.random.Generator` (the layouts, and the
        noisy button's outcomes).
      time_limit: seconds per episode (> 0; float('inf') for no limit).
      **task_kwargs: `ButtonsTask` arguments (red_button, rewarded_box, lid_open_time,
        noisy_button).
    """
    task = ButtonsTask(random=check_seed(seed), **task_kwargs)
    return icub.continuous_environment(load_physics(task.noisy_button), task, time_limit)


MAX_PHASE_SECONDS = 10.0
"""The longest phase of a press motion (`press_motions`), in simulated seconds: the
scripted press lasts 1.6 s in all, a formed movement 0.9 s. It bounds the time and
memory a press can take."""


@functools.lru_cache(maxsize=1)
def arm_ranges():
    """The arm joints' ranges in the button scene, (lower (7,), upper (7,)) radians."""
    arm = icub.Arm(load_physics())
    return arm.lower.copy(), arm.upper.copy()


def check_press_motions(press_motions):
    """`press_motions` checked: None, or for each of the `N_BUTTONS` buttons a non-empty
    sequence of (joint targets, seconds) pairs, returned as tuples of read-only (7,)
    arrays and floats. Joint targets must lie within the joints' ranges (up to
    `icub.ACTION_TOLERANCE`, then clipped), seconds in (0, `MAX_PHASE_SECONDS`].

    Raises:
      ValueError: for anything else, naming the button and the step
        (`ArgumentTypeError` for what is not a number).
    """
    if press_motions is None:
        return None
    if isinstance(press_motions, (str, bytes)) or not hasattr(press_motions, "__len__") \
            or len(press_motions) != N_BUTTONS:
        raise ValueError(f"press_motions must be None or one motion per button "
                         f"({N_BUTTONS}), got {_validate.show(press_motions)}")
    lower, upper = arm_ranges()
    checked = []
    for button, motion in enumerate(press_motions):
        if isinstance(motion, (str, bytes)) or not hasattr(motion, "__len__") or not motion:
            raise ValueError(f"press_motions[{button}] must be a non-empty sequence of "
                             f"(joint targets, seconds) pairs, got {_validate.show(motion)}")
        steps = []
        for i, step in enumerate(motion):
            if not isinstance(step, (list, tuple)) or len(step) != 2:
                raise ValueError(f"press_motions[{button}][{i}] must be a (joint targets, "
                                 f"seconds) pair, got {_validate.show(step)}")
            name = f"press_motions[{button}][{i}] joint targets"
            target = _validate.finite_array(name, step[0], shape=(len(icub.ARM_JOINTS),))
            outside = (target < lower - icub.ACTION_TOLERANCE) \
                | (target > upper + icub.ACTION_TOLERANCE)
            if outside.any():
                j = int(np.flatnonzero(outside)[0])
                raise ValueError(f"{name} must lie within the joints' ranges: joint {j} "
                                 f"({icub.ARM_JOINTS[j]}) in [{lower[j]:.4f}, "
                                 f"{upper[j]:.4f}] rad, got {target[j]!r}")
            target = np.clip(target, lower, upper)
            target.flags.writeable = False
            seconds = _validate.real(f"press_motions[{button}][{i}] seconds", step[1], 0.0,
                                     MAX_PHASE_SECONDS, low_open=True)
            steps.append((target, seconds))
        checked.append(tuple(steps))
    return tuple(checked)


class PhysicsButtonConsole(ButtonTrials):
    """The paper's button experiment on the simulated iCub, with discrete actions.

    Same action spec, observation spec and episode rules (`ButtonTrials`) as
    `ButtonConsole`. An action is a motor primitive: the lids are shut (and the arm
    waits until they are), the arm reaches above the button, pushes down through it,
    lifts and returns home, every posture a target that the position actuators track,
    updated every 20 ms while MuJoCo steps in C in between. The `ButtonsTask` watches
    the buttons at every update: a button pushed past `PRESS_DEPTH` opens the lid of
    its colour. The observation is taken once the motion is over and, if a lid was
    opened, once it is open at least 30 degrees: `boxes` is read from the lids.

    With `noisy_button`, action 5 presses the noisy button on its stand (scene
    assets/buttons_noisy.xml); the task draws its outcome from the same generator as
    the layouts, in the same order as `ButtonConsole`, so the twins stay in step.

    Args:
      red_button, presses_per_trial, rewarded_box, noisy_button, seed: as
        `ButtonConsole`.
      press_motions: None for the scripted primitive (default), or the movement that
        presses each of the five buttons instead: one sequence per button of (joint
        targets (7,), seconds) pairs, each a minimum-jerk motion of the arm
        (`icub.Arm.move`), e.g. movements the robot formed itself
        (`icm.experiments.run_goal_babbling`); the noisy button keeps the scripted
        press.

    Attributes:
      physics: the `ButtonsPhysics`, to inspect or render.
      task: the `ButtonsTask`.
    """

    REACH_TIME, PUSH_TIME, HOLD_TIME, LIFT_TIME, RETURN_TIME = 0.45, 0.3, 0.15, 0.25, 0.45
    """Durations (seconds) of the primitive's phases."""
    LID_WAIT = 1.5
    """Longest wait (seconds) for a lid to open or shut."""
    LID_SHUT_ANGLE = np.deg2rad(3.0)
    """A lid counts as shut, before a press, below this angle (radians)."""

    def __init__(self, red_button=DEFAULT_RED_BUTTON,
                 presses_per_trial=DEFAULT_PRESSES_PER_TRIAL, rewarded_box=None,
                 noisy_button=False, seed=None, press_motions=None):
        self.press_motions = check_press_motions(press_motions)
        self.task = ButtonsTask(red_button=red_button, rewarded_box=rewarded_box,
                                noisy_button=noisy_button, random=check_seed(seed))
        self.red_button = self.task.red_button
        super().__init__(presses_per_trial, rewarded_box, noisy_button)
        self.physics = load_physics(self.noisy_button)
        self.arm = icub.Arm(self.physics)
        self.motions = self.task.motions(self.physics)

    def reseed(self, seed):
        """Restarts the layouts' random generator from `seed` (None, an integer >= 0 or
        a Generator); the next step starts a new trial."""
        self.task.generator = check_seed(seed)
        self._reset_next_step = True

    def _new_trial(self):
        """Resets the physics: a new layout, arm at home, buttons up, lids shut."""
        with self.physics.reset_context():
            self.task.initialize_episode(self.physics)
        return self.task.lights.copy()

    def _press(self, button):
        return self.press(button)

    def press(self, button, recorder=None):
        """Runs the press primitive on `button`; returns the boxes seen after it.

        Args:
          button: index of the button (0-4, or 5 with the noisy button).
          recorder: optional function of the physics, called after every update of
            the actuators' targets (every 20 ms of simulated time), e.g. to record a
            time series or render frames.

        Raises:
          ValueError: if `button` is not a button index or `recorder` not a function.
        """
        button = check_discrete_action(button, self.n_actions, "button")
        _validate.function("recorder", recorder)
        physics, task, motions, arm = self.physics, self.task, self.motions, self.arm
        lids = physics._indices()._lid_qpos
        qpos = physics.data.qpos
        shut = self.LID_SHUT_ANGLE
        task.shut_lids(physics)
        if qpos[lids[0]] >= shut or qpos[lids[1]] >= shut:
            arm.hold(self.LID_WAIT, monitor=lambda: task.update(physics)
                     or (qpos[lids[0]] < shut and qpos[lids[1]] < shut))
        task.clear_log()
        opened_before = list(task._lid_opened_at)

        if recorder is None:
            watch = lambda: task.update(physics)  # returns None: never stops the motion
        else:
            def watch():
                task.update(physics)
                recorder(physics)

        if self.press_motions is None or button >= N_BUTTONS:  # scripted
            arm.move(motions.above[button], self.REACH_TIME, watch)
            arm.move(motions.down[button], self.PUSH_TIME, watch)
            arm.hold(self.HOLD_TIME, watch)
            arm.move(motions.above[button], self.LIFT_TIME, watch)
            arm.move(motions.home, self.RETURN_TIME, watch)
        else:
            for target, duration in self.press_motions[button]:
                arm.move(target, duration, watch)
        opened = [before is None and after is not None
                  for before, after in zip(opened_before, task._lid_opened_at)]
        waiting = [lids[i] for i in range(2) if opened[i]]
        lid_open = lambda: all(qpos[i] >= BOX_OPEN_ANGLE for i in waiting)
        if not lid_open():
            arm.hold(self.LID_WAIT, monitor=lambda: watch() or lid_open())
        return physics.boxes_open()


class PhysicsButtonConsoleBatch:
    """One simulated console per row, with the interface of `ButtonConsoleBatch`, for
    running the batched learners on the physics (row k is
    `PhysicsButtonConsole(seed=seeds[k])`, stepped one row after the other).

    Args:
      seeds: one integer seed per row.
      red_button: the button that is always red.
      presses_per_trial: presses in a trial (the consoles' own episode length).
      noisy_button: add the noisy button, action 5.
      press_motions: None (the scripted presses), or one `press_motions` of
        `PhysicsButtonConsole` per row.

    Attributes:
      effects: the effects a press can have, `ALL_EFFECTS`: on the physics, both boxes
        too, which the scripted presses never give but other movements can.
    """

    def __init__(self, seeds, red_button=DEFAULT_RED_BUTTON,
                 presses_per_trial=DEFAULT_PRESSES_PER_TRIAL, noisy_button=False,
                 press_motions=None):
        seeds = list(seeds)
        if press_motions is None:
            press_motions = [None] * len(seeds)
        elif not isinstance(press_motions, (list, tuple)) or len(press_motions) != len(seeds):
            raise ValueError(f"press_motions must be None or one entry per row "
                             f"({len(seeds)}), got {_validate.show(press_motions)}")
        self.consoles = [PhysicsButtonConsole(red_button=red_button,
                                              presses_per_trial=presses_per_trial,
                                              noisy_button=noisy_button, seed=s,
                                              press_motions=motions)
                         for s, motions in zip(seeds, press_motions)]
        self.red_button = check_red_button(red_button)
        self.noisy_button = _validate.boolean("noisy_button", noisy_button)
        self.n_actions = n_actions(self.noisy_button)
        self._greens = green_candidates(self.red_button)
        self.layout = np.zeros(len(self.consoles), dtype=np.int64)
        self.effects = ALL_EFFECTS

    def __len__(self):
        return len(self.consoles)

    def new_trials(self):
        """Resets every console; returns the layout indices [rows]."""
        self.layout = np.array([self._greens.index(int(np.flatnonzero(
            c.reset().observation["lights"] == GREEN)[0])) for c in self.consoles])
        return self.layout

    def press(self, actions):
        """Runs the press primitive of `actions[k]` on console k; returns the effect
        indices [rows] into `effects`, read from the lids (whatever they show: a
        press that pushes the red and the green button at once opens both boxes)."""
        return np.array([effect_index(c.step(int(a)).observation["boxes"])
                         for c, a in zip(self.consoles, actions)])
