"""Figures of the button experiment: the console, its rules, and Figure 2."""

import matplotlib.patches
import numpy as np

import dm_env
import matplotlib.axes

from icm import _validate
from icm.envs import buttons
from icm.figures._common import TASK_COLOURS, check_title, new_figure


LIGHT_COLOURS = {0: "#d9d9d9", 1: TASK_COLOURS["red"], 2: TASK_COLOURS["green"]}


def draw_console(ax, lights, boxes=(0, 0), pressed=None, title=None):
    """Draws the button console: 5 buttons with their lights, and the two boxes.

    Args:
      ax: a matplotlib axes.
      lights: 5 values, 0 off, 1 red, 2 green.
      boxes: (red, green), 1 open.
      pressed: index of the button being pressed, drawn with a hand marker.
      title: axes title.
    """
    _validate.instance("ax", ax, matplotlib.axes.Axes, "a matplotlib Axes")
    lights = buttons.check_lights(lights)
    boxes = _validate.finite_array("boxes", boxes, shape=(len(buttons.BOX_NAMES),))
    if pressed is not None:
        pressed = _validate.integer("pressed", pressed, 0, buttons.N_BUTTONS - 1)
    check_title(title)
    ax.set_xlim(-0.6, 4.6)
    ax.set_ylim(-0.9, 2.0)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.add_patch(matplotlib.patches.FancyBboxPatch(
        (-0.5, -0.5), 5.0, 1.0, boxstyle="round,pad=0.05", facecolor="#f2f2f2",
        edgecolor="#555555"))
    for b, light in enumerate(lights):
        ax.add_patch(matplotlib.patches.Circle((b, 0), 0.32, facecolor=LIGHT_COLOURS[int(light)],
                                               edgecolor="#333333", linewidth=1.5))
        ax.text(b, -0.75, str(b), ha="center", va="center", fontsize=8, color="#555555")
    if pressed is not None:
        ax.annotate("", xy=(pressed, 0.35), xytext=(pressed, 1.0),
                    arrowprops=dict(arrowstyle="-|>", color="black", linewidth=2))
    # The boxes are wide enough for their word at the smallest text the figure may
    # show (`Figure.fit_text`) when a strip of four consoles is shown 740 px wide.
    for i, (name, x) in enumerate((("red", 0.8), ("green", 3.2))):
        is_open = bool(boxes[i])
        colour = TASK_COLOURS[name]
        ax.add_patch(matplotlib.patches.Rectangle((x - 0.8, 1.1), 1.6, 0.75,
                                                  facecolor=colour if is_open else "white",
                                                  edgecolor=colour, linewidth=2,
                                                  alpha=0.85 if is_open else 1.0))
        ax.text(x, 1.475, "open" if is_open else "shut", ha="center", va="center",
                fontsize=7.5, color="white" if is_open else colour, weight="bold")
    if title:
        ax.set_title(title, fontsize=9)


def trial_figure(steps, actions):
    """One trial as a strip: the console before the first press, then after each press.

    Args:
      steps: the trial's dm_env time steps, from the FIRST one on.
      actions: the buttons pressed (one fewer than steps).
    """
    if not isinstance(steps, (list, tuple)) or not steps or \
            not all(isinstance(s, dm_env.TimeStep) for s in steps):
        raise _validate.ArgumentTypeError(f"steps must be a non-empty list of dm_env time "
                                          f"steps, got {_validate.show(steps)}")
    if not isinstance(actions, (list, tuple, np.ndarray)) or len(actions) != len(steps) - 1:
        raise ValueError(f"actions must list the {len(steps) - 1} buttons pressed between "
                         f"the steps, got {_validate.show(actions)}")
    fig, axes = new_figure(width=2.3 * len(steps), height=1.9, ncols=len(steps))
    for i, (ax, step) in enumerate(zip(np.atleast_1d(axes), steps)):
        obs = step.observation
        if i == 0:
            title = "start of the trial"
        else:
            title = f"press {i}: button {int(actions[i - 1])}"
        draw_console(ax, obs["lights"], obs["boxes"],
                     pressed=None if i == 0 else int(actions[i - 1]), title=title)
    return fig


