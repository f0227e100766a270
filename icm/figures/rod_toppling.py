"""Figures of the rod-toppling chapter: Figure 7 (Q-table, predictor, state confidence
and prediction error at the three moments of a run), the multi-seed summary, and the
physics run beside the tabular one."""

import functools

import matplotlib.cm
import matplotlib.collections
import matplotlib.colors
import matplotlib.patches
import numpy as np

from icm import _validate
from icm.envs import rods
from icm.experiments import rod_toppling as _rod_toppling
from icm.experiments.results import check_results
from icm.experiments.rod_toppling import RodTopplingResult
from icm.figures._common import (check_result, legend_below, markevery, new_figure,
                                 plot_mean_band, series_style)

_MADE_BY = "icm.experiments.run_rod_toppling"
from icm.figures.icub import ROD_COLOURS

NONE_COLOUR = "#9a9a9a"
"""Colour of episodes that ended on the time limit, with no rod toppled."""
Q_COLOURMAP = "viridis"
"""Colour map of the Q-table panels (on a square-root scale from 0 to 1, so that the
small values of a bored robot stay visible)."""
CONFIDENCE_COLOURMAP = "Greens"
"""Colour map of the state-confidence panels (0 to 1)."""
_Q_NORM = matplotlib.colors.PowerNorm(0.5, vmin=0.0, vmax=1.0)
_ARROW = {0: (0.0, 1.0), 1: (0.0, -1.0), 2: (-1.0, 0.0), 3: (1.0, 0.0)}  # action -> (dx, dy)


@functools.lru_cache(maxsize=1)
def rod_cells():
    """{"red": cell, "blue": cell}: the grid cell nearest each rod, read from the model
    (assets/rods.xml)."""
    physics = rods.load_physics()
    physics.forward()
    cells = [(c, r) for c in range(rods.N_COLUMNS) for r in range(rods.N_ROWS)]
    out = {}
    for name in rods.ROD_NAMES:
        position = physics.named.data.xpos[f"{name}_rod"][:2]
        out[name] = min(cells, key=lambda cell: np.linalg.norm(
            physics.cell_centre(cell)[:2] - position))
    return out


def _triangle(cell, action):
    """The quarter of a cell's square on the side `action` moves to: a triangle."""
    x, y = cell
    dx, dy = _ARROW[action]
    # The edge on that side, seen from the centre.
    if dx == 0:
        edge = [(x - 0.5, y + 0.5 * dy), (x + 0.5, y + 0.5 * dy)]
    else:
        edge = [(x + 0.5 * dx, y - 0.5), (x + 0.5 * dx, y + 0.5)]
    return [(x, y)] + edge


def _grid_axes(ax):
    """Sets up `ax` for the 5 x 3 grid: columns left to right, rows from the robot
    (bottom) outwards, the cells the hand cannot rest on hatched, the rods drawn."""
    ax.set_xlim(-0.55, rods.N_COLUMNS - 0.45)
    ax.set_ylim(-0.55, rods.N_ROWS - 0.45)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    for spine in ax.spines.values():
        spine.set_visible(False)
    standable = rods.load_topple_map()["standable"]
    for column in range(rods.N_COLUMNS):
        for row in range(rods.N_ROWS):
            if (column, row) not in standable:
                ax.add_patch(matplotlib.patches.Rectangle(
                    (column - 0.5, row - 0.5), 1, 1, facecolor="white", edgecolor="#cccccc",
                    hatch="////", linewidth=0.5))
    for name, (column, row) in rod_cells().items():
        ax.add_patch(matplotlib.patches.Rectangle(
            (column - 0.16, row - 0.16), 0.32, 0.32, facecolor=ROD_COLOURS[name],
            edgecolor="black", linewidth=0.8, zorder=5))


def draw_q_table(ax, q_table):
    """Draws a Q-table [column, row, action] on the grid: each cell split in four
    triangles (the side each move goes to) coloured by Q, and an arrow for the greedy
    move (none where every move ties, e.g. a cell never visited).

    Returns:
      The collection of triangles (a mappable for a colour bar).
    """
    q_table = _check_grid_values("q_table", q_table, (len(rods.ACTIONS),))
    _grid_axes(ax)
    patches, values = [], []
    for (column, row), q in _standable_cells(q_table):
        for action in range(len(rods.ACTIONS)):
            patches.append(matplotlib.patches.Polygon(_triangle((column, row), action)))
            values.append(q[action])
        if np.ptp(q) > 0:
            best = int(np.argmax(q))
            dx, dy = _ARROW[best]
            ax.annotate("", xy=(column + 0.38 * dx, row + 0.38 * dy), xytext=(column, row),
                        arrowprops=dict(arrowstyle="-|>", color="white", linewidth=1.6,
                                        shrinkA=0, shrinkB=0), zorder=4)
    collection = matplotlib.collections.PatchCollection(
        patches, cmap=Q_COLOURMAP, norm=_Q_NORM, edgecolor="white", linewidth=0.4)
    collection.set_array(np.array(values))
    ax.add_collection(collection)
    return collection


