"""The implement exercises, by label: the function each asks for, its check (the public
cases, shown in the book and in the students' notebooks), its hidden cases (drawn
from a seed that only the grading material holds), and its points and time limits.
The assignments (`icm.course`) read everything from here; the chapters' notebooks
hold the exercises' text, placeholders and solutions."""

import copy
import dataclasses
import warnings
import zlib

import numpy as np

from icm import _validate
from icm.exercises import (actor_critic, buttons, curiosity_signal, goal_choice, interest,
                           motion, robustness, rods)
from icm.exercises._own import call_own

PUBLIC_POINTS = 2
"""Points of an exercise's public test (its check's cases, which the student sees)."""
HIDDEN_POINTS = (2, 2, 2, 2)
"""Points of each of an exercise's hidden tests (one test per entry, each on its own
cases drawn from the grading seed)."""
TIMEOUT = 20.0
"""Seconds each test of an exercise may take (a right answer takes well under one)."""


@dataclasses.dataclass(frozen=True)
class Exercise:
    """One implement exercise.

    Attributes:
      label: the exercise's label in the book, e.g. "ex-press-outcome".
      function: the name of the function the student writes, e.g. "press_outcome".
      check: check(function, cases=None) -> `CheckResult`, on the public cases by
        default; with no experiment or figure.
      hidden_cases: hidden_cases(rng) -> a list of cases of the shapes of the public
        ones, drawn from a `numpy.random.Generator`.
      public_cases: public_cases() -> the check's own cases.
      forbidden: the `icm.exercises._own.Forbidden` of the check: what an answer
        must not call.
      takes_generator: whether the function takes a `numpy.random.Generator` after
        a case's arguments (the goal-choice rule).
      points: the public test's points.
      hidden_points: each hidden test's points.
      timeout: the seconds each test may take.
    """

    label: str
    function: str
    check: object
    hidden_cases: object
    public_cases: object
    forbidden: object
    takes_generator: bool = False
    points: float = PUBLIC_POINTS
    hidden_points: tuple = HIDDEN_POINTS
    timeout: float = TIMEOUT

    @property
    def total(self):
        """The exercise's points: the public test's and the hidden tests'."""
        return self.points + sum(self.hidden_points)

    def public(self, function):
        """The check on the public cases.

        Args:
          function: the student's function.

        Returns:
          A `CheckResult`.
        """
        return self.check(function)

    def hidden(self, function, seed, test):
        """The check on the cases of one hidden test, drawn from the grading seed.

        Args:
          function: the student's function.
          seed: the grading seed, an integer >= 0.
          test: which hidden test, 0 to len(hidden_points) - 1.

        Returns:
          A `CheckResult`.

        Raises:
          ValueError: for a bad seed or test.
        """
        seed = _validate.integer_at_least("seed", seed, 0)
        test = _validate.integer("test", test, 0, len(self.hidden_points) - 1)
        return self.check(function, cases=self.hidden_cases(self.generator(seed, test)))

    def borrowed(self, function, rng):
        """What the function calls that it must not, on every public case and on cases
        of every hidden shape drawn from `rng`, each run whatever the one before it
        gave (a wrong result, an error): the first such call, or None.

        Args:
          function: the student's function.
          rng: a `numpy.random.Generator` for the hidden shapes' cases.

        Returns:
          An `icm.exercises._own.Borrowed`, or None.
        """
        cases = list(self.public_cases()) + list(self.hidden_cases(rng))
        for case in cases:
            arguments = copy.deepcopy(case.args)
            if self.takes_generator:
                arguments = (list(arguments[0]), arguments[1], np.random.default_rng(0))
            try:
                with warnings.catch_warnings(), np.errstate(all="ignore"):
                    warnings.simplefilter("ignore")
                    _, borrowed = call_own(function, arguments, self.forbidden)
            except Exception:  # a wrong answer: only what it calls matters here
                continue
            if borrowed is not None:
                return borrowed
        return None

    def generator(self, seed, test):
        """The generator of one hidden test's cases: its own stream of the grading seed,
        so that no two exercises or tests share cases.

        Args:
          seed: the grading seed.
          test: which hidden test.

        Returns:
          A `numpy.random.Generator`.
        """
        return np.random.default_rng([seed, zlib.crc32(self.label.encode()), test])


def _no_experiment(check):
    def public_only(function, cases=None):
        return check(function, experiment=False, cases=cases)
    return public_only


EXERCISES = {exercise.label: exercise for exercise in (
    Exercise("ex-press-outcome", "press_outcome", buttons.check_press_outcome,
             buttons.hidden_outcome_cases, buttons.public_outcome_cases, buttons.OUTCOME_FORBIDDEN),
    Exercise("ex-nearest-neighbour", "predict", buttons.check_nearest_neighbour,
             buttons.hidden_predict_cases, buttons.public_predict_cases, buttons.PREDICT_FORBIDDEN),
    Exercise("ex-least-squares-slope", "least_squares_slope",
             interest.check_least_squares_slope, interest.hidden_slope_cases,
             interest.public_slope_cases, interest.INTEREST_FORBIDDEN),
    Exercise("ex-task-interest", "task_interest", _no_experiment(interest.check_task_interest),
             interest.hidden_interest_cases, interest.public_interest_cases,
             interest.INTEREST_FORBIDDEN),
    Exercise("ex-minimum-jerk", "minimum_jerk", motion.check_minimum_jerk, motion.hidden_cases,
             motion.public_cases, motion.FORBIDDEN),
    Exercise("ex-softmax", "softmax", actor_critic.check_softmax,
             actor_critic.hidden_softmax_cases, actor_critic.public_softmax_cases,
             actor_critic.SOFTMAX_FORBIDDEN),
    Exercise("ex-td-update", "td_update", actor_critic.check_td_update,
             actor_critic.hidden_td_cases, actor_critic.public_td_cases, actor_critic.TD_FORBIDDEN),
    Exercise("ex-q-learning-step", "q_learning_step", rods.check_q_learning_step,
             rods.hidden_step_cases, rods.public_step_cases, rods.STEP_FORBIDDEN),
    Exercise("ex-state-confidence", "state_confidence", rods.check_state_confidence,
             rods.hidden_confidence_cases, rods.public_confidence_cases, rods.CONFIDENCE_FORBIDDEN),
    Exercise("ex-red-first", "red_first", robustness.check_red_first, robustness.hidden_cases,
             robustness.public_cases, robustness.FORBIDDEN),
    # Each test also runs the noise case (interest per button), about half a second.
    Exercise("ex-curiosity-signal", "my_interest",
             _no_experiment(curiosity_signal.check_curiosity_signal),
             curiosity_signal.hidden_signal_cases, curiosity_signal.public_signal_cases,
             interest.INTEREST_FORBIDDEN),
    # 3000 draws of the rule per case: the slowest check.
    Exercise("ex-goal-choice", "choose_region", goal_choice.check_goal_choice,
             goal_choice.hidden_cases, goal_choice.public_cases, goal_choice.FORBIDDEN,
             takes_generator=True, timeout=60.0),
)}
"""Every implement exercise of the book, by label (a test checks that they agree)."""
