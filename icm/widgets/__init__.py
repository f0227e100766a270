"""Interactive panels for the book: sliders that rerun an experiment and redraw a figure.

The panels need a running Jupyter kernel to move; in the static HTML book they show
the controls and the figure of their first run.
"""

from icm.widgets.actor_critic import FIGURE6_CHOICES, FIGURE6_SLIDERS, figure6_panel
from icm.widgets.goal_oriented import FIGURE5_SLIDERS, figure5_panel
from icm.widgets.rod_toppling import FIGURE7_CHOICES, FIGURE7_SLIDERS, figure7_panel
