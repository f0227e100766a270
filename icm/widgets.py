"""Interactive panels for the book: sliders that rerun an experiment and redraw a figure.

The panels need a running Jupyter kernel to move; in the static HTML book they show
the controls and the figure of their first run.
"""

import ipywidgets
from IPython.display import display

from icm import figures
from icm.learners import goal_oriented, interest

FIGURE5_SLIDERS = {
    "epsilon": dict(min=0.0, max=1.0, step=0.05, value=goal_oriented.DEFAULT_EPSILON),
    "window": dict(min=2, max=20, step=1, value=interest.DEFAULT_WINDOW),
    "new_task_factor": dict(min=0.0, max=1.0, step=0.05,
                            value=interest.DEFAULT_NEW_TASK_FACTOR),
    "n_seeds": dict(min=5, max=200, step=5, value=20),
}
"""Slider ranges of `figure5_panel`: the allowed ranges of the learner's arguments
(window capped at 20 to stay readable), and seeds few enough to redraw quickly."""


def _slider(name, spec):
    cls = ipywidgets.IntSlider if isinstance(spec["value"], int) else ipywidgets.FloatSlider
    return cls(description=name, continuous_update=False,
               style={"description_width": "initial"}, **spec)


def figure5_panel(n_trials=60, **fixed):
    """A panel that reruns the goal-oriented learner and redraws Figure 5.

    Args:
      n_trials: trials per run.
      **fixed: other arguments of `run_goal_oriented`, held fixed (e.g. reading).

    Returns:
      An `ipywidgets.VBox` with sliders for epsilon, window, new-task factor and
      number of seeds above the figure.
    """
    sliders = {name: _slider(name, spec) for name, spec in FIGURE5_SLIDERS.items()}
    output = ipywidgets.Output()

    def redraw(**values):
        with output:
            output.clear_output(wait=True)
            display(figures.figure5_for(n_trials=n_trials, **fixed, **values))

    for slider in sliders.values():
        slider.observe(lambda _change: redraw(**{n: s.value for n, s in sliders.items()}),
                       names="value")
    redraw(**{n: s.value for n, s in sliders.items()})
    return ipywidgets.VBox([ipywidgets.HBox(list(sliders.values())[:2]),
                            ipywidgets.HBox(list(sliders.values())[2:]), output])
