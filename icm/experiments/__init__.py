"""Experiments: many seeded runs of a learner on a task, returned as arrays; sweeps of
settings times seeds."""

from icm.experiments.actor_critic import ActorCriticResult, run_actor_critic
from icm.experiments.actor_critic import comparison_table as actor_critic_table
from icm.experiments.goal_babbling import (FormedActionsResult, GoalBabblingResult,
                                          run_formed_actions, run_goal_babbling)
from icm.experiments.goal_babbling import comparison_table as goal_babbling_table
from icm.experiments.goal_oriented import (GoalOrientedResult, comparison_table,
                                          run_goal_oriented)
from icm.experiments.rod_toppling import RodTopplingResult, run_rod_toppling
from icm.experiments.sweep import sweep

__all__ = ["ActorCriticResult", "FormedActionsResult", "GoalBabblingResult",
           "GoalOrientedResult", "RodTopplingResult", "actor_critic_table",
           "comparison_table", "goal_babbling_table", "run_actor_critic",
           "run_formed_actions", "run_goal_babbling", "run_goal_oriented",
           "run_rod_toppling", "sweep"]
