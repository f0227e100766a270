"""The Figure 7 panel: sliders that rerun the curious Q-learner on the rods."""

from icm.widgets._common import curves_panel, live_sliders

FIGURE7_SLIDERS = live_sliders("figure7")
"""Slider ranges of the live `figure7_panel`, from its settings' `Slider.live` (see
`icm.widgets._common.live_sliders`)."""


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
      An `ipywidgets.VBox` or an `icm.figures.static_panels.StaticPanel`.

    Raises:
      ValueError: for a fixed argument the panel cannot hold.
    """
    return curves_panel("figure7", static, fixed)
