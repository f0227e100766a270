"""Checks of the rod-toppling exercises: one step of the Q-learner of equation 3, paid
by its linear predictor's error, and the predictor's state confidence (Figure 7)."""

import numpy as np

from icm.exercises import _core
from icm.exercises._core import Case
from icm.exercises._own import Forbidden
from icm.learners.predictors import UNTRIED_ERROR

STEP_PARAMETERS = ("q", "predictions", "state", "action", "observed", "next_state", "done",
                   "alpha", "gamma", "lr")
CONFIDENCE_PARAMETERS = ("last_errors",)
STEP_FORBIDDEN = Forbidden(("icm.learners.q_learning", "icm.learners.predictors",
                            "icm.experiments._rods_kernel"))
"""What a move of the Q-learner must not call: the learner and its predictor."""
CONFIDENCE_FORBIDDEN = Forbidden(("icm.learners.predictors",))
"""What a state confidence must not call: the linear predictor's own."""
EQ3 = "Equation 3: Q(s, a) += alpha * (r + gamma * max over a' of Q(s', a') - Q(s, a))."
REWARD_HINT = ("The reward is the predictor's error before it learns from this move: "
               "sum_i abs(o_i - p_i) with the old prediction, then p += lr * (o - p).")
PREDICTION_HINT = ("The prediction of (state, action) moves towards what was observed: "
                   "p += lr * (o - p), an untried pair starting from 0; no other pair "
                   "changes.")
STEP_QUANTITIES = (("reward", "the reward", REWARD_HINT),
                   ("predictions", "the prediction", PREDICTION_HINT),
                   ("q", "Q", EQ3 + " Only Q(s, a) changes."))
"""What a move is judged on, in the order it computes them: the first one wrong is
the one the report names."""


def reference_q_learning_step(q, predictions, state, action, observed, next_state, done,
                              alpha, gamma, lr):
    """One move of the rods' learner, as `QLearner.learn` with a `LinearPredictor` makes
    it (a test checks they agree): the reward is the predictor's absolute error on
    (state, action) before it learns, sum_i abs(o_i - p_i); the prediction moves towards
    the outcome, p += lr * (o - p); then equation 3, Q(s, a) += alpha * (r + gamma *
    max_a' Q(s', a') - Q(s, a)), with no next value when the move ended the episode.

    Args:
      q: the Q-table, a list of rows (one per state), changed in place.
      predictions: (state, action) -> list of predicted outcomes (missing: zeros),
        changed in place.
      state, action, observed, next_state: the move and what it did.
      done: whether the move ended the episode.
      alpha, gamma, lr: the step size, the discount, the predictor's rate.

    Returns:
      The reward.
    """
    predicted = predictions.get((state, action), [0.0] * len(observed))
    reward = sum(abs(o - p) for o, p in zip(observed, predicted))
    predictions[(state, action)] = [p + lr * (o - p) for o, p in zip(observed, predicted)]
    target = reward if done else reward + gamma * max(q[next_state])
    q[state][action] += alpha * (target - q[state][action])
    return reward


def _after(args, returned):
    return {"reward": returned, "q": args[0], "predictions": args[1]}


def _q(rows, value=0.1):
    return [[value] * 4 for _ in range(rows)]


