"""Experiments: many seeded runs of a learner on a task, returned as arrays; sweeps of
settings times seeds."""

from icm.experiments.actor_critic import ActorCriticResult, run_actor_critic
from icm.experiments.actor_critic import comparison_table as actor_critic_table
from icm.experiments.curiosity import (RewardComparison, SignalComparison,
                                      run_reward_comparison, run_signal_comparison)
from icm.experiments.goal_oriented import (GoalOrientedResult, comparison_table,
                                          run_goal_oriented)
from icm.experiments.rod_toppling import RodTopplingResult, run_rod_toppling
from icm.experiments.sweep import sweep

__all__ = ["ActorCriticResult", "GoalOrientedResult", "RewardComparison",
           "RodTopplingResult", "SignalComparison", "actor_critic_table",
           "comparison_table", "run_actor_critic", "run_goal_oriented",
           "run_reward_comparison", "run_rod_toppling", "run_signal_comparison", "sweep"]
