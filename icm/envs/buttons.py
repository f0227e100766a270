"""The button experiment of the paper (section 2.1): five lit buttons and two boxes.

A console carries 5 buttons. In every trial one button is lit red and one green; the
red one is always at the same place, the green one is drawn at random among the other
four at the start of each trial. Pressing the lit red button opens the red box, the lit
green one the green box, an unlit one nothing. Boxes close again before the next press,
so every press starts from "no box open".

This module holds:

- the rules (`draw_green`, `press_outcome`, `layouts`),
- the fast tabular environment `ButtonConsole`, which applies the rules directly,
- the simulated iCub: `ButtonsPhysics` (the MJCF scene assets/buttons.xml with named
  accessors), `ButtonsTask` (a continuous dm_control task: the action is the 7 arm
  joint targets; a button pressed past `PRESS_DEPTH` opens the lid of its light's
  colour), `load_continuous`, and `PhysicsButtonConsole`, the paper's discrete actions
  as motor primitives on top of the same task.
"""

import collections

import dm_env
import numpy as np
from dm_env import specs

from icm import _validate
from icm.envs import icub
from icm.envs._common import check_discrete_action, check_seed, dm_control_random

N_BUTTONS = 5
OFF, RED, GREEN = 0, 1, 2
"""Values of a button's light in the `lights` observation."""
BOX_NAMES = ("red", "green")
"""Order of the boxes in the `boxes` observation."""

DEFAULT_RED_BUTTON = 2
"""The red button sits in the middle of the console, straight in front of the robot."""
DEFAULT_PRESSES_PER_TRIAL = 3
"""Three presses a trial (the paper does not say how many): fewer presses than buttons,
so the robot must choose what to try. Within one trial the green button does not move,
so with many presses per trial green is as easy as red until the next trial; the
chapter "Goal-oriented interest" shows what changes with 5."""


def check_red_button(red_button):
    """Returns `red_button` if it is a button index, else raises ValueError."""
    return _validate.integer_in_range("red_button", red_button, 0, N_BUTTONS - 1)


def green_candidates(red_button):
    """The four buttons that the green light may take, in increasing order."""
    red_button = check_red_button(red_button)
    return [b for b in range(N_BUTTONS) if b != red_button]


def draw_green(random, red_button):
    """Draws the green button uniformly among the 4 that are not red.

    One uniform number u from `random` picks candidate floor(4 u): a trial always
    draws exactly one number, so the tabular twin and the physics, given the same
    seed, draw the same layouts.

    Args:
      random: a `numpy.random.Generator` (the environment's).
      red_button: index of the red button.

    Returns:
      The index of the green button.
    """
    _validate.instance("random", random, np.random.Generator)
    candidates = green_candidates(red_button)
    return candidates[int(random.random() * len(candidates))]


def lights_for(red_button, green_button):
    """The `lights` observation (shape (5,), int64) of a layout."""
    red_button = check_red_button(red_button)
    green_button = _validate.integer("green_button", green_button, 0, N_BUTTONS - 1)
    if green_button == red_button:
        raise ValueError(f"green_button must differ from red_button ({red_button}), "
                         f"got {green_button}")
    lights = np.full(N_BUTTONS, OFF, dtype=np.int64)
    lights[red_button] = RED
    lights[green_button] = GREEN
    return lights


def layouts(red_button=DEFAULT_RED_BUTTON):
    """All four possible `lights` arrays for a given red button (green left to right)."""
    red_button = check_red_button(red_button)
    return [lights_for(red_button, g) for g in green_candidates(red_button)]


def check_lights(lights, name="lights"):
    """`lights` as an int64 array of 5 values in {0 off, 1 red, 2 green}, else raises."""
    array = _validate.finite_array(name, lights, shape=(N_BUTTONS,))
    if not np.all(np.isin(array, (OFF, RED, GREEN))):
        raise ValueError(f"{name} must hold 5 values, each 0 (off), 1 (red) or 2 (green), "
                         f"got {_validate.show(lights)}")
    return array.astype(np.int64)


