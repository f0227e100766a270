"""The Figure 7 panel: sliders that rerun the curious Q-learner on the rods."""

from icm.learners import predictors, q_learning
from icm.widgets._common import curves_panel

FIGURE7_SLIDERS = {
    "epsilon": dict(min=0.0, max=1.0, step=0.05, value=q_learning.DEFAULT_EPSILON),
    "alpha": dict(min=0.05, max=1.0, step=0.05, value=q_learning.DEFAULT_ALPHA),
    "gamma": dict(min=0.0, max=1.0, step=0.05, value=q_learning.DEFAULT_GAMMA),
    "predictor_lr": dict(min=0.05, max=1.0, step=0.05, value=predictors.DEFAULT_LINEAR_LR),
}
"""Slider ranges of the live `figure7_panel`: the learner's allowed ranges (learning
rates from 0.05 since 0 is not allowed). Every value of the static panel's grid is on
these sliders."""


def figure7_panel(static=None, **fixed):
    """The Figure 7 panel: the error the curious Q-learner's predictor would still make
    on each rod, and the share of episodes toppling it, 100 seeds, 150 episodes, for
    the epsilon, alpha, gamma and predictor learning rate of its sliders.

    Args:
      static: True for the static version (precomputed grid, moves in the HTML book
        without a kernel), False for the live ipywidgets panel; None (default): static
        while the book is built, live otherwise.
      **fixed: other arguments of `run_rod_toppling`, held fixed (e.g. initial_q=0.0,
        n_episodes=300); live panel only.

    Returns:
      An `ipywidgets.VBox` or an `icm.figures.interactive.StaticPanel`.

    Raises:
      ValueError: for a fixed argument the panel cannot hold.
    """
    return curves_panel("figure7", FIGURE7_SLIDERS, static, fixed)
