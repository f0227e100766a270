"""The Figure 5 panel: sliders that rerun the goal-oriented learner."""

from icm import _validate, figures
from icm.experiments import run_goal_oriented
from icm.learners import goal_oriented, interest
from icm.widgets._common import check_fixed, panel, slider

FIGURE5_SLIDERS = {
    "epsilon": dict(min=0.0, max=1.0, step=0.05, value=goal_oriented.DEFAULT_EPSILON),
    "window": dict(min=2, max=20, step=1, value=interest.DEFAULT_WINDOW),
    "new_task_factor": dict(min=0.0, max=1.0, step=0.05,
                            value=interest.DEFAULT_NEW_TASK_FACTOR),
    "n_seeds": dict(min=5, max=200, step=5, value=20),
}
"""Slider ranges of `figure5_panel`: the allowed ranges of the learner's arguments
(window capped at 20 to stay readable), and seeds few enough to redraw quickly."""


def figure5_panel(n_trials=60, **fixed):
    """A panel that reruns the goal-oriented learner and redraws Figure 5.

    Args:
      n_trials: trials per run.
      **fixed: other arguments of `run_goal_oriented`, held fixed (e.g. reading).

    Returns:
      An `ipywidgets.VBox` with sliders for epsilon, window, new-task factor and
      number of seeds above the figure.

    Raises:
      ValueError: for n_trials < 1 or a fixed argument the panel cannot hold.
    """
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    check_fixed(run_goal_oriented, fixed, tuple(FIGURE5_SLIDERS) + ("n_trials",))
    sliders = {name: slider(name, spec) for name, spec in FIGURE5_SLIDERS.items()}
    return panel(sliders, lambda **values: figures.figure5_for(n_trials=n_trials, **fixed,
                                                                **values))
