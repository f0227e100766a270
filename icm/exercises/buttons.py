"""Checks of the button-console exercises: the console's rule (which box a press opens)
and the goal-oriented learner's predictor (the nearest stored experience, with the
action weight)."""

import numpy as np

from icm.envs import buttons
from icm.exercises import _core
from icm.exercises._core import Case
from icm.learners.predictors import NearestNeighbourPredictor

OUTCOME_PARAMETERS = ("lights", "button")
PREDICT_PARAMETERS = ("memory", "context", "action", "action_weight", "default")
_LIGHT_NAMES = {buttons.OFF: "off", buttons.RED: "lit red", buttons.GREEN: "lit green"}


def reference_press_outcome(lights, button):
    """The boxes after a press, by the console's rule (`icm.envs.buttons.press_outcome`).

    Args:
      lights: 5 values, 0 off, 1 red, 2 green.
      button: the button pressed, 0-4.

    Returns:
      (red, green), each 1 for an open box, else 0.
    """
    return tuple(int(b) for b in buttons.press_outcome(np.array(lights), button))


def _outcome_cases():
    cases = []
    hints = {buttons.RED: "the button lit red opens the red box, the first entry of "
                          "(red, green).",
             buttons.GREEN: "the button lit green opens the green box, the second entry of "
                            "(red, green).",
             buttons.OFF: "a button that is off opens nothing: (0, 0)."}
    for light in (buttons.RED, buttons.GREEN, buttons.OFF):
        for layout in buttons.layouts():
            for button in range(buttons.N_BUTTONS):
                if layout[button] == light:
                    cases.append(Case(
                        f"lights {layout.tolist()}, button {button} ({_LIGHT_NAMES[light]})",
                        (layout.tolist(), button), hints[light]))
    return cases


def check_press_outcome(press_outcome):
    """Checks a student's rule of the console, `press_outcome(lights, button)`: the boxes
    (red, green) after pressing `button` (0-4) under `lights` (5 values: 0 off, 1 red,
    2 green), 1 for an open box. Every button of every layout is tried, the red one
    first.

    Args:
      press_outcome: the student's function.

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of (lights, button).
    """
    return _core.run_cases("press_outcome", "press_outcome", press_outcome,
                           OUTCOME_PARAMETERS, _outcome_cases(), reference_press_outcome,
                           returns="a pair (red, green)")


def reference_predict(memory, context, action, action_weight, default):
    """What `NearestNeighbourPredictor(action_weight)` predicts for (context, action)
    after storing `memory`.

    Args:
      memory: a list of (context, action, effect), oldest first.
      context: the lights of the query.
      action: the button of the query.
      action_weight: the cost of a different button.
      default: the prediction of an empty memory.

    Returns:
      The predicted effect, a tuple.
    """
    predictor = NearestNeighbourPredictor(action_weight)
    for stored_context, stored_action, effect in memory:
        predictor.update(tuple(stored_context), stored_action, tuple(effect))
    predicted = predictor.predict(tuple(context), action, default=default)
    return tuple(predicted)


def _predict_cases():
    a, b, c, d = (tuple(layout.tolist()) for layout in buttons.layouts())
    red, green, nothing = (1, 0), (0, 1), (0, 0)
    cases = [
        Case("empty memory: nothing stored yet", ([], a, 2, 10.0, nothing),
             "with nothing stored, return `default`."),
        Case("the same context and button stored", ([(a, 2, red)], a, 2, 10.0, nothing),
             "an experience at distance 0 is the nearest."),
        Case("the same button under other lights, action weight 10",
             ([(a, 2, red), (b, 3, nothing)], b, 2, 10.0, nothing),
             "distance = the number of lights that differ + action_weight if the buttons "
             "differ: with weight 10 the same button under other lights is nearer than "
             "another button under the same lights."),
        Case("the same memory, action weight 1: a plain Hamming distance",
             ([(a, 2, red), (b, 3, nothing)], b, 2, 1.0, nothing),
             "use the action_weight argument: with 1, two differing lights (2) are farther "
             "than a different button under the same lights (1)."),
        Case("ties: two experiences at the same distance, the latest wins",
             ([(b, 1, nothing), (c, 1, green)], a, 1, 10.0, nothing),
             "among equally near experiences the most recently stored one wins: compare "
             "with <=, not <, as you go through the memory from oldest to newest."),
        Case("ties: the same experience stored twice, effects differ",
             ([(a, 0, nothing), (a, 0, red)], a, 0, 10.0, nothing),
             "among equally near experiences the most recently stored one wins."),
        Case("no experience with this button", ([(a, 0, nothing), (c, 1, green)], a, 4,
                                                10.0, nothing),
             "every experience is a different button: the lights decide."),
    ]
    rng = np.random.default_rng(7)
    layouts = [a, b, c, d]
    for i in range(8):
        memory = []
        for _ in range(int(rng.integers(1, 9))):
            layout = layouts[int(rng.integers(4))]
            button = int(rng.integers(5))
            memory.append((layout, button, reference_press_outcome(list(layout), button)))
        weight = float(rng.choice([1.0, 2.5, 10.0]))
        cases.append(Case(f"random memory {i + 1}",
                          (memory, layouts[int(rng.integers(4))], int(rng.integers(5)),
                           weight, nothing),
                          "distance = lights that differ + action_weight * (buttons "
                          "differ); the nearest wins, the latest among ties."))
    return cases


def check_nearest_neighbour(predict):
    """Checks a student's nearest-neighbour prediction, `predict(memory, context, action,
    action_weight, default)`: the effect of the stored experience (context, action,
    effect) nearest to (context, action), the distance being the number of differing
    lights plus `action_weight` if the buttons differ; the latest among equally near
    ones; `default` when the memory is empty.

    Args:
      predict: the student's function.

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of those five arguments.
    """
    return _core.run_cases("nearest-neighbour prediction", "predict", predict,
                           PREDICT_PARAMETERS, _predict_cases(), reference_predict,
                           returns="an effect, a pair (red, green)")