def _check_grid_values(name, values, tail):
    """`values` as a float array [column, row, *tail]; NaN is allowed (cells where the
    hand never rests), infinity is not."""
    shape = (rods.N_COLUMNS, rods.N_ROWS) + tail
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise _validate.ArgumentTypeError(f"{name} must be an array of shape {shape}, got "
                                          f"{_validate.show(values)}") from None
    if array.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {array.shape}")
    if np.any(np.isinf(array)):
        raise ValueError(f"{name} must not hold infinities, got {_validate.show(values)}")
    return array


def _standable_cells(grid):
    for column in range(rods.N_COLUMNS):
        for row in range(rods.N_ROWS):
            values = np.asarray(grid[column, row])
            if not np.all(np.isnan(values)):
                yield (column, row), values


def _predicted_colour(p_red, p_blue):
    """White where no topple is predicted, towards a rod's colour as its predicted
    topple goes to 1."""
    white = np.ones(3)
    red = np.array(matplotlib.colors.to_rgb(ROD_COLOURS["red"]))
    blue = np.array(matplotlib.colors.to_rgb(ROD_COLOURS["blue"]))
    colour = white + p_red * (red - white) + p_blue * (blue - white)
    return tuple(np.clip(colour, 0, 1))


def draw_predictor(ax, predictions):
    """Draws the linear predictor [column, row, action, rod] on the grid: each cell's
    four triangles (the side each move goes to) coloured from white (predicts both
    rods stay up) to a rod's colour (predicts that rod topples)."""
    predictions = _check_grid_values("predictions", predictions,
                                     (len(rods.ACTIONS), len(rods.ROD_NAMES)))
    _grid_axes(ax)
    for (column, row), p in _standable_cells(predictions):
        for action in range(len(rods.ACTIONS)):
            ax.add_patch(matplotlib.patches.Polygon(
                _triangle((column, row), action), facecolor=_predicted_colour(*p[action]),
                edgecolor="#dddddd", linewidth=0.4))


def draw_confidence(ax, confidence):
    """Draws the state confidence [column, row] on the grid, with its value in each
    cell.

    Returns:
      The collection of cells (a mappable for a colour bar).
    """
    confidence = _check_grid_values("confidence", confidence, ())
    _grid_axes(ax)
    patches, values = [], []
    for (column, row), c in _standable_cells(confidence):
        patches.append(matplotlib.patches.Rectangle((column - 0.5, row - 0.5), 1, 1))
        values.append(float(c))
        ax.text(column, row - 0.26, _short(float(c)), ha="center", va="center", fontsize=7.5,
                color="white" if c > 0.6 else "black", zorder=6)
    collection = matplotlib.collections.PatchCollection(
        patches, cmap=CONFIDENCE_COLOURMAP, norm=matplotlib.colors.Normalize(0, 1),
        edgecolor="white", linewidth=0.6)
    collection.set_array(np.array(values))
    ax.add_collection(collection)
    return collection


def _short(value):
    """A value between 0 and 1 in at most three characters: "0", ".25", "1"."""
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return text[1:] if text.startswith("0.") else text


def draw_prediction_errors(ax, result, seed, episode, last_episode, reading="all"):
    """Draws, for episodes 1..`episode` of one run, the prediction error paid as reward
    in each episode (dots, one colour per rod) and the largest error left on the
    rod's pairs in the given reading (lines: every pair that topples it, or those it
    has been toppled from), with the 0.1 line of "predicted well"."""
    check_result("result", result, RodTopplingResult, _MADE_BY)
    seed = _validate.integer("seed", seed, 0, result.n_seeds - 1)
    episode = _validate.integer("episode", episode, 1, result.n_episodes)
    last_episode = _validate.integer("last_episode", last_episode, 1)
    x = np.arange(1, episode + 1)
    for i, rod in enumerate(_rod_toppling.RODS):
        colour = ROD_COLOURS[rod]
        paid = result.prediction_error[seed, :episode, i]
        hit = paid > 0
        style = series_style(rod)
        ax.plot(x[hit], paid[hit], style["marker"], color=colour, markersize=4, alpha=0.8,
                label=f"error paid, {rod}")
        ax.plot(x, result.rod_errors(reading)[seed, :episode, i], style["linestyle"],
                color=colour, linewidth=1.4, label=f"largest error left, {rod}")
    ax.axhline(_rod_toppling.WELL_PREDICTED_ERROR, color="black", linestyle=":", linewidth=0.8)
    ax.set_xlim(0.5, last_episode + 1.5)
    ax.set_ylim(-0.03, 1.08)
    ax.set_xlabel("episode", fontsize=9)
    ax.tick_params(labelsize=8)


