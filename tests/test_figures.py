"""Figures and widget panels draw what the results hold."""

import matplotlib.figure
import numpy as np
import pytest

import icm
from icm import figures


@pytest.fixture(scope="module")
def small_run():
    return icm.experiments.run_goal_oriented(n_seeds=12, n_trials=25, seed=3)


def test_figure5_draws_the_mean_interest_of_each_task_with_a_band(small_run):
    fig = figures.figure5(small_run)
    assert isinstance(fig, matplotlib.figure.Figure)
    ax = fig.axes[0]
    lines = [l for l in ax.get_lines() if l.get_label().startswith("open the")]
    assert [l.get_label() for l in lines] == ["open the red box", "open the green box"]
    for i, line in enumerate(lines):
        assert np.allclose(line.get_ydata(), small_run.interest[:, :, i].mean(axis=0))
        assert np.array_equal(line.get_xdata(), np.arange(1, 26))
    assert len(ax.collections) == 2  # one confidence band per task
    assert fig.png()[:8] == b"\x89PNG\r\n\x1a\n"


def test_band_contains_the_mean_and_shrinks_with_more_seeds():
    values = np.random.default_rng(0).normal(size=(400, 3))
    mean, low, high = icm.stats.mean_band(values[:20])
    assert np.all(low < mean) and np.all(mean < high)
    _, low_many, high_many = icm.stats.mean_band(values)
    assert np.all(high_many - low_many < high - low)


def test_first_from_which_finds_where_a_condition_holds_for_good():
    condition = np.array([[0, 1, 0, 1, 1], [1, 1, 1, 1, 1], [1, 1, 1, 1, 0]], dtype=bool)
    assert icm.stats.first_from_which(condition).tolist() == [3, 0, -1]


def test_diagrams_and_console_figures_draw():
    assert figures.figure2().axes
    assert len(figures.outcome_table_figure().axes[0].patches) == 20


def test_comes_first_handles_never():
    first = np.array([2, 5, -1, 3, 4])
    second = np.array([4, 5, 3, -1, -1])
    assert icm.stats.comes_first(first, second).tolist() == [True, False, False, True, True]
    assert not icm.stats.comes_first(-1, -1)


def _png_text(fig):
    import io

    from PIL import Image

    return Image.open(io.BytesIO(fig.png())).text


def test_a_figure_carries_its_alternative_text_in_words(small_run):
    fig = figures.figure5(small_run)
    png, metadata = fig._repr_png_()
    alt = metadata["alt"]
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and _png_text(fig)["Description"] == alt
    for words in ("open the red box (solid line, circles)",
                  "open the green box (dashed line, squares)", "Horizontal axis: trial",
                  "Vertical axis: interest"):
        assert words in alt, (words, alt)
    fig.describe("Interest in red peaks first.")
    assert fig.alt_text().startswith("Interest in red peaks first. ")


def test_red_and_green_differ_in_more_than_colour(small_run):
    for fig in (figures.figure5(small_run), figures.mastery_figure(small_run)):
        for ax in fig.axes:
            lines = {l.get_label(): l for l in ax.get_lines() if "red" in l.get_label()
                     or "green" in l.get_label()}
            red = [l for label, l in lines.items() if "red" in label]
            green = [l for label, l in lines.items() if "green" in label]
            for r, g in zip(red, green):
                assert (r.get_linestyle(), r.get_marker()) != (g.get_linestyle(), g.get_marker())
                assert r.get_linestyle() != g.get_linestyle()


def test_small_text_is_raised_to_what_reads_where_the_figure_is_shown():
    fig, ax = figures.new_figure(width=10.0, height=3.0)
    ax.plot([0, 1], [0, 1])
    ax.set_title("tiny", fontsize=4)
    ax.tick_params(labelsize=3)
    text = _png_text(fig)
    # 10 inches at 110 dpi are shown 740 px wide: 16 px there is 23.8 px in the PNG.
    smallest = float(text["icm:smallest-text-px"])
    assert smallest * figures._common.DISPLAY_WIDTH_PX / (10.0 * fig.png_dpi) >= 16 - 1e-3
    assert ax.title.get_fontsize() == pytest.approx(fig.min_text_points())


def test_the_png_counts_legends_over_data_and_overlapping_texts():
    fig, ax = figures.new_figure()
    x = np.linspace(0, 1, 50)
    ax.plot(x, np.ones_like(x), label="a flat line")  # runs under the legend
    ax.legend(loc="center")
    assert int(_png_text(fig)["icm:legend-overlaps"]) > 0
    fig, ax = figures.new_figure()
    ax.plot(x, x, label="a rising line")
    ax.legend(loc="upper left")  # the line is far below-right of it
    assert int(_png_text(fig)["icm:legend-overlaps"]) == 0
    ax.text(0.5, 0.5, "one")
    ax.text(0.5, 0.5, "two")
    assert int(_png_text(fig)["icm:text-overlaps"]) == 1

    # Two boxed labels whose arrows point at neighbouring things: apart, however their
    # arrows run; the same labels on one another: counted.
    fig, ax = figures.new_figure()
    box = dict(boxstyle="round", facecolor="white")
    ax.annotate("left label", xy=(0.52, 0.1), xytext=(0.1, 0.3), bbox=box,
                arrowprops=dict(arrowstyle="->"))
    ax.annotate("right label", xy=(0.48, 0.1), xytext=(0.7, 0.8), bbox=box,
                arrowprops=dict(arrowstyle="->"))
    assert int(_png_text(fig)["icm:text-overlaps"]) == 0
    ax.annotate("on the right one", xy=(0.5, 0.1), xytext=(0.72, 0.8), bbox=box,
                arrowprops=dict(arrowstyle="->"))
    assert int(_png_text(fig)["icm:text-overlaps"]) == 1