def press_outcome(lights, button):
    """The `boxes` observation (red, green; 1 open) after pressing `button` under `lights`."""
    lights = check_lights(lights)
    button = _validate.integer("button", button, 0, N_BUTTONS - 1)
    boxes = np.zeros(len(BOX_NAMES), dtype=np.int64)
    light = lights[button]
    if light == RED:
        boxes[0] = 1
    elif light == GREEN:
        boxes[1] = 1
    return boxes


def check_rewarded_box(rewarded_box):
    """Returns `rewarded_box` if it is None, "red" or "green", else raises ValueError."""
    return _validate.one_of("rewarded_box", rewarded_box, (None,) + BOX_NAMES)


def extrinsic_reward(boxes, rewarded_box):
    """1.0 if the `rewarded_box` ("red" or "green") is open in `boxes`, else 0.0 (always
    0.0 when `rewarded_box` is None: the paper's intrinsic setting)."""
    rewarded_box = check_rewarded_box(rewarded_box)
    boxes = _validate.finite_array("boxes", boxes, shape=(len(BOX_NAMES),))
    if rewarded_box is None:
        return 0.0
    return float(boxes[BOX_NAMES.index(rewarded_box)] == 1)


def observation_spec():
    """The observation spec shared by the tabular and the physics button environments."""
    return collections.OrderedDict(
        lights=specs.BoundedArray((N_BUTTONS,), np.int64, OFF, GREEN, name="lights"),
        boxes=specs.BoundedArray((len(BOX_NAMES),), np.int64, 0, 1, name="boxes"),
    )


def action_spec():
    """One discrete action per button: the index of the button to press."""
    return specs.DiscreteArray(N_BUTTONS, dtype=np.int64, name="button")


class ButtonTrials(dm_env.Environment):
    """The episode rules of the button experiment, shared by `ButtonConsole` (tabular)
    and `PhysicsButtonConsole` (simulated iCub), so both follow them by construction.

    One episode is one trial of `presses_per_trial` presses. The first time step of a
    trial shows the new light layout with both boxes closed; every later one shows the
    boxes right after the press. The last step of a trial is a time limit, not a
    termination, so its discount is 1.0. By default the reward is always 0.0: nothing
    outside the robot pays it to press anything. For the extrinsic actor-critic of the
    paper's Figure 3a, `rewarded_box` makes the environment pay 1.0 for each press that
    opens that box. A step after the end of a trial starts a new one.

    Subclasses say how a trial starts (`_new_trial`, returning the lights) and what a
    press does (`_press`, returning the boxes).
    """

    def __init__(self, presses_per_trial, rewarded_box):
        self.presses_per_trial = _validate.integer_at_least(
            "presses_per_trial", presses_per_trial, 1)
        self.rewarded_box = check_rewarded_box(rewarded_box)
        self._lights = None
        self._presses = 0
        self._reset_next_step = True

    def _new_trial(self):
        raise NotImplementedError

    def _press(self, button):
        raise NotImplementedError

    @property
    def lights(self):
        """A copy of the current light layout (None before the first reset)."""
        return None if self._lights is None else self._lights.copy()

    @property
    def green_button(self):
        """Index of the button lit green in the current trial."""
        return int(np.flatnonzero(self._lights == GREEN)[0])

    def _observation(self, boxes):
        return collections.OrderedDict(lights=self._lights.copy(), boxes=boxes)

    def reset(self):
        """Starts a new trial: a new layout, both boxes shut.

        Returns:
          The FIRST time step: the new layout, both boxes shut.
        """
        self._lights = self._new_trial()
        self._presses = 0
        self._reset_next_step = False
        return dm_env.restart(self._observation(np.zeros(2, dtype=np.int64)))

    def step(self, action):
        """Presses button `action` (0-4).

        Returns:
          The time step after the press: the lights and the boxes as they are after it;
          the first step after the end of a trial starts a new one instead.

        Raises:
          ValueError: if `action` is not a button index.
        """
        button = check_discrete_action(action, N_BUTTONS)
        if self._reset_next_step:
            return self.reset()
        boxes = self._press(button)
        self._presses += 1
        observation = self._observation(boxes)
        reward = extrinsic_reward(boxes, self.rewarded_box)
        if self._presses >= self.presses_per_trial:
            self._reset_next_step = True
            return dm_env.truncation(reward, observation, discount=1.0)
        return dm_env.transition(reward, observation)

    def observation_spec(self):
        """The observation spec: `lights` and `boxes` (see `observation_spec()`)."""
        return observation_spec()

    def action_spec(self):
        """The action spec: one of 5 buttons (see `action_spec()`)."""
        return action_spec()


