"""Interactive panels for the book: sliders that redraw the paper's figures.

Each panel is live in a running notebook (ipywidgets: every slider move reruns the
experiment, 100 seeds) and static in the HTML book (a Vega-Lite figure over a
precomputed grid of settings, which moves in the browser with no kernel;
`icm.experiments.panel_data.precompute` reads the book's grids from assets/). Both draw
`icm.experiments.panel_data.panel_curves_for`, so they show the same numbers at every
setting of the grid.
"""

from icm.widgets.actor_critic import FIGURE6_CHOICES, FIGURE6_SLIDERS, figure6_panel
from icm.widgets.goal_oriented import FIGURE5_SLIDERS, figure5_panel, sweep_panel
from icm.widgets.rod_toppling import FIGURE7_SLIDERS, figure7_panel
