"""The Figure 5 panel and the epsilon x window sweep: sliders that rerun the
goal-oriented learner."""

from icm.widgets._common import curves_panel, live_sliders, panel, slider, wants_static

FIGURE5_SLIDERS = live_sliders("figure5")
"""Slider ranges of the live `figure5_panel`, from its settings' `Slider.live` (see
`icm.widgets._common.live_sliders`)."""


def figure5_panel(static=None, **fixed):
    """The Figure 5 panel: the goal-oriented learner's interest in each task, 100 seeds,
    60 trials, for the epsilon, window and new-task factor of its sliders.

    Args:
      static: True for the static version (a Vega-Lite figure over the precomputed
        grid of `icm.experiments.panel_data`, which moves in the HTML book without a
        kernel), False for the live ipywidgets panel that reruns the learner on every
        change; None (default): static while the book is built, live otherwise.
      **fixed: other arguments of `run_goal_oriented`, held fixed (e.g.
        reading="literal", n_seeds=20); live panel only.

    Returns:
      An `ipywidgets.VBox` (sliders above the figure) or an
      `icm.figures.static_panels.StaticPanel`.

    Raises:
      ValueError: for a fixed argument the panel cannot hold.
    """
    return curves_panel("figure5", static, fixed)


def sweep_panel(static=None):
    """The epsilon x window sweep of Figure 5's runs: for the new-task factor of its
    slider, the mean mastery gap (green - red) and the share of seeds that master red
    first, for each epsilon and window of the Figure 5 grid (100 seeds each).

    Args:
      static: as in `figure5_panel`.

    Returns:
      An `ipywidgets.VBox` or an `icm.figures.static_panels.StaticPanel`.
    """
    from icm import figures
    from icm.experiments import panel_data

    if wants_static(static):
        from icm.figures import static_panels

        return static_panels.sweep_panel(panel_data.precompute("figure5"))
    spec = panel_data.spec("figure5")
    factors = spec.sliders["new_task_factor"]
    factor = slider("new_task_factor", dict(min=factors[0], max=factors[-1],
                                            step=factors[1] - factors[0],
                                            value=spec.defaults["new_task_factor"]),
                    spec.setting("new_task_factor").label)

    def draw(new_task_factor):
        settings = [s for s in spec.settings()
                    if abs(s["new_task_factor"] - factors[0]) < 1e-9]
        settings = [dict(s, new_task_factor=new_task_factor) for s in settings]
        cells = [panel_data.sweep_cell(panel_data.panel_run("figure5", **s)) for s in settings]
        return figures.sweep_figure(settings, cells)

    return panel({"new_task_factor": factor}, draw)


__all__ = ["FIGURE5_SLIDERS", "figure5_panel", "sweep_panel"]
