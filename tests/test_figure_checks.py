"""The figures' own checks (icm.figures._common.Figure.png): one drawing per PNG, the
measures read from that drawing, and no text running out of the box it is written on
(Figure 1.1's box labels once read "ope" and "shut" cut at the box's edge)."""

import io

import matplotlib.patches
import pytest
from PIL import Image

import icm
from icm import figures
from icm.envs import buttons
from icm.figures import _common


def _measures(fig):
    return Image.open(io.BytesIO(fig.png())).text


def _a_box_with(text, width):
    fig, ax = figures.new_figure(width=4.0, height=2.0)
    ax.set_xlim(0, 4)
    ax.set_ylim(0, 2)
    ax.add_patch(matplotlib.patches.Rectangle((2 - width / 2, 0.7), width, 0.6,
                                              facecolor="#d62728"))
    ax.text(2, 1.0, text, ha="center", va="center", color="white")
    return fig


def test_a_text_wider_than_its_box_is_counted_and_one_that_fits_is_not():
    assert _measures(_a_box_with("a label far too long for its box", 0.8))[
        "icm:text-outside-box"] == "1"
    assert _measures(_a_box_with("fits", 3.0))["icm:text-outside-box"] == "0"
    # A text that is on no box is not held to one, however long.
    fig, ax = figures.new_figure(width=4.0, height=2.0)
    ax.text(0.5, 0.5, "free text, on no box at all", ha="center")
    assert _measures(fig)["icm:text-outside-box"] == "0"


def test_the_smallest_box_under_a_text_is_the_one_that_must_hold_it():
    # A label on a small box that lies on a large one (a button on a console): the
    # small box must hold it, the large one around both does not excuse it.
    fig = _a_box_with("a label far too long for its box", 0.8)
    ax = fig.axes[0]
    ax.add_patch(matplotlib.patches.Rectangle((0.05, 0.05), 3.9, 1.9, facecolor="none",
                                              edgecolor="black", zorder=0))
    assert _measures(fig)["icm:text-outside-box"] == "1"
    # Round shapes: a text on a button (a circle) fits inside its round edge or not.
    fig, ax = figures.new_figure(width=4.0, height=4.0)
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    ax.set_aspect("equal")
    ax.add_patch(matplotlib.patches.Circle((0, 0), 0.5))
    ax.text(0, 0, "1", ha="center", va="center")
    ax.text(0, 0.42, "near the rim, too wide", ha="center", va="center")
    assert _measures(fig)["icm:text-outside-box"] == "1"


def _trial(seed=0):
    """The trial of Figure 1.1: the red button, an unlit one, the green one."""
    env = icm.envs.load("buttons", seed=seed)
    step = env.reset()
    lights = step.observation["lights"]
    unlit = [b for b in range(buttons.N_BUTTONS) if lights[b] == buttons.OFF][0]
    actions = [env.red_button, unlit, env.green_button]
    return [step] + [env.step(a) for a in actions], actions


@pytest.mark.parametrize("presses", [0, 1, 3])
def test_figure_1_1s_box_labels_fit_their_boxes(presses):
    steps, actions = _trial()
    fig = figures.trial_figure(steps[:presses + 1], actions[:presses])
    measures = _measures(fig)
    assert measures["icm:text-outside-box"] == "0", measures
    assert measures["icm:text-overlaps"] == "0", measures
    words = sorted(t.get_text() for ax in fig.axes for t in ax.texts if t.get_text().isalpha())
    assert words.count("open") == (presses >= 1) + (presses >= 3), words  # red, then green


def test_the_rules_tables_labels_fit_their_cells():
    assert _measures(figures.outcome_table_figure())["icm:text-outside-box"] == "0"


def test_a_png_is_one_drawing_with_its_measures(monkeypatch):
    # The PNG is drawn once: the text fitted before, the measures read from the same
    # renderer, the pixels written as drawn; a figure with a constrained layout gets
    # the layout pass without rendering that savefig makes first. Each further drawing
    # (savefig after an inspection's own, as before) costs a redraw.
    drawn, rendered = [], []
    draw = _common.Figure.draw

    def spy(self, renderer):
        drawn.append(renderer)
        if "draw_path" not in vars(renderer):  # not a layout pass (draws disabled)
            rendered.append(renderer)
        return draw(self, renderer)

    monkeypatch.setattr(_common.Figure, "draw", spy)
    run = icm.experiments.run_goal_oriented(n_seeds=4, n_trials=12, seed=1)
    fig = figures.figure5(run)
    png = fig.png()
    assert len(rendered) == 1  # one drawing into pixels
    assert len(drawn) == 2  # and the layout pass before it (constrained layout)
    image = Image.open(io.BytesIO(png))
    # At png_dpi: the PNG's size is the figure's at that resolution, the figure's own
    # dpi is left as it was.
    assert image.size == (round(fig.get_figwidth() * fig.png_dpi),
                          round(fig.get_figheight() * fig.png_dpi))
    assert fig.dpi != fig.png_dpi
    for key in ("Description", "icm:smallest-text-px", "icm:legend-overlaps",
                "icm:text-overlaps", "icm:text-outside-box"):
        assert key in image.text, key
    drawn.clear()
    rendered.clear()
    panel = figures.figure5_panel_figure(run)  # a live panel: quick, a fixed layout
    assert panel.quick_png and panel.get_layout_engine() is None
    panel.png()
    assert len(rendered) == 1 and len(drawn) == 1
