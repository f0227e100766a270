"""The rules of the button experiment, shared by the tabular twin and the physics.

Five buttons, two boxes. In every trial one button is lit red and one green; the red
one never moves, the green one is drawn at random among the other four at the start
of each trial. Pressing the lit red button opens the red box, the lit green one the
green box, an unlit one nothing. The boxes close before every press.

The noisy button (`noisy_button=True`, a chapter beyond the paper) is a sixth button,
action 5, never lit: each press opens the red box, the green box or neither, with
probability 1/3 each, whatever the lights.

Randomness: a trial draws one uniform number (its layout), a press of the noisy button
one more (its outcome), both from the environment's Generator, in that order; so the
tabular twin and the physics, seeded alike, draw the same layouts and outcomes.
"""

import collections

import numpy as np
from dm_env import specs

from icm import _validate
from icm._settings import Setting

N_BUTTONS = 5
"""Lit buttons on the console."""
NOISY_BUTTON = 5
"""The action index of the noisy button (`noisy_button=True`)."""
OFF, RED, GREEN = 0, 1, 2
"""Values of a button's light in the `lights` observation."""
BOX_NAMES = ("red", "green")
"""Order of the boxes in the `boxes` observation."""
EFFECTS = ((0, 0), (0, 1), (1, 0))
"""The boxes a press can leave open, by effect index: nothing, the green box, the red
box (the batched learners number effects so: in increasing order, the order in which
the interest modules add up their tasks)."""
NOTHING, GREEN_BOX, RED_BOX = 0, 1, 2
"""Effect indices of `EFFECTS`."""
ALL_EFFECTS = EFFECTS + ((1, 1),)
"""Every `boxes` observation, by effect index: `EFFECTS`, then both boxes open
(`BOTH_BOXES`). The paper's console, and the tabular twin, never open both: one press
pushes one button. On the physics console a movement that is not the scripted
primitive can push two buttons at once (a formed press whose hand pushes the
neighbouring button too), and if they are the red and the green one, both boxes
open."""
BOTH_BOXES = 3
"""Effect index of both boxes open in `ALL_EFFECTS`."""

DEFAULT_RED_BUTTON = 2
"""The red button sits in the middle of the console, straight in front of the robot."""
PRESSES_PER_TRIAL = Setting(
    default=3, label="presses per trial", kind="integer", low=1, high=1000,
    source="the paper divides the experiment into trials and does not say how many "
           "presses a trial holds. The book takes 3: fewer presses than buttons, so the "
           "robot must choose what to try. Within one trial the green button does not "
           "move, so with many presses per trial green is as easy as red until the next "
           "trial",
    swept=(1, 2, 3, 5))
"""Presses in one trial of the button experiment (a world setting the robustness
study sweeps)."""
DEFAULT_PRESSES_PER_TRIAL = PRESSES_PER_TRIAL.default


def n_actions(noisy_button):
    """Buttons the robot can press: 5, or 6 with the noisy button."""
    return N_BUTTONS + int(_validate.boolean("noisy_button", noisy_button))


def check_red_button(red_button):
    """Returns `red_button` if it is a button index, else raises ValueError."""
    return _validate.integer_in_range("red_button", red_button, 0, N_BUTTONS - 1)


def green_candidates(red_button):
    """The four buttons that the green light may take, in increasing order."""
    red_button = check_red_button(red_button)
    return [b for b in range(N_BUTTONS) if b != red_button]


def layout_index(u):
    """The layout drawn by the uniform number u in [0, 1): floor(4 u), an index into
    `green_candidates` and `layouts` (works element-wise on arrays)."""
    return np.floor(np.asarray(u) * 4).astype(np.int64) if np.ndim(u) else int(u * 4)


def draw_green(random, red_button):
    """Draws the green button uniformly among the 4 that are not red.

    One uniform number u from `random` picks candidate floor(4 u) (`layout_index`):
    a trial always draws exactly one number.

    Args:
      random: a `numpy.random.Generator` (the environment's).
      red_button: index of the red button.

    Returns:
      The index of the green button.
    """
    _validate.instance("random", random, np.random.Generator)
    return green_candidates(red_button)[layout_index(random.random())]


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
    """The `boxes` observation (red, green; 1 open) after pressing one of the 5 lit
    buttons, `button`, under `lights`."""
    lights = check_lights(lights)
    button = _validate.integer("button", button, 0, N_BUTTONS - 1)
    boxes = np.zeros(len(BOX_NAMES), dtype=np.int64)
    light = lights[button]
    if light == RED:
        boxes[0] = 1
    elif light == GREEN:
        boxes[1] = 1
    return boxes


def noisy_effect(u):
    """The effect index of a press of the noisy button, from a uniform number u in
    [0, 1): the red box (u < 1/3), the green box (u < 2/3), else nothing (element-wise
    on arrays)."""
    third = np.floor(np.asarray(u) * 3).astype(np.int64)
    effect = np.choose(np.minimum(third, 2), (RED_BOX, GREEN_BOX, NOTHING))
    return effect if np.ndim(u) else int(effect)


def noisy_outcome(u):
    """The `boxes` observation after a press of the noisy button, from a uniform u."""
    return np.array(EFFECTS[noisy_effect(u)], dtype=np.int64)


def effect_index(boxes):
    """The index in `ALL_EFFECTS` of a `boxes` observation (the same as in `EFFECTS`
    for the effects it lists; `BOTH_BOXES` for both open).

    Raises:
      ValueError: if `boxes` is not two values, each 0 or 1.
    """
    array = _validate.finite_array("boxes", boxes, shape=(len(BOX_NAMES),))
    if not np.all(np.isin(array, (0, 1))):
        raise ValueError(f"boxes must hold 2 values, each 0 (shut) or 1 (open), got "
                         f"{_validate.show(boxes)}")
    return ALL_EFFECTS.index(tuple(int(b) for b in array))


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


def action_spec(noisy_button=False):
    """One discrete action per button: the index of the button to press (5 buttons, or
    6 with the noisy button)."""
    return specs.DiscreteArray(n_actions(noisy_button), dtype=np.int64, name="button")


__all__ = ["N_BUTTONS", "NOISY_BUTTON", "OFF", "RED", "GREEN", "BOX_NAMES", "EFFECTS",
           "NOTHING", "RED_BOX", "GREEN_BOX", "ALL_EFFECTS", "BOTH_BOXES", "DEFAULT_RED_BUTTON",
           "DEFAULT_PRESSES_PER_TRIAL", "PRESSES_PER_TRIAL", "n_actions", "check_red_button",
           "green_candidates",
           "layout_index", "draw_green", "lights_for", "layouts", "check_lights",
           "press_outcome", "noisy_effect", "noisy_outcome", "effect_index",
           "check_rewarded_box", "extrinsic_reward", "observation_spec", "action_spec"]