class ButtonConsole(ButtonTrials):
    """The tabular button experiment: the paper's rules applied directly, no physics.

    The episode rules are those of `ButtonTrials`: one trial of `presses_per_trial`
    presses, ended by a time limit (discount 1.0); reward 0.0 unless `rewarded_box`.

    Args:
      red_button: index (0-4) of the button that is always red. Default 2, the middle.
      presses_per_trial: presses in one trial (>= 1). Default 3.
      rewarded_box: None (default, no reward), "red" or "green": the box whose
        opening pays 1.0.
      seed: None, an integer >= 0 or a `numpy.random.Generator`; draws the green
        buttons (one number per trial).

    Raises:
      ValueError: for a red button outside 0..4, presses_per_trial < 1, an unknown
        rewarded box, a bad seed, or (in `step`) an action that is not a button index.
    """

    def __init__(self, red_button=DEFAULT_RED_BUTTON,
                 presses_per_trial=DEFAULT_PRESSES_PER_TRIAL, rewarded_box=None, seed=None):
        self.red_button = check_red_button(red_button)
        super().__init__(presses_per_trial, rewarded_box)
        self._random = check_seed(seed)

    def reseed(self, seed):
        """Restarts the layouts' random generator from `seed` (None, an integer >= 0 or
        a Generator); the next step starts a new trial."""
        self._random = check_seed(seed)
        self._reset_next_step = True

    def _new_trial(self):
        return lights_for(self.red_button, draw_green(self._random, self.red_button))

    def _press(self, button):
        return press_outcome(self._lights, button)


# --- The simulated iCub ---------------------------------------------------------------

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
_BUTTON_JOINTS = [f"button{b}" for b in range(N_BUTTONS)]
_LIDS = [f"{name}_lid" for name in BOX_NAMES]


class ButtonsPhysics(icub.ArmPhysics):
    """The button scene (assets/buttons.xml) with named accessors.

    The accessors that the press primitive calls every 20 ms of simulated time use
    indices looked up once from the names, which keeps the primitive's cost close to
    that of the physics steps themselves.
    """

    def _indices(self):
        if getattr(self, "_cached_model", None) is not self.model.ptr:
            model = self.model
            joint = lambda name: model.jnt_qposadr[model.name2id(name, "joint")]
            self._button_qpos = np.array([joint(name) for name in _BUTTON_JOINTS])
            self._lid_qpos = np.array([joint(name) for name in _LIDS])
            self._lid_ctrl = np.array([model.name2id(name, "actuator") for name in _LIDS])
            self._cached_model = model.ptr
        return self

    def button_depths(self):
        """How far each button is pushed in (metres, 0 at rest), shape (5,)."""
        return -self.data.qpos[self._indices()._button_qpos]

    def button_depth(self, button):
        """How far button `button` (0-4) is pushed in, in metres."""
        button = _validate.integer("button", button, 0, N_BUTTONS - 1)
        return -float(self.named.data.qpos[_BUTTON_JOINTS[button]][0])

    def lid_angles(self):
        """The red and green lids' opening angles (radians), shape (2,)."""
        return self.data.qpos[self._indices()._lid_qpos]

    def boxes_open(self):
        """The `boxes` observation read from the lids: 1 where a lid is open >= 30 deg."""
        return (self.lid_angles() >= BOX_OPEN_ANGLE).astype(np.int64)

    def set_lid_targets(self, red, green):
        """Commands the lid actuators (radians)."""
        red = _validate.real("red", red)
        green = _validate.real("green", green)
        ctrl = self.data.ctrl
        index = self._indices()._lid_ctrl
        ctrl[index[0]], ctrl[index[1]] = red, green

    def set_lights(self, lights):
        """Lights the button caps: 0 off, 1 red, 2 green (changes their material)."""
        for b, light in enumerate(check_lights(lights)):
            self.named.model.geom_matid[f"button{b}_cap"] = self.model.name2id(
                _LIGHT_MATERIALS[int(light)], "material")



