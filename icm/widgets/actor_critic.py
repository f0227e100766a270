"""The Figure 6 panel: sliders and choices that rerun the actor-critic."""

import ipywidgets

from icm import _validate, figures
from icm.experiments import run_actor_critic
from icm.learners import actor_critic
from icm.widgets._common import check_fixed, panel, slider

FIGURE6_SLIDERS = {
    "temperature": dict(min=0.05, max=2.0, step=0.05, value=actor_critic.DEFAULT_TEMPERATURE),
    "lr_actor": dict(min=0.05, max=1.0, step=0.05, value=actor_critic.DEFAULT_LR_ACTOR),
    "lr_critic": dict(min=0.05, max=1.0, step=0.05, value=actor_critic.DEFAULT_LR_CRITIC),
    "gamma": dict(min=0.0, max=1.0, step=0.05, value=actor_critic.DEFAULT_GAMMA),
    "n_seeds": dict(min=5, max=200, step=5, value=20),
}
"""Slider ranges of `figure6_panel`: the learner's allowed ranges (temperature capped at
2, where the softmax is close to uniform; learning rates from 0.05 since 0 is not
allowed), and seeds few enough to redraw quickly."""
FIGURE6_CHOICES = {
    "reward": actor_critic.REWARDS,
    "variant": tuple(actor_critic.VARIANTS),
}
"""Choices of `figure6_panel`, first option the default: where the reward comes from,
and which reading of the paper's formulas."""


def figure6_panel(n_trials=60, **fixed):
    """A panel that reruns the actor-critic and redraws Figure 6.

    Args:
      n_trials: trials per run.
      **fixed: other arguments of `run_actor_critic`, held fixed (e.g. rewarded_box).

    Returns:
      An `ipywidgets.VBox`: sliders for temperature, the two learning rates, gamma and
      the number of seeds, and choices of reward and variant, above the figure.

    Raises:
      ValueError: for n_trials < 1 or a fixed argument the panel cannot hold.
    """
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    check_fixed(run_actor_critic, fixed,
                tuple(FIGURE6_SLIDERS) + tuple(FIGURE6_CHOICES) + ("n_trials",))
    controls = {name: slider(name, spec) for name, spec in FIGURE6_SLIDERS.items()}
    for name, options in FIGURE6_CHOICES.items():
        controls[name] = ipywidgets.Dropdown(description=name, options=options,
                                             value=options[0])

    def draw(**values):
        return figures.figure6_for(n_trials=n_trials, **fixed, **values)

    return panel(controls, draw)

