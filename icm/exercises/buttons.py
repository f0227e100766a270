"""Checks of the button-console exercises: the console's rule (which box a press opens)
and the goal-oriented learner's predictor (the nearest stored experience, with the
action weight)."""

import numpy as np

from icm.envs import buttons
from icm.exercises import _core
from icm.exercises._core import Case
from icm.exercises._own import Forbidden
from icm.learners.predictors import NearestNeighbourPredictor

OUTCOME_PARAMETERS = ("lights", "button")
PREDICT_PARAMETERS = ("memory", "context", "action", "action_weight", "default")
_LIGHT_NAMES = {buttons.OFF: "off", buttons.RED: "lit red", buttons.GREEN: "lit green"}
OUTCOME_FORBIDDEN = Forbidden(("icm.envs.buttons", "icm.envs.twins"))
"""What the console's rule must not call: the console's own."""
PREDICT_FORBIDDEN = Forbidden(("icm.learners.predictors",))
"""What a nearest-neighbour prediction must not call: the library's predictors."""
_OUTCOME_HINTS = {buttons.RED: "the button lit red opens the red box, the first entry of "
                               "(red, green).",
                  buttons.GREEN: "the button lit green opens the green box, the second "
                                 "entry of (red, green).",
                  buttons.OFF: "a button that is off opens nothing: (0, 0)."}


def reference_press_outcome(lights, button):
    """The boxes after a press, by the console's rule (`icm.envs.buttons.press_outcome`).

    Args:
      lights: 5 values, 0 off, 1 red, 2 green.
      button: the button pressed, 0-4.

    Returns:
      (red, green), each 1 for an open box, else 0.
    """
    return tuple(int(b) for b in buttons.press_outcome(np.array(lights), button))


def public_outcome_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    cases = []
    hints = _OUTCOME_HINTS
    for light in (buttons.RED, buttons.GREEN, buttons.OFF):
        for layout in buttons.layouts():
            for button in range(buttons.N_BUTTONS):
                if layout[button] == light:
                    cases.append(Case(
                        f"lights {layout.tolist()}, button {button} ({_LIGHT_NAMES[light]})",
                        (layout.tolist(), button), hints[light]))
    return cases


def check_press_outcome(press_outcome, cases=None):
    """Checks a student's rule of the console, `press_outcome(lights, button)`: the boxes
    (red, green) after pressing `button` (0-4) under `lights` (5 values: 0 off, 1 red,
    2 green), 1 for an open box. Every button of every layout is tried, the red one
    first.

    Args:
      press_outcome: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of (lights, button).
    """
    cases = public_outcome_cases() if cases is None else cases
    return _core.run_cases("press_outcome", "press_outcome", press_outcome,
                           OUTCOME_PARAMETERS, cases, reference_press_outcome,
                           returns="a pair (red, green)", forbidden=OUTCOME_FORBIDDEN)


def hidden_outcome_cases(rng):
    """Cases of the shapes of the public ones (every button of a layout, the red one
    first) on layouts drawn from `rng` whose red button is not the paper's: the
    public cases are the paper's four layouts.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    cases = []
    reds = [b for b in range(buttons.N_BUTTONS) if b != buttons.DEFAULT_RED_BUTTON]
    for red in rng.choice(reds, size=2, replace=False):
        options = buttons.layouts(int(red))
        layout = options[int(rng.integers(len(options)))].tolist()
        order = sorted(range(buttons.N_BUTTONS),
                       key=lambda b: (buttons.RED, buttons.GREEN, buttons.OFF).index(layout[b]))
        for button in order:
            cases.append(Case(f"another layout, button {_LIGHT_NAMES[layout[button]]} "
                              f"(hidden)", (layout, button), _OUTCOME_HINTS[layout[button]]))
    return cases


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


def public_predict_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
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


def check_nearest_neighbour(predict, cases=None):
    """Checks a student's nearest-neighbour prediction, `predict(memory, context, action,
    action_weight, default)`: the effect of the stored experience (context, action,
    effect) nearest to (context, action), the distance being the number of differing
    lights plus `action_weight` if the buttons differ; the latest among equally near
    ones; `default` when the memory is empty.

    Args:
      predict: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of those five arguments.
    """
    cases = public_predict_cases() if cases is None else cases
    return _core.run_cases("nearest-neighbour prediction", "predict", predict,
                           PREDICT_PARAMETERS, cases, reference_predict,
                           returns="an effect, a pair (red, green)",
                           forbidden=PREDICT_FORBIDDEN)


def hidden_predict_cases(rng):
    """Cases of the shapes of the public ones, with memories, queries, action weights
    and defaults drawn from `rng` (layouts with the red button anywhere).

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    layouts = [tuple(layout.tolist()) for red in range(buttons.N_BUTTONS)
               for layout in buttons.layouts(red)]

    def layout():
        return layouts[int(rng.integers(len(layouts)))]

    def experience(context=None, action=None):
        context = layout() if context is None else context
        action = int(rng.integers(buttons.N_BUTTONS)) if action is None else action
        return (context, action, reference_press_outcome(list(context), action))

    def weight():
        return float(rng.choice([0.5, 1.0, 1.5, 3.0, 7.5, 12.0]))

    default = tuple(int(v) for v in rng.integers(0, 2, 2))
    a, button = layout(), int(rng.integers(buttons.N_BUTTONS))
    twice = experience(a, button)
    tie = ((a, button, (0, 0)), (a, button, (1, 1)))
    cases = [
        Case("empty memory (hidden)", ([], a, button, weight(), default),
             "with nothing stored, return `default`."),
        Case("the same context and button stored (hidden)",
             ([experience(), twice, experience()], a, button, weight(), default),
             "an experience at distance 0 is the nearest."),
        Case("ties: the same experience stored twice (hidden)",
             (list(tie), a, button, weight(), default),
             "among equally near experiences the most recently stored one wins."),
    ]
    for i in range(6):
        memory = [experience() for _ in range(int(rng.integers(2, 12)))]
        cases.append(Case(f"random memory (hidden {i + 1})",
                          (memory, layout(), int(rng.integers(buttons.N_BUTTONS)), weight(),
                           default),
                          "distance = lights that differ + action_weight * (buttons "
                          "differ); the nearest wins, the latest among ties."))
    return cases
