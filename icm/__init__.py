"""icm: intrinsic motivation on a simulated iCub, after the paper "Intrinsic Motivations
for Forming Actions and Producing Goal Directed Behaviour".

Subpackages: `envs` (the button and rod tasks), `learners` (predictors, interest
measures, agents), `experiments` (seeded multi-run experiments), `figures` (the paper's
figures), `widgets` (interactive panels for the book), `stats` (bands over seeds).
"""

from icm import envs, experiments, figures, learners, stats, widgets

__version__ = "0.1.0"
__all__ = ["envs", "experiments", "figures", "learners", "stats", "widgets"]