def public_step_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    knows = _q(3)
    knows[1] = [0.1, 0.5, 0.2, 0.1]
    cases = [
        Case("an untried move topples the red rod",
             (_q(3), {}, 0, 1, [1.0, 0.0], 1, False, 0.5, 0.9, 0.2),
             "An untried (state, action) is predicted 0 (\"the rods stay up\"). " + REWARD_HINT,
             "reward"),
        Case("the episode ended: no next value",
             (knows, {(0, 1): [0.5, 0.0]}, 0, 1, [1.0, 0.0], 1, True, 0.5, 0.9, 0.2),
             "When the move ended the episode (done), nothing follows: the target is the "
             "reward alone, without gamma * max Q(s', .).", "q"),
        Case("the episode goes on: the next state's best value counts",
             (knows, {}, 0, 2, [0.0, 0.0], 1, False, 0.5, 0.9, 0.2),
             EQ3 + " Take the maximum over the next state's actions, not Q(s', a).", "q"),
        Case("a move predicted right pays nothing",
             (_q(3), {(2, 0): [0.0, 0.0]}, 2, 0, [0.0, 0.0], 2, False, 0.5, 0.9, 0.2),
             "A move whose outcome was predicted exactly pays 0: a known move is boring.",
             "reward"),
        Case("a topple predicted well pays little",
             (_q(3), {(2, 0): [0.9, 0.0]}, 2, 0, [1.0, 0.0], 1, True, 0.5, 0.9, 0.2),
             REWARD_HINT, "reward"),
        # The row's best action: max Q(s', .) read after Q(s, a) changed would differ.
        Case("the next state is the state itself",
             (knows, {}, 1, 1, [0.0, 0.0], 1, False, 0.5, 0.9, 0.2),
             "Read max Q(s', .) before you change Q(s, a), even when s' is s.", "q"),
        Case("both rods mispredicted: the errors add",
             (_q(2), {(0, 0): [0.3, 0.6]}, 0, 0, [0.0, 1.0], 1, True, 0.5, 0.9, 0.2),
             "The error is summed over the outcome's entries: |o_1 - p_1| + |o_2 - p_2|.",
             "reward"),
        Case("other rates: alpha 1, gamma 0.5, lr 1",
             (knows, {(0, 0): [0.2, 0.0]}, 0, 0, [1.0, 0.0], 1, False, 1.0, 0.5, 1.0),
             "Use the alpha, gamma and lr arguments."),
    ]
    rng = np.random.default_rng(17)
    for i in range(6):
        q = rng.random((4, 4)).round(3).tolist()
        state, action = int(rng.integers(4)), int(rng.integers(4))
        predictions = {(state, action): rng.random(2).round(2).tolist()} if i % 2 else {}
        cases.append(Case(f"random move {i + 1}",
                          (q, predictions, state, action,
                           [float(rng.integers(2)), 0.0], int(rng.integers(4)),
                           bool(i % 3 == 0), 0.5, 0.9, 0.2),
                          REWARD_HINT + " " + EQ3))
    return cases