def figure7(result, seed=0, reading="all", episode=None):
    """Figure 7: one run's Q-table, predictor, state confidence and prediction errors
    at the paper's moments, found in the run's data: (a) after the first episode, (b)
    after the episode from which red is predicted well, (c) after the first episode
    that ends with the blue rod toppled.

    Args:
      result: a `RodTopplingResult`.
      seed: which run of `result` to draw (0..n_seeds-1).
      reading: when red counts as predicted well, "all" (every pair that topples it)
        or "toppled" (every pair it has been toppled from); see
        `icm.experiments.rod_toppling.READINGS`.
      episode: also draw the run after this episode (it must be one of the run's
        `snapshot_episodes`).

    Returns:
      The `Figure`: one column per moment; rows Q-table (greedy move as an arrow),
      predictor, state confidence, prediction error over the episodes so far.

    Raises:
      ValueError: for a seed outside the result, an unknown reading, or an episode
        without a snapshot.
    """
    check_result("result", result, RodTopplingResult, _MADE_BY)
    seed = _validate.integer_in_range("seed", seed, 0, result.n_seeds - 1)
    _validate.one_of("reading", reading, _rod_toppling.READINGS)
    red_well = "red predicted well" if reading == "all" else "red predicted well (toppled)"
    columns = [("(a) after the first episode", "first episode"),
               ("(b) red predicted well", red_well),
               ("(c) first blue topple", "blue begins")]
    if episode is not None:
        episode = _validate.integer("episode", episode, 1, result.n_episodes)
        name = f"episode {episode}"
        if name not in result.snapshot_names:
            raise ValueError(f"episode must be one of the run's snapshot_episodes "
                             f"{result.settings['snapshot_episodes']}, got {episode!r}")
        columns.append((f"(d) episode {episode}", name))
    snapshots = [result.snapshot(seed, name) for _, name in columns]
    last = max([s["episode"] for s in snapshots if s is not None] + [1])

    fig, axes = new_figure(width=2.0 * len(columns) + 0.9, height=9.4, ncols=len(columns),
                           nrows=4, squeeze=False)
    q_mappable = c_mappable = None
    for j, ((title, _), snap) in enumerate(zip(columns, snapshots)):
        episode_text = "never in this run" if snap is None else f"episode {snap['episode']}"
        # A column named after its episode needs it said once.
        heading = title if title.endswith(episode_text) else f"{title}\n{episode_text}"
        heading = heading.replace(") ", ")\n", 1)
        axes[0, j].set_title(heading, fontsize=10)
        if snap is None:
            for ax in axes[:, j]:
                ax.set_axis_off()
            continue
        q_mappable = draw_q_table(axes[0, j], snap["q_table"])
        draw_predictor(axes[1, j], snap["predictions"])
        c_mappable = draw_confidence(axes[2, j], snap["confidence"])
        draw_prediction_errors(axes[3, j], result, seed, snap["episode"], last, reading)
    for i, label in enumerate(["Q-table, greedy move", "predictor", "state confidence",
                               "prediction error"]):
        axes[i, 0].set_ylabel(label, fontsize=10)
    handles, labels = axes[3, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=2, frameon=False,
               fontsize=9)
    if q_mappable is not None:
        bar = fig.colorbar(q_mappable, ax=axes[0, :], shrink=0.8, pad=0.01)
        bar.set_label("Q", fontsize=8)
        bar.ax.tick_params(labelsize=7)
    red_map = matplotlib.colors.LinearSegmentedColormap.from_list(
        "predicted", ["white", ROD_COLOURS["red"]])
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(matplotlib.colors.Normalize(0, 1), red_map),
                       ax=axes[1, :], shrink=0.8, pad=0.01)
    bar.set_label("predicted topple\n(blue likewise)", fontsize=8)
    bar.ax.tick_params(labelsize=7)
    if c_mappable is not None:
        bar = fig.colorbar(c_mappable, ax=axes[2, :], shrink=0.8, pad=0.01)
        bar.set_label("confidence", fontsize=8)
        bar.ax.tick_params(labelsize=7)
    fig.suptitle(f"Run {seed}, red predicted well read as \"{reading}\"", fontsize=10)
    moments = [f"{title.split(')')[0]}) at episode {snap['episode']}" if snap is not None
               else f"{title.split(')')[0]}) never" for (title, _), snap in zip(columns, snapshots)]
    return fig.describe(
        f"Figure 7 for run {seed}: the Q-table, the predictor, the state confidence and "
        f"the prediction errors on the 5 by 3 grid at the paper's moments, "
        f"{', '.join(moments)}.")


