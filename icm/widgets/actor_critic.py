"""The Figure 6 panel: sliders and choices that rerun the actor-critic."""

from icm.learners import actor_critic
from icm.widgets._common import curves_panel

FIGURE6_SLIDERS = {
    "lr_actor": dict(min=0.05, max=1.0, step=0.05, value=actor_critic.DEFAULT_LR_ACTOR),
    "lr_critic": dict(min=0.05, max=1.0, step=0.05, value=actor_critic.DEFAULT_LR_CRITIC),
    "temperature": dict(min=0.05, max=2.0, step=0.05, value=actor_critic.DEFAULT_TEMPERATURE),
}
"""Slider ranges of the live `figure6_panel`: the learner's allowed ranges (learning
rates from 0.05 since 0 is not allowed; temperature capped at 2, where the softmax is
close to uniform). Every value of the static panel's grid is on these sliders."""

FIGURE6_CHOICES = {"variant": tuple(actor_critic.VARIANTS)}
"""Choices of `figure6_panel`, first option the default: which reading of the paper's
formulas (see `icm.learners.actor_critic.VARIANTS`)."""


def figure6_panel(static=None, **fixed):
    """The Figure 6 panel: the actor-critic's prediction error on each task, 100 seeds,
    60 trials, for the learning rates, temperature and variant of its controls.

    Args:
      static: True for the static version (precomputed grid, moves in the HTML book
        without a kernel), False for the live ipywidgets panel; None (default): static
        while the book is built, live otherwise.
      **fixed: other arguments of `run_actor_critic`, held fixed (e.g.
        reward="extrinsic", gamma=0.9); live panel only.

    Returns:
      An `ipywidgets.VBox` or an `icm.figures.interactive.StaticPanel`.

    Raises:
      ValueError: for a fixed argument the panel cannot hold.
    """
    return curves_panel("figure6", FIGURE6_SLIDERS, static, fixed)
