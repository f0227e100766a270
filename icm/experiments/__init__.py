"""Experiments: many seeded runs of a learner on a task, returned as arrays."""

from icm.experiments.goal_oriented import (GoalOrientedResult, comparison_table,
                                          run_goal_oriented)

__all__ = ["GoalOrientedResult", "comparison_table", "run_goal_oriented"]