def outcome_table_figure(red_button=None):
    """The rules as a table: for each of the 4 light layouts (rows) and each button
    pressed (columns), the box that opens. Red's column never changes; green's moves."""
    red_button = buttons.DEFAULT_RED_BUTTON if red_button is None else \
        buttons.check_red_button(red_button)
    layouts = buttons.layouts(red_button)
    fig, ax = new_figure(width=6.4, height=3.4)
    for row, lights in enumerate(layouts):
        for b in range(buttons.N_BUTTONS):
            boxes = buttons.press_outcome(lights, b)
            colour = (TASK_COLOURS["red"] if boxes[0] else
                      TASK_COLOURS["green"] if boxes[1] else "#f0f0f0")
            ax.add_patch(matplotlib.patches.Rectangle((b, row), 1, 1, facecolor=colour,
                                                      edgecolor="white", linewidth=2))
            label = "red box" if boxes[0] else "green box" if boxes[1] else "nothing"
            ax.text(b + 0.5, row + 0.5, label, ha="center", va="center", fontsize=8,
                    color="white" if boxes.any() else "#777777")
    ax.set_xlim(0, buttons.N_BUTTONS)
    ax.set_ylim(len(layouts), 0)
    ax.set_xticks(np.arange(buttons.N_BUTTONS) + 0.5, [f"press {b}" for b in range(5)])
    ax.set_yticks(np.arange(len(layouts)) + 0.5,
                  [f"green at {int(np.flatnonzero(l == buttons.GREEN)[0])}" for l in layouts])
    ax.tick_params(length=0)
    for spine in ax.spines.values():
        spine.set_visible(False)
    ax.set_title(f"What each press does, in each of the 4 layouts (red at {red_button})",
                 fontsize=10)
    return fig




def _box(ax, xy, text, colour):
    x, y = xy
    ax.add_patch(matplotlib.patches.FancyBboxPatch(
        (x - 0.16, y - 0.08), 0.32, 0.16, boxstyle="round,pad=0.02",
        facecolor=colour, edgecolor="#333333", linewidth=1.2))
    ax.text(x, y, text, ha="center", va="center", fontsize=11, weight="bold")


def _arrow(ax, start, end, label, label_offset=(0.0, 0.0), rad=0.0):
    ax.annotate("", xy=end, xytext=start,
                arrowprops=dict(arrowstyle="-|>", color="#333333", linewidth=1.4,
                                shrinkA=2, shrinkB=2,
                                connectionstyle=f"arc3,rad={rad}"))
    mid = ((start[0] + end[0]) / 2 + label_offset[0], (start[1] + end[1]) / 2 + label_offset[1])
    ax.text(*mid, label, ha="center", va="center", fontsize=9,
            bbox=dict(boxstyle="round,pad=0.2", facecolor="white", edgecolor="none"))


def figure2():
    """Figure 2: the modular goal-oriented architecture, with the order of its messages.

    (1) the actor observes the environment; (2) it asks the predictor what an action
    would do; (3) the predicted effect goes to the interest module; (4) which says how
    interesting it is. Steps 2-4 repeat for every action; then the actor acts, and the
    predictor and interest module learn from what happened.
    """
    fig, ax = new_figure(width=6.7, height=4.6)
    ax.set_xlim(0, 1.6)
    ax.set_ylim(-0.22, 1)
    ax.axis("off")
    env, actor, predictor, interest = (0.25, 0.5), (0.8, 0.5), (1.35, 0.8), (1.35, 0.2)
    _box(ax, env, "Environment", "#dde7f3")
    _box(ax, actor, "Actor", "#f3e6d0")
    _box(ax, predictor, "Predictor", "#e2f0d9")
    _box(ax, interest, "Interest", "#f6dcdc")
    # The labels of the two short arrows sit above and below the boxes, clear of them.
    _arrow(ax, (0.41, 0.55), (0.64, 0.55), "1  observation", (0, 0.13))
    _arrow(ax, (0.64, 0.44), (0.41, 0.44), "action", (0, -0.13))
    _arrow(ax, (0.9, 0.6), (1.19, 0.78), "2  context, action?", (-0.06, 0.06))
    _arrow(ax, (1.35, 0.71), (1.35, 0.29), "3  predicted effect\n= task", (0.0, 0.0))
    _arrow(ax, (1.19, 0.22), (0.9, 0.4), "4  interest of task", (-0.05, -0.06))
    ax.text(0.8, -0.2, "2-3-4 repeat for each of the 5 buttons; the actor\nthen picks "
            "an action epsilon-greedily on interest\nand executes it",
            ha="center", va="bottom", fontsize=8.5, style="italic")
    return fig.describe(
        "The paper's Figure 2 as a diagram of four boxes: Environment, Actor, Predictor "
        "and Interest. Arrows: (1) the environment's observation goes to the actor; (2) "
        "the actor asks the predictor about a context and action; (3) the predicted "
        "effect, a task, goes to the interest module; (4) the interest of that task "
        "goes back to the actor, which sends its action to the environment. Steps 2 to 4 "
        "repeat for each of the 5 buttons before the actor picks one epsilon-greedily.")
