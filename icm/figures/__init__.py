"""Figures of the paper, rebuilt from the library's own runs.

Every function returns a `Figure` (a matplotlib Figure made without pyplot that Jupyter
shows as a PNG), so the library never touches the global backend, a notebook shows
each figure exactly once, and a figure redrawn by a widget is not kept alive by pyplot.
"""

from icm.figures._common import (DISPLAY_WIDTH_PX, TASK_COLOURS, Figure, new_figure,
                                 plot_mean_band)
from icm.figures.actor_critic import (figure3, figure4, figure6, figure6_grid,
                                      practice_figure)
from icm.figures.buttons import draw_console, figure2, outcome_table_figure, trial_figure
from icm.figures.forming_actions import (coverage_figure, coverage_maps_figure,
                                        first_press_figure, goal_choice_figure,
                                        learned_presses_figure, presses_formed_figure,
                                        record_learned_press, test_error_figure)
from icm.figures.goal_oriented import figure5, figure5_grid, mastery_figure
from icm.figures.icub import (animation, animation_html, cameras_figure, figure1,
                              observation_table, press_trace_figure, record_move,
                              record_press, topple_map_figure)
from icm.figures.rod_toppling import (figure7, physics_comparison_figure,
                                      topple_share_figure)
from icm.figures.robustness import robustness_map
from icm.figures.panel_plots import (draw_curves, figure5_panel_figure, figure6_panel_figure,
                                figure7_panel_figure, panel_figure, sweep_figure)
from icm.figures.sweep import sweep_heatmap
