"""The Figure 6 panel: sliders and choices that rerun the actor-critic."""

from icm.experiments import panel_data
from icm.widgets._common import curves_panel, live_sliders

FIGURE6_SLIDERS = live_sliders("figure6")
"""Slider ranges of the live `figure6_panel`, from its settings' `Slider.live` (see
`icm.widgets._common.live_sliders`)."""

FIGURE6_CHOICES = panel_data.spec("figure6").choices
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
      An `ipywidgets.VBox` or an `icm.figures.static_panels.StaticPanel`.

    Raises:
      ValueError: for a fixed argument the panel cannot hold.
    """
    return curves_panel("figure6", static, fixed)
