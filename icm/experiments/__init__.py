"""Experiments: many seeded runs of a learner on a task, played through the one loop
(`loop`) and returned as arrays; grids and sweeps of settings times seeds; the numbers
of the book's panels (`panel_data`). What the chapters say of them (claims, verdicts,
tables) is `icm.chapters`'."""

from icm.experiments.actor_critic import run_actor_critic, run_actor_critic_grid
from icm.experiments.actor_critic_results import ActorCriticResult
from icm.experiments.curiosity import (RewardComparison, SignalComparison,
                                      run_reward_comparison, run_signal_comparison)
from icm.experiments.babbling_results import GoalBabblingResult
from icm.experiments.formed_actions import FormedActionsResult, run_formed_actions
from icm.experiments.goal_babbling import run_goal_babbling
from icm.experiments.goal_oriented_results import GoalOrientedResult
from icm.experiments.goal_oriented import run_goal_oriented, run_goal_oriented_grid
from icm.experiments.rod_toppling import RodTopplingResult, run_rod_toppling
from icm.experiments.sweep import sweep
from icm.experiments import panel_data  # noqa: E402 (after the experiments it runs)

__all__ = ["ActorCriticResult", "FormedActionsResult", "GoalBabblingResult",
           "GoalOrientedResult", "RewardComparison", "RodTopplingResult",
           "SignalComparison", "panel_data", "run_actor_critic", "run_actor_critic_grid",
           "run_formed_actions", "run_goal_babbling", "run_goal_oriented",
           "run_goal_oriented_grid", "run_reward_comparison", "run_rod_toppling",
           "run_signal_comparison", "sweep"]