def load_physics():
    """A fresh `ButtonsPhysics` of assets/buttons.xml."""
    return ButtonsPhysics.from_xml_path(str(icub.asset_path("buttons.xml")))


class ButtonMotions:
    """The arm postures of the press primitive, from inverse kinematics on the model.

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
        for b in range(N_BUTTONS):
            cap = physics.named.data.geom_xpos[f"button{b}_cap"].copy()
            top = cap[2] + physics.named.model.geom_size[f"button{b}_cap"][1]
            self.above.append(arm.solve([cap[0], cap[1], top + self.ABOVE], start=self.home))
            self.down.append(arm.solve([cap[0], cap[1], top + self.DOWN], start=self.above[b]))


class ButtonsTask(icub.ArmTask):
    """The button experiment as a continuous dm_control task.

    Action: target angles of the 7 right-arm joints (radians), tracked by the position
    actuators. Each episode lights one red and one green button (the red one fixed,
    the green one drawn from the task's `random`) and starts with the arm at home,
    buttons up and lids shut. After every physics update the task checks the buttons:
    one pushed deeper than `PRESS_DEPTH` opens the lid of its light's colour, which
    shuts again `lid_open_time` seconds later. Reward 0.0, or 1.0 while `rewarded_box`
    is open.

    Args:
      red_button: index of the red button (default 2).
      rewarded_box: None, "red" or "green".
      lid_open_time: seconds a lid stays open (> 0).
      random: None, an integer >= 0 or a `numpy.random.Generator`: draws the layouts,
        one number per episode, as `ButtonConsole` does.
    """

    def __init__(self, red_button=DEFAULT_RED_BUTTON, rewarded_box=None,
                 lid_open_time=LID_OPEN_TIME, random=None):
        self.generator = check_seed(random, "random")
        super().__init__(random=dm_control_random(self.generator))
        self.red_button = check_red_button(red_button)
        self.rewarded_box = check_rewarded_box(rewarded_box)
        self.lid_open_time = _validate.positive("lid_open_time", lid_open_time)
        self.lights = None
        self.press_log = []
        self.deepest = np.zeros(N_BUTTONS)
        self._down = np.zeros(N_BUTTONS, dtype=bool)
        self._lid_opened_at = [None, None]
        self._motions = None

    def motions(self, physics):
        """The press primitive's postures for this physics (computed once)."""
        if self._motions is None:
            self._motions = ButtonMotions(physics)
        return self._motions

    def initialize_episode(self, physics):
        green = draw_green(self.generator, self.red_button)
        self.lights = lights_for(self.red_button, green)
        physics.set_lights(self.lights)
        physics.named.data.qpos[_BUTTON_JOINTS] = 0.0
        physics.named.data.qpos[_LIDS] = 0.0
        physics.set_lid_targets(0.0, 0.0)
        icub.Arm(physics).place(self.motions(physics).home)
        self._down[:] = False
        self._lid_opened_at = [None, None]
        self.clear_log()

    def clear_log(self):
        """Forgets the presses and depths seen so far (`press_log`, `deepest`)."""
        self.press_log = []
        self.deepest = np.zeros(N_BUTTONS)


    def after_step(self, physics):
        self.update(physics)

    def update(self, physics):
        """Detects new presses and opens or shuts the lids (called after physics steps)."""
        depths = physics.button_depths()
        np.maximum(self.deepest, depths, out=self.deepest)
        pressed = depths > PRESS_DEPTH
        now = physics.data.time
        new = pressed & ~self._down
        if new.any():
            for b in np.flatnonzero(new):
                self.press_log.append(int(b))
                light = self.lights[b]
                if light != OFF:
                    box = 0 if light == RED else 1
                    self._lid_opened_at[box] = now
        self._down = (self._down | pressed) & (depths >= PRESS_DEPTH / 2)
        targets = [LID_OPEN_ANGLE if opened is not None and now - opened < self.lid_open_time
                   else 0.0 for opened in self._lid_opened_at]
        physics.set_lid_targets(*targets)

    def shut_lids(self, physics):
        """Commands both lids shut now (the discrete layer does this before a press)."""
        self._lid_opened_at = [None, None]
        physics.set_lid_targets(0.0, 0.0)


    def observation_spec(self, physics):
        return collections.OrderedDict(
            **self.arm_observation_spec(),
            button_depths=specs.Array((N_BUTTONS,), np.float64, name="button_depths"),
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
      seed: None, an integer >= 0 or a `numpy.random.Generator` (the layouts).
      time_limit: seconds per episode (> 0; float('inf') for no limit).
      **task_kwargs: `ButtonsTask` arguments (red_button, rewarded_box, lid_open_time).
    """
    return icub.continuous_environment(load_physics(), ButtonsTask(random=seed, **task_kwargs),
                                       time_limit)


class PhysicsButtonConsole(ButtonTrials):
    """The paper's button experiment on the simulated iCub, with discrete actions.

    Same action spec, observation spec and episode rules (`ButtonTrials`) as
    `ButtonConsole`. An action is a motor primitive: the lids are shut (and the arm
    waits until they are), the arm reaches above the button, pushes down through it,
    lifts and returns home, every posture a target that the position actuators track.
    The `ButtonsTask` watches the buttons during the motion: a button pushed past
    `PRESS_DEPTH` opens the lid of its colour. The observation is taken once the
    motion is over and, if a lid was opened, once it is open at least 30 degrees:
    `boxes` is read from the lids.

    Args: as `ButtonConsole` (red_button, presses_per_trial, rewarded_box, seed).

    Attributes:
      physics: the `ButtonsPhysics`, to inspect or render.
      task: the `ButtonsTask`.
    """

    REACH_TIME, PUSH_TIME, HOLD_TIME, LIFT_TIME, RETURN_TIME = 0.45, 0.3, 0.15, 0.25, 0.45
    """Durations (seconds) of the primitive's phases."""
    LID_WAIT = 1.5
    """Longest wait (seconds) for a lid to open or shut."""

    def __init__(self, red_button=DEFAULT_RED_BUTTON,
                 presses_per_trial=DEFAULT_PRESSES_PER_TRIAL, rewarded_box=None, seed=None):
        self.task = ButtonsTask(red_button=red_button, rewarded_box=rewarded_box,
                                random=seed)
        self.red_button = self.task.red_button
        super().__init__(presses_per_trial, rewarded_box)
        self.physics = load_physics()
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

    def _wait(self, condition):
        """Lets the physics run, arm holding still, until `condition()` or LID_WAIT."""
        if not condition():
            self.arm.hold(self.LID_WAIT, monitor=lambda: self.task.update(self.physics)
                          or condition())

    def press(self, button, recorder=None):
        """Runs the press primitive on `button`; returns the boxes seen after it.

        Args:
          button: index of the button (0-4).
          recorder: optional function of the physics, called after every update of
            the actuators' targets (every 20 ms of simulated time), e.g. to record a
            time series or render frames.

        Raises:
          ValueError: if `button` is not a button index or `recorder` not a function.
        """
        button = check_discrete_action(button, N_BUTTONS, "button")
        _validate.function("recorder", recorder)
        physics, task, motions = self.physics, self.task, self.motions
        task.shut_lids(physics)
        self._wait(lambda: np.all(physics.lid_angles() < np.deg2rad(3.0)))
        task.clear_log()
        opened_before = list(task._lid_opened_at)

        def watch():
            task.update(physics)
            if recorder is not None:
                recorder(physics)
            return False

        self.arm.move(motions.above[button], self.REACH_TIME, watch)
        self.arm.move(motions.down[button], self.PUSH_TIME, watch)
        self.arm.hold(self.HOLD_TIME, watch)
        self.arm.move(motions.above[button], self.LIFT_TIME, watch)
        self.arm.move(motions.home, self.RETURN_TIME, watch)
        opened = [before is None and after is not None
                  for before, after in zip(opened_before, task._lid_opened_at)]
        lid_open = lambda: all(physics.lid_angles()[i] >= BOX_OPEN_ANGLE
                               for i in range(2) if opened[i])
        if not lid_open():
            self.arm.hold(self.LID_WAIT, monitor=lambda: watch() or lid_open())
        return physics.boxes_open()
