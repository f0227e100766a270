"""Interactive panels for the book: sliders that rerun an experiment and redraw a figure.

The panels need a running Jupyter kernel to move; in the static HTML book they show
the controls and the figure of their first run.
"""

from icm.widgets.goal_oriented import FIGURE5_SLIDERS, figure5_panel
