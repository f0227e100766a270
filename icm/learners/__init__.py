"""Learners: predictors, interest measures and the agents built from them."""

from icm.learners.actor_critic import ActorCritic, softmax
from icm.learners.goal_oriented import GoalOrientedAgent
from icm.learners.interest import LearningProgressInterest, least_squares_slope
from icm.learners.predictors import LinearPredictor, NearestNeighbourPredictor
from icm.learners.q_learning import QLearner

__all__ = ["ActorCritic", "GoalOrientedAgent", "LearningProgressInterest", "LinearPredictor",
           "NearestNeighbourPredictor", "QLearner", "least_squares_slope", "softmax"]