def _shares(result, value):
    return (result.toppled == value).astype(float)


def topple_share_figure(result):
    """The multi-seed summary: left, the share of episodes that end with each rod
    toppled (or none) against episode, mean over seeds with 95% bands; right, the
    share of seeds whose predictor has learned each rod by each episode (both
    readings), and the share that have toppled blue at least once."""
    check_result("result", result, RodTopplingResult, _MADE_BY)
    fig, (left, right) = new_figure(width=6.7, height=8.2, nrows=2)
    for i, rod in enumerate(_rod_toppling.RODS):
        plot_mean_band(left, _shares(result, i), ROD_COLOURS[rod], f"{rod} rod toppled",
                       **series_style(rod))
    plot_mean_band(left, _shares(result, -1), NONE_COLOUR, "none (time limit)",
                   linestyle=":", marker="x")
    left.set(xlabel="episode", ylabel="share of episodes (mean over seeds)",
             xlim=(1, result.n_episodes), ylim=(0, 1.02))
    left.set_title(f"How episodes end, {result.n_seeds} seeds, 95% band", fontsize=10)
    legend_below(left, ncols=3)

    episodes = np.arange(1, result.n_episodes + 1)
    for reading, style in (("all", "-"), ("toppled", "--")):
        well = result.well_predicted(reading)
        for i, rod in enumerate(_rod_toppling.RODS):
            share = [np.mean((well[:, i] >= 1) & (well[:, i] <= e)) for e in episodes]
            right.step(episodes, share, where="post", color=ROD_COLOURS[rod], linestyle=style,
                       linewidth=1.8, label=f"{rod} predicted well ({reading})",
                       marker=series_style(rod)["marker"], markersize=5,
                       markevery=markevery(len(episodes), series_style(rod)["marker"]))
    first_blue = result.first_topple("blue")
    share = [np.mean((first_blue >= 1) & (first_blue <= e)) for e in episodes]
    right.step(episodes, share, where="post", color="black", linestyle=":", linewidth=1.4,
               label="blue toppled at least once")
    right.set(xlabel="episode", ylabel="share of seeds", xlim=(1, result.n_episodes),
              ylim=(0, 1.02))
    right.set_title("When each rod is learned", fontsize=10)
    legend_below(right, ncols=2)
    return fig


def physics_comparison_figure(runs):
    """How the episodes of single runs end, one row per run: a square per episode
    coloured by the rod toppled (grey: none), its height the number of moves.

    Args:
      runs: a dict {row label: RodTopplingResult}; the first seed of each is drawn.
    """
    check_results("runs", runs, RodTopplingResult)
    fig, axes = new_figure(width=9.0, height=1.1 + 1.4 * len(runs), nrows=len(runs),
                           sharex=True, squeeze=False)
    colours = {0: ROD_COLOURS["red"], 1: ROD_COLOURS["blue"], -1: NONE_COLOUR}
    top = max(int(r.episode_length[0].max()) for r in runs.values())
    for ax, (label, result) in zip(axes[:, 0], runs.items()):
        episodes = np.arange(1, result.n_episodes + 1)
        ax.bar(episodes, result.episode_length[0], width=0.85,
               color=[colours[int(t)] for t in result.toppled[0]])
        ax.set_ylabel("moves", fontsize=9)
        ax.set_ylim(0, top + 1)
        ax.set_title(label, fontsize=10, loc="left")
        ax.tick_params(labelsize=8)
    axes[-1, 0].set_xlabel("episode")
    handles = [matplotlib.patches.Patch(color=c, label=l) for c, l in
               ((ROD_COLOURS["red"], "red toppled"), (ROD_COLOURS["blue"], "blue toppled"),
                (NONE_COLOUR, "none (time limit)"))]
    fig.legend(handles=handles, frameon=False, fontsize=9, ncols=3, loc="outside upper right")
    return fig