def hidden_step_cases(rng):
    """Cases of the shapes of the public ones, with values drawn from `rng`: the
    check's hidden cases.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    def table(rows):
        return rng.random((rows, 4)).round(3).tolist()

    def rates():
        return (round(float(rng.uniform(0.1, 1.0)), 2), round(float(rng.uniform(0.1, 0.99)), 2),
                round(float(rng.uniform(0.05, 1.0)), 2))

    def outcome():
        return [float(rng.integers(2)), float(rng.integers(2))]

    cases = []
    for i in range(2):
        rows = int(rng.integers(3, 7))
        q, state, action = table(rows), int(rng.integers(rows)), int(rng.integers(4))
        cases.append(Case(f"an untried move (hidden {i + 1})",
                          (q, {}, state, action, outcome(), int(rng.integers(rows)), False)
                          + rates(), "An untried pair is predicted 0. " + REWARD_HINT,
                          "reward"))
        seen = {(state, action): rng.random(2).round(2).tolist()}
        cases.append(Case(f"the episode ended (hidden {i + 1})",
                          (table(rows), seen, state, action, outcome(),
                           int(rng.integers(rows)), True) + rates(),
                          "When the move ended the episode the target is the reward alone.",
                          "q"))
        q = table(rows)
        best = int(np.argmax(q[state]))
        cases.append(Case(f"the next state is the state itself (hidden {i + 1})",
                          (q, dict(seen), state, best, outcome(), state, False) + rates(),
                          "Read max Q(s', .) before you change Q(s, a), even when s' is s.",
                          "q"))
        cases.append(Case(f"a move predicted right (hidden {i + 1})",
                          (table(rows), {(state, action): [1.0, 0.0]}, state, action,
                           [1.0, 0.0], int(rng.integers(rows)), False) + rates(),
                          "A move whose outcome was predicted exactly pays 0.", "reward"))
        other = {(int(rng.integers(rows)), int(rng.integers(4))): [0.5, 0.5]}
        other[(state, action)] = rng.random(2).round(2).tolist()
        cases.append(Case(f"a random move (hidden {i + 1})",
                          (table(rows), other, state, action, outcome(),
                           int(rng.integers(rows)), bool(rng.integers(2))) + rates(),
                          REWARD_HINT + " " + EQ3))
    return cases


def check_q_learning_step(q_learning_step, cases=None):
    """Checks a student's move of the rods' learner, `q_learning_step(q, predictions,
    state, action, observed, next_state, done, alpha, gamma, lr)`: the reward is the
    linear predictor's absolute error on (state, action) before it learns (an untried
    pair is predicted 0), the prediction moves towards `observed` by `lr`, then Q(s,
    a) follows equation 3 (no next value when `done`); `q` and `predictions` change in
    place, and the reward is returned.

    Args:
      q_learning_step: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of those ten arguments.
    """
    cases = public_step_cases() if cases is None else cases
    return _core.run_cases("q_learning_step", "q_learning_step", q_learning_step,
                           STEP_PARAMETERS, cases, reference_q_learning_step,
                           observe=_after, quantities=STEP_QUANTITIES,
                           forbidden=STEP_FORBIDDEN)


def reference_state_confidence(last_errors):
    """The state confidence of a cell, as `LinearPredictor.confidence` computes it (a
    test checks it).

    Args:
      last_errors: the latest error of each move in the cell (None: never tried).

    Returns:
      1 minus the mean, over the moves, of the error capped at 1, an untried move
      counting `UNTRIED_ERROR` (1).
    """
    capped = [UNTRIED_ERROR if e is None else min(e, 1.0) for e in last_errors]
    return 1.0 - sum(capped) / len(capped)


def public_confidence_cases():
    """The cases the check runs when given none (the ones the book shows the
    student), the paper's edge cases first: a list of `Case`.

    Returns:
      A list of `icm.exercises._core.Case`.
    """
    return [
        Case("a cell never visited: every move untried", ([None, None, None, None],),
             "A move never tried counts as an error of 1: a cell never visited has "
             "confidence 0."),
        Case("every move tried and predicted right", ([0.0, 0.0, 0.0, 0.0],),
             "Errors of 0 everywhere: confidence 1."),
        Case("one move topples a rod predicted with error 0.5", ([0.0, 0.5, 0.0, 0.0],),
             "1 minus the mean of the four errors."),
        Case("some moves untried", ([0.0, None, 0.2, None],),
             "An untried move (None) counts as an error of 1, not 0, and it still counts "
             "in the mean."),
        Case("an error above 1 (both rods wrong) is capped at 1", ([2.0, 0.0, 0.0, 0.0],),
             "Cap each error at 1 before the mean: min(error, 1)."),
        Case("ties: the same error on every move", ([0.3, 0.3, 0.3, 0.3],),
             "1 minus the mean error."),
        Case("a cell with one move", ([0.25],), "Use the number of moves given, not 4."),
    ]


def check_state_confidence(state_confidence, cases=None):
    """Checks a student's state confidence, `state_confidence(last_errors)`: from the
    error of the latest prediction of each move in a cell (None for a move never
    tried), 1 minus the mean of the errors, each capped at 1, an untried move counting
    1.

    Args:
      state_confidence: the student's function.
      cases: the cases to try, a list of `Case` (default: the check's own, the ones
        the book shows; the grader passes its hidden ones).

    Returns:
      A `CheckResult`.

    Raises:
      ArgumentTypeError: if the argument is not a function of one argument.
    """
    cases = public_confidence_cases() if cases is None else cases
    return _core.run_cases("state_confidence", "state_confidence", state_confidence,
                           CONFIDENCE_PARAMETERS, cases,
                           reference_state_confidence, returns="a number",
                           forbidden=CONFIDENCE_FORBIDDEN)


def hidden_confidence_cases(rng):
    """Cases of the shapes of the public ones, with values drawn from `rng`.

    Args:
      rng: a `numpy.random.Generator`.

    Returns:
      A list of `Case`.
    """
    def errors(n, untried=0.0, above=0.0):
        values = []
        for _ in range(n):
            u = rng.random()
            values.append(None if u < untried else
                          round(float(rng.uniform(1.0, 2.0)), 3) if u < untried + above else
                          round(float(rng.random()), 3))
        return values

    n = int(rng.integers(3, 7))
    return [
        Case("a cell never visited (hidden)", ([None] * n,),
             "A move never tried counts as an error of 1."),
        Case("every move predicted right (hidden)", ([0.0] * n,), "Errors of 0: confidence 1."),
        Case("some moves untried (hidden)", (errors(n, untried=0.5),),
             "An untried move (None) counts as an error of 1, and it counts in the mean."),
        Case("errors above 1 are capped (hidden)", (errors(n, above=0.5),),
             "Cap each error at 1 before the mean."),
        Case("a cell with another number of moves (hidden)",
             (errors(int(rng.integers(1, 9)), untried=0.3, above=0.2),),
             "Use the number of moves given."),
    ]
