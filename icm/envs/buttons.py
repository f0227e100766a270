"""The button experiment of the paper (section 2.1): five lit buttons and two boxes.

A console carries 5 buttons. In every trial one button is lit red and one green; the
red one is always at the same place, the green one is drawn at random among the other
four at the start of each trial. Pressing the lit red button opens the red box, the lit
green one the green box, an unlit one nothing. Boxes close again before the next press,
so every press starts from "no box open".

This module holds the rules (`draw_green`, `press_outcome`, `layouts`) and the fast
tabular environment `ButtonConsole`, which applies the rules directly.
"""

import collections

import dm_env
import numpy as np
from dm_env import specs

from icm import _validate
from icm.envs._common import check_discrete_action, random_state

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
    return [b for b in range(N_BUTTONS) if b != red_button]


def draw_green(random, red_button):
    """Draws the green button uniformly among the 4 that are not red.

    Args:
      random: a `numpy.random.RandomState`; the physics task passes its own, so the
        same seed gives the same sequence of layouts in both versions.
      red_button: index of the red button.

    Returns:
      The index of the green button.
    """
    candidates = green_candidates(red_button)
    return candidates[random.randint(len(candidates))]


def lights_for(red_button, green_button):
    """The `lights` observation (shape (5,), int64) of a layout."""
    lights = np.full(N_BUTTONS, OFF, dtype=np.int64)
    lights[red_button] = RED
    lights[green_button] = GREEN
    return lights


def layouts(red_button=DEFAULT_RED_BUTTON):
    """All four possible `lights` arrays for a given red button (green left to right)."""
    red_button = check_red_button(red_button)
    return [lights_for(red_button, g) for g in green_candidates(red_button)]


def press_outcome(lights, button):
    """The `boxes` observation (red, green; 1 open) after pressing `button` under `lights`."""
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


class ButtonConsole(dm_env.Environment):
    """The tabular button experiment: the paper's rules applied directly, no physics.

    One episode is one trial of `presses_per_trial` presses. The first time step of a
    trial shows the new light layout with both boxes closed; every later one shows the
    boxes right after the press. The last step of a trial is a time limit, not a
    termination, so its discount is 1.0. By default the reward is always 0.0: nothing
    outside the robot pays it to press anything. For the extrinsic actor-critic of the
    paper's Figure 3a, `rewarded_box` makes the environment pay 1.0 for each press that
    opens that box.

    Args:
      red_button: index (0-4) of the button that is always red. Default 2, the middle.
      presses_per_trial: presses in one trial (>= 1). Default 3.
      rewarded_box: None (default, no reward), "red" or "green": the box whose
        opening pays 1.0.
      seed: None, an int or a `numpy.random.RandomState`; draws the green buttons.

    Raises:
      ValueError: for a red button outside 0..4, presses_per_trial < 1, an unknown
        rewarded box, a bad seed, or (in `step`) an action that is not a button index.
    """

    def __init__(self, red_button=DEFAULT_RED_BUTTON,
                 presses_per_trial=DEFAULT_PRESSES_PER_TRIAL, rewarded_box=None, seed=None):
        self.red_button = check_red_button(red_button)
        self.rewarded_box = check_rewarded_box(rewarded_box)
        self.presses_per_trial = _validate.integer_at_least(
            "presses_per_trial", presses_per_trial, 1)
        self._random = random_state(seed)
        self._lights = None
        self._presses = 0
        self._reset_next_step = True

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
        """Starts a new trial: draws the green button, closes both boxes."""
        green = draw_green(self._random, self.red_button)
        self._lights = lights_for(self.red_button, green)
        self._presses = 0
        self._reset_next_step = False
        return dm_env.restart(self._observation(np.zeros(2, dtype=np.int64)))

    def step(self, action):
        """Presses button `action` and returns the boxes as they are after the press."""
        button = check_discrete_action(action, N_BUTTONS)
        if self._reset_next_step:
            return self.reset()
        boxes = press_outcome(self._lights, button)
        self._presses += 1
        observation = self._observation(boxes)
        reward = extrinsic_reward(boxes, self.rewarded_box)
        if self._presses >= self.presses_per_trial:
            self._reset_next_step = True
            return dm_env.truncation(reward, observation, discount=1.0)
        return dm_env.transition(reward, observation)

    def observation_spec(self):
        return observation_spec()

    def action_spec(self):
        return action_spec()
