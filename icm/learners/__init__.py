"""Learners: predictors, interest measures and the agents built from them."""

from icm.learners.goal_oriented import GoalOrientedAgent
from icm.learners.interest import LearningProgressInterest, least_squares_slope
from icm.learners.predictors import NearestNeighbourPredictor

__all__ = ["GoalOrientedAgent", "LearningProgressInterest", "NearestNeighbourPredictor",
           "least_squares_slope"]
