"""The Figure 7 panel: sliders that rerun the curious Q-learner on the rods and redraw
one run at the moments of Figure 7 and at a chosen episode."""

import ipywidgets

from icm import _validate, figures
from icm.learners import predictors, q_learning
from icm.experiments import run_rod_toppling
from icm.widgets._common import check_fixed, panel, slider

DEFAULT_PANEL_EPISODES = 150
"""Episodes per run in `figure7_panel`: enough for both rods to be learned with the
default settings, few enough to redraw in about a second."""
FIGURE7_SLIDERS = {
    "epsilon": dict(min=0.0, max=1.0, step=0.05, value=q_learning.DEFAULT_EPSILON),
    "alpha": dict(min=0.05, max=1.0, step=0.05, value=q_learning.DEFAULT_ALPHA),
    "gamma": dict(min=0.0, max=1.0, step=0.05, value=q_learning.DEFAULT_GAMMA),
    "predictor_lr": dict(min=0.05, max=1.0, step=0.05, value=predictors.DEFAULT_LINEAR_LR),
    "initial_q": dict(min=0.0, max=1.0, step=0.05, value=q_learning.DEFAULT_INITIAL_Q),
    "episode": dict(min=1, max=DEFAULT_PANEL_EPISODES, step=1,
                    value=DEFAULT_PANEL_EPISODES),
}
"""Slider ranges of `figure7_panel`: the learner's allowed ranges (learning rates from
0.05 since 0 is not allowed; initial Q up to 1, the largest reward), and the episode
to show in the fourth column (its maximum follows the panel's n_episodes)."""
FIGURE7_CHOICES = {"reading": ("toppled", "all")}
"""Choices of `figure7_panel`, first option the default: when red counts as predicted
well (see `icm.experiments.rod_toppling.READINGS`); "toppled" first, as in the
chapter's Figure 7."""


def figure7_panel(n_episodes=DEFAULT_PANEL_EPISODES, seed=0, **fixed):
    """A panel that reruns one seed of the curious Q-learner on the rods and redraws
    Figure 7 with a fourth column at the chosen episode.

    Args:
      n_episodes: episodes per run (integer >= 1); the episode slider goes up to it.
      seed: the run's root seed.
      **fixed: other arguments of `run_rod_toppling`, held fixed (e.g. max_moves).

    Returns:
      An `ipywidgets.VBox`: sliders for epsilon, alpha, gamma, the predictor's
      learning rate, the initial Q and the episode, and a choice of reading, above the
      figure.

    Raises:
      ValueError: if n_episodes is not an integer >= 1.
    """
    n_episodes = _validate.integer_at_least("n_episodes", n_episodes, 1)
    _validate.seed("seed", seed)
    check_fixed(run_rod_toppling, fixed, tuple(FIGURE7_SLIDERS) + tuple(FIGURE7_CHOICES)
                + ("n_episodes", "n_seeds", "snapshot_episodes"))
    specs = dict(FIGURE7_SLIDERS)
    specs["episode"] = dict(specs["episode"], max=n_episodes,
                            value=min(specs["episode"]["value"], n_episodes))
    controls = {name: slider(name, spec) for name, spec in specs.items()}
    for name, options in FIGURE7_CHOICES.items():
        controls[name] = ipywidgets.Dropdown(description=name, options=options,
                                             value=options[0])

    def draw(**values):
        return figures.figure7_for(n_episodes=n_episodes, seed=seed, **fixed, **values)

    return panel(controls, draw, per_row=3)
