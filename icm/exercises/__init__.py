"""Exercises: checks that run a student's piece of a learner on generated cases (the
paper's edge cases first) against the library's reference, and say which case failed,
with its input, the expected and the given result, and a hint; and the options of the
book's "predict, then check" questions.

Each check takes the student's function and returns a `CheckResult`, which a notebook
shows as a report (true in an `if` when every case passed). A function whose body is
still the placeholder (`raise NotImplementedError`) is reported as not implemented
yet; an argument that is not a function of the exercise's arguments is refused with
an `ArgumentTypeError` naming it.
"""

from icm.exercises._core import CheckResult
from icm.exercises.actor_critic import check_softmax, check_td_update
from icm.exercises.buttons import check_nearest_neighbour, check_press_outcome
from icm.exercises.goal_choice import check_goal_choice
from icm.exercises.curiosity_signal import check_curiosity_signal
from icm.exercises.interest import check_least_squares_slope, check_task_interest
from icm.exercises.motion import check_minimum_jerk
from icm.exercises.quiz import Choices, option_for
from icm.exercises.robustness import check_red_first
from icm.exercises.rods import check_q_learning_step, check_state_confidence

__all__ = ["CheckResult", "Choices", "check_curiosity_signal", "check_goal_choice",
           "check_least_squares_slope", "check_minimum_jerk", "check_nearest_neighbour",
           "check_press_outcome", "check_q_learning_step", "check_red_first",
           "check_softmax", "check_state_confidence", "check_task_interest",
           "check_td_update", "option_for"]
