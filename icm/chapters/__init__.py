"""The chapters of the book, one module per chapter that states claims or quotes
numbers: its claims in words, their checks, its Markdown tables and the numbers its
text glues, computed from the results `icm.experiments` returns."""

from icm.chapters import (actor_critic, button_experiment, curiosity, forming_actions, goal_oriented_interest,
                          robustness, rod_toppling, simulated_icub)

__all__ = ["actor_critic", "button_experiment", "curiosity", "forming_actions",
           "goal_oriented_interest", "robustness", "rod_toppling", "simulated_icub"]
