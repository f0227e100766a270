"""Figures of the chapter "Forming actions": test error of the three goal-babbling
strategies, coverage of the console, where learning progress put its goals, the
learned presses rendered from the simulation, and, for the remedies (growing up,
being shown), when each button was first pressed and where the finger went."""

import matplotlib.patches
import matplotlib.ticker
import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.experiments import babbling_results, babbling_space
from icm.experiments.babbling_results import GoalBabblingResult
from icm.chapters.words import percent
from icm.experiments.results import check_results
from icm.learners import goal_choice
from icm.learners.goal_babbling import N_BOOTSTRAP
from icm.studies.forming_actions import arms
from icm.studies.forming_actions import remedies as remedies_study
from icm.figures._common import (LINESTYLES, MARKERS, check_result, figure_and_axes, legend_below,
                                 new_figure, plot_mean_band)

_MADE_BY = "icm.experiments.run_goal_babbling"
STRATEGY_COLOURS = {"random_motor": "#7f7f7f", "random_goal": "#1f77b4",
                    "learning_progress": "#e66101"}
"""One colour per strategy."""
STRATEGY_LABELS = {name: strategy.label for name, strategy in goal_choice.STRATEGIES.items()}
"""How the figures name the strategies."""
_OUTCOME_COLOURS = {"touched": "#1f77b4", "other": "#b0b0b0"}


def _label(result):
    return STRATEGY_LABELS.get(result.strategy, result.strategy)


def test_error_figure(results):
    """The test error against rollouts, one curve per run: the mean over seeds with
    its 95% band, in centimetres.

    Args:
      results: a dict {label: GoalBabblingResult}, e.g. one per strategy.
    """
    check_results("results", results, GoalBabblingResult)
    fig, ax = new_figure(width=6.8, height=3.8)
    for i, (label, result) in enumerate(results.items()):
        plot_mean_band(ax, 100 * result.test_error,
                       STRATEGY_COLOURS.get(result.strategy, "black"),
                       f"{label} ({result.n_seeds} seeds)", x=result.checkpoints,
                       linestyle=LINESTYLES[i % len(LINESTYLES)],
                       marker=MARKERS[1 + i % (len(MARKERS) - 1)])
    ax.set_xlabel("rollouts")
    ax.set_ylabel("test error (cm, mean over seeds)")
    ax.set_ylim(bottom=0)
    ax.set_xlim(left=0)
    ax.set_title("Distance from the test goals to what the inverse model reaches, "
                 "95% band", fontsize=10)
    ax.legend(frameon=False, fontsize=8)
    return fig


def _draw_console(ax, geometry):
    """The console's top, seen from above: robot's left (+y) on the left, away from
    the robot (+x) up; the caps as circles numbered 0 to 4."""
    centre, half = geometry["console_centre"], geometry["console_half"]
    ax.add_patch(matplotlib.patches.Rectangle(
        (centre[1] - half[1], centre[0] - half[0]), 2 * half[1], 2 * half[0],
        facecolor="#f4f4f4", edgecolor="#555555", linewidth=1, zorder=0))
    for b, cap in enumerate(geometry["caps"]):
        ax.add_patch(matplotlib.patches.Circle((cap[1], cap[0]), geometry["cap_radius"],
                                               facecolor="white", edgecolor="#555555",
                                               linewidth=0.8, zorder=0))
        ax.text(cap[1], cap[0] - half[0] - 0.012, str(b), ha="center", va="top",
                fontsize=7, color="#555555")
    ax.set_xlim(babbling_space.GOAL_HIGH[1], babbling_space.GOAL_LOW[1])  # robot's left on the left
    ax.set_ylim(babbling_space.GOAL_LOW[0], babbling_space.GOAL_HIGH[0])
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])


def coverage_figure(results, early=0.2):
    """Where the finger went, seen from above, per run: the outcomes of the first
    `early` share of the rollouts (left) and of all of them (right), over every seed.
    Blue: the finger ended touching the console or a cap; grey: in the air or on the
    table. Crosses: the press goals.

    Args:
      results: a dict {label: GoalBabblingResult}.
      early: the share of rollouts in the left column, in (0, 1).
    """
    check_results("results", results, GoalBabblingResult)
    early = _validate.real("early", early, 0.0, 1.0, low_open=True, high_open=True)
    geometry = babbling_space.console_geometry()
    fig, axes = new_figure(width=7.6, height=2.35 * len(results) + 0.4, ncols=2,
                           nrows=len(results), squeeze=False)
    for row, (label, result) in zip(axes, results.items()):
        stops = (max(1, int(round(early * result.n_rollouts))), result.n_rollouts)
        for ax, stop in zip(row, stops):
            _draw_console(ax, geometry)
            outcomes = result.outcomes[:, :stop].reshape(-1, 3)
            touched = result.touched[:, :stop].reshape(-1)
            for kind, mask in (("other", ~touched), ("touched", touched)):
                ax.scatter(outcomes[mask, 1], outcomes[mask, 0], s=3, linewidths=0,
                           color=_OUTCOME_COLOURS[kind], alpha=0.6,
                           label={"touched": "ended on the console",
                                  "other": "ended elsewhere"}[kind])
            goals = geometry["press_goals"]
            ax.scatter(goals[:, 1], goals[:, 0], marker="x", s=18, color="black",
                       linewidths=1, label="press goals")
            pressed = (result.pressed[:, :stop] >= 0).mean()
            ax.set_title(f"{label}:\nfirst {stop} rollouts, {result.n_seeds} seeds\n"
                         f"{percent(touched.mean())} on the console, {percent(pressed)} pressed",
                         fontsize=8)
    # Under the maps, not on them: a legend there would cover the console's buttons.
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=3, frameon=False,
               markerscale=3)
    return fig


def goal_choice_figure(result, n_stretches=8):
    """Where learning progress put its interest and its goals over the run: the
    interest of each column of regions after each rollout (left, mean over seeds),
    and the share of goals in each column per stretch of the run (right), both on a
    logarithmic scale of rollouts. Columns are listed from the robot's left (button
    0) down to its right, each the console and the air above it.

    Args:
      result: a `GoalBabblingResult` of the "learning_progress" strategy.
      n_stretches: stretches of the run on the right (>= 1), of equal length on the
        logarithmic scale, from the end of the random start.
    """
    check_result("result", result, GoalBabblingResult, _MADE_BY)
    if not goal_choice.STRATEGIES[result.strategy].by_interest:
        raise ValueError(f"result must come from a strategy that follows the regions' "
                         f"interest ({', '.join(n for n, s in goal_choice.STRATEGIES.items() if s.by_interest)}), "
                         f"got {result.strategy!r}")
    n_stretches = _validate.integer_at_least("n_stretches", n_stretches, 1)
    start = min(N_BOOTSTRAP, result.n_rollouts - 1)
    if result.n_rollouts - start < n_stretches:
        raise ValueError(f"n_stretches must be at most the {result.n_rollouts - start} "
                         f"rollouts with goals, got {n_stretches}")
    order = list(reversed(range(len(babbling_space.COLUMN_NAMES))))  # the robot's left on top
    names = [babbling_space.COLUMN_NAMES[c] for c in order]
    # One above the other at the page's width: side by side, the labels would be shrunk
    # to unreadable text in the book.
    fig, (left, right) = new_figure(width=7.4, height=6.4, nrows=2)
    interest = result.column_interest()[start:, order]  # [rollout, column]
    x = np.arange(start, result.n_rollouts + 1) + 0.5
    mesh = left.pcolormesh(x, np.arange(len(order) + 1) - 0.5, interest.T, cmap="Purples",
                           vmin=0, shading="flat")
    fig.colorbar(mesh, ax=left, shrink=0.85, label="interest (m per goal)")
    left.set_title(f"Interest of each column of regions, mean of {result.n_seeds} seeds",
                   fontsize=10)
    edges = np.unique(np.geomspace(start, result.n_rollouts, n_stretches + 1).round()
                      .astype(np.int64))
    edges[0], edges[-1] = start, result.n_rollouts
    shares = result.goal_shares(edges)[:, order]
    mesh = right.pcolormesh(edges, np.arange(len(order) + 1) - 0.5, shares.T,
                            cmap="Oranges", vmin=0, shading="flat")
    fig.colorbar(mesh, ax=right, shrink=0.85, label="share of goals")
    right.set_title(f"Share of goals in each column, {result.n_seeds} seeds", fontsize=10)
    ticks = [t for t in (20, 50, 100, 200, 500, 1000, 2000, 5000, 10000)
             if start <= t <= result.n_rollouts]
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_xlim(max(start, 1), result.n_rollouts)
        ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(ticks))
        ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_yticks(range(len(names)), names, fontsize=9)
        ax.set_ylim(len(names) - 0.5, -0.5)
        ax.set_xlabel("rollouts (log scale)")
    return fig


def record_learned_press(result, seed=0, button=0, camera="close_up", height=240,
                         width=320):
    """Runs one learned press on the physics console (the button lit red) and renders
    the scene at the end of the hold, when the finger is at its outcome.

    Args:
      result: a `GoalBabblingResult`.
      seed: which of its seeds' movements.
      button: the button to press (0-4).
      camera, height, width: the view (see `icm.figures.icub.render`).

    Returns:
      A dict: "frame" (RGB image), "pressed" (the buttons pushed past the press
      depth, in order), "boxes" (the boxes seen after the press: red, green).
    """
    from icm.envs.buttons.movements import MovementLab
    from icm.figures.icub import check_camera, check_image_size, render

    check_result("result", result, GoalBabblingResult, _MADE_BY)
    seed = _validate.integer("seed", seed, 0, result.n_seeds - 1)
    button = _validate.integer("button", button, 0, buttons.N_BUTTONS - 1)
    height, width = check_image_size(height, width)
    lab = MovementLab()
    console = buttons.PhysicsButtonConsole(
        red_button=button, seed=0,
        press_motions=[lab.phases(m) for m in result.press_movements[seed]])
    check_camera(console.physics, camera)
    console.reset()
    frames, updates = [], []
    outcome_update = sum(lab.n_updates[:2])

    def recorder(physics):
        updates.append(None)
        if len(updates) == outcome_update:
            frames.append(render(physics, camera, height, width))

    boxes = console.press(button, recorder=recorder)
    return {"frame": frames[0], "pressed": list(console.task.press_log), "boxes": boxes}


def learned_presses_figure(result, seed=0, camera="close_up"):
    """Each button pressed by the movement the robot learned for it (one seed), seen
    at the end of the hold, each in a trial where that button is lit red.

    Args:
      result: a `GoalBabblingResult`.
      seed: which of its seeds.
      camera: the camera to render from (default: the close-up, which sees the finger
        on the button).
    """
    check_result("result", result, GoalBabblingResult, _MADE_BY)
    # Three and two a row, at the page's width: five in a row would be too small to see
    # the finger.
    fig, axes = new_figure(width=7.6, height=4.9, ncols=3, nrows=2)
    axes = axes.ravel()
    axes[-1].axis("off")
    for button, ax in enumerate(axes[:buttons.N_BUTTONS]):
        record = record_learned_press(result, seed, button, camera)
        ax.imshow(record["frame"])
        ax.axis("off")
        pressed = ", ".join(map(str, record["pressed"])) or "none"
        opened = "red box open" if record["boxes"][0] else "red box shut"
        ax.set_title(f"button {button}: pressed {pressed}\n{opened}", fontsize=9)
    fig.suptitle(f"The learned presses ({_label(result)}, seed {seed}), at the end of "
                 "the hold", fontsize=10)
    return fig


STUDY_COLOURS = {"learning progress": "#e66101", "where the finger stopped only": "#5e3c99",
                 "random goal babbling": "#1f77b4", "random motor babbling": "#7f7f7f",
                 "depth weight 1": "#fdb863", "depth weight 3": "#b35806",
                 "LWLR inverse model": "#1b9e77", "competence progress": "#a6761d",
                 "splitting regions": "#7570b3", "return home simulated": "#e7298a"}
"""One colour per variant of the study (`icm.studies.forming_actions.strategies`)."""


def presses_formed_figure(study, labels, roots="tuning", ax=None):
    """The share of seeds that have formed all five presses against rollouts: the mean
    over the study's seeds with its 95% band, one curve per variant.

    Args:
      study: the study (`icm.studies.forming_actions.strategies.load_study()`).
      labels: the variants to draw, a non-empty list of the study's labels.
      roots: "tuning" (the study's `TUNING_ROOTS`) or "held_out" (`HELD_OUT_ROOTS`,
        run by `HELD_OUT_VARIANTS` only).
      ax: a matplotlib Axes to draw on, or None for a new figure.
    """
    if not isinstance(study, dict) or "runs" not in study or "budgets" not in study:
        raise _validate.ArgumentTypeError(f"study must be a study dict (from icm.studies."
                                          f"forming_actions.strategies.load_study), got "
                                          f"{_validate.show(study)}")
    if isinstance(labels, str) or not isinstance(labels, (list, tuple)) or not labels:
        raise _validate.ArgumentTypeError(f"labels must be a non-empty list of the study's "
                                          f"variants, got {_validate.show(labels)}")
    for label in labels:
        _validate.one_of("labels[i]", label, tuple(study["runs"]))
    roots = _validate.one_of("roots", roots, ("tuning", "held_out"))
    root_seeds = arms.TUNING_ROOTS if roots == "tuning" else arms.HELD_OUT_ROOTS
    for label in labels:
        missing = [r for r in root_seeds if str(r) not in study["runs"][label]]
        if missing:
            raise ValueError(f"labels: the study did not run {label!r} on the {roots} "
                             f"root seeds {missing}")
    # Taller for more variants: the legend under the axes grows.
    fig, ax = figure_and_axes(ax, width=6.8, height=3.4 + 0.35 * ((len(labels) + 1) // 2))
    budgets = np.array(study["budgets"])
    for i, label in enumerate(labels):
        runs = study["runs"][label]
        pressed = np.concatenate([np.array(runs[str(root)]["pressed"])
                                  for root in root_seeds])
        all_five = pressed.all(axis=2).astype(float)  # [seed, budget]
        plot_mean_band(ax, all_five, STUDY_COLOURS.get(label, "black"),
                       f"{label} ({len(all_five)} seeds)", x=budgets,
                       linestyle=LINESTYLES[i % len(LINESTYLES)],
                       marker=MARKERS[1 + i % (len(MARKERS) - 1)])
    ax.set_xlabel("rollouts")
    ax.set_ylabel("share of seeds with all five presses")
    ax.set_ylim(0, 1.02)
    ax.set_xlim(budgets[0], budgets[-1])
    legend_below(ax, ncols=2)  # under the axes: in them it covered the curves
    return fig


REMEDY_COLOURS = {"random motor babbling": "#7f7f7f", "random goal babbling": "#1f77b4",
                  "learning progress": "#e66101", "growing up": "#1b9e77",
                  "shown button 2": "#c2a5cf", "shown buttons 0 and 4": "#9970ab",
                  "shown all five": "#40004b"}
"""One colour per condition of `icm.studies.forming_actions.remedies` (the teacher's in
purples, darker for more buttons shown)."""
REMEDY_STYLES = {"random motor babbling": (":", "x"), "random goal babbling": ("-.", "^"),
                 "learning progress": ("-", "o"), "growing up": ("--", "s"),
                 "shown button 2": ("--", "D"), "shown buttons 0 and 4": ("-.", "v"),
                 "shown all five": (":", "P")}
"""Per condition, the line style and marker of its curves, so that no two conditions
drawn together (the strategies with the growing arm; learning progress with each
amount of teaching) differ by colour alone."""
FIRST_PRESS_POINTS = 41
"""The first-press curves are drawn at this many rollouts, evenly spaced on the
logarithmic scale from 10 to the budget."""


def _check_remedy_labels(study, labels):
    remedies_study.check_study(study)
    if isinstance(labels, str) or not isinstance(labels, (list, tuple)) or not labels:
        raise _validate.ArgumentTypeError(f"labels must be a non-empty list of the study's "
                                          f"conditions, got {_validate.show(labels)}")
    for label in labels:
        _validate.one_of("labels[i]", label, tuple(study["runs"]))


def _median_word(median):
    return "never (median)" if np.isnan(median) else f"{median:.0f}"


def first_press_figure(study, labels):
    """When the robot first pressed each button itself: one panel per button, the share
    of seeds whose own rollouts (demonstrations left out) had pressed that button,
    and no other, by each rollout (logarithmic scale); the mean over the study's seeds
    with its 95% band, one curve per condition, each with its colour, line style and
    marker (`REMEDY_STYLES`). A button a condition's teacher showed has open markers
    in that condition.

    Args:
      study: the study (`icm.studies.forming_actions.remedies.load_study()`).
      labels: the conditions to draw, a non-empty list of the study's labels.
    """
    import matplotlib.lines

    _check_remedy_labels(study, labels)
    n_rollouts = study["n_rollouts"]
    x = np.unique(np.round(np.geomspace(10, n_rollouts, FIRST_PRESS_POINTS)))
    fig, axes = new_figure(width=7.6, height=5.6, ncols=3, nrows=2, sharey=True)
    axes = axes.ravel()
    any_shown = False
    firsts = {label: remedies_study.pooled(study, label)["first_press"] for label in labels}
    for button, ax in enumerate(axes[:buttons.N_BUTTONS]):
        for label in labels:
            first = firsts[label][:, button]
            done = ((first[:, None] > 0) & (first[:, None] <= x[None, :])).astype(float)
            shown = button in remedies_study.shown_buttons(label)
            any_shown |= shown
            linestyle, marker = REMEDY_STYLES.get(label, ("-", None))
            plot_mean_band(ax, done, REMEDY_COLOURS.get(label, "black"), label, x=x,
                           linestyle=linestyle, marker=marker)
            if shown:
                ax.get_lines()[-1].set_markerfacecolor("white")
        ax.set_title(f"button {button}")
        ax.set_xscale("log")
        ax.set_xlim(x[0], n_rollouts)
        ax.set_ylim(0, 1.02)
        ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator([10, 100, 1000]))
        ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.yaxis.set_major_locator(matplotlib.ticker.FixedLocator([0, 0.5, 1]))
    for ax in axes[3:5]:
        ax.set_xlabel("rollouts")
    fig.supylabel("share of seeds that had pressed it")
    n_seeds = {len(first) for first in firsts.values()}
    handles = []
    for label in labels:
        linestyle, marker = REMEDY_STYLES.get(label, ("-", None))
        handles.append(matplotlib.lines.Line2D([], [], color=REMEDY_COLOURS.get(label, "black"),
                                               linewidth=2, linestyle=linestyle,
                                               marker=marker, label=label))
    if any_shown:
        handles.append(matplotlib.lines.Line2D([], [], color="#555555", linewidth=0,
                                               marker="o", markerfacecolor="white",
                                               label="open: a button\nthe teacher showed"))
    axes[-1].axis("off")
    axes[-1].legend(handles=handles, frameon=False, loc="center",
                    title=f"{' or '.join(map(str, sorted(n_seeds)))} seeds each")
    medians = "; ".join(
        f"{label}: " + ", ".join(_median_word(m) for m in
                                 babbling_results.median_first_press(firsts[label], n_rollouts))
        for label in labels)
    return fig.describe(
        "When the robot first pressed each button itself, one panel per button: the "
        "share of seeds that had, against rollouts on a logarithmic scale. The median "
        f"rollout of the first own press of buttons 0 to 4, per condition: {medians}.")


def coverage_maps_figure(study, labels):
    """Where the robot's own rollouts (demonstrations left out) ended with the finger on
    the console or a cap, seen from above (robot at the bottom, its left on the
    left): one row per condition, the first `arms.EARLY` rollouts on the
    left and all of them on the right; the count per square centimetre over all the
    study's seeds, on a logarithmic colour scale shared by every map. Outlines: the
    console and its caps, numbered under the maps; crosses: the press goals.

    Args:
      study: the study (`icm.studies.forming_actions.remedies.load_study()`).
      labels: the conditions to draw, a non-empty list of the study's labels.
    """
    import matplotlib.colors

    _check_remedy_labels(study, labels)
    x_edges, y_edges = arms.coverage_edges()
    pooled = {label: remedies_study.pooled(study, label) for label in labels}
    counts = [pooled[label]["coverage"] for label in labels]
    top = max(1, max(int(c[stretch].max()) for c in counts for stretch in c))
    norm = matplotlib.colors.LogNorm(vmin=1, vmax=top)
    fig, axes = new_figure(width=7.6, height=1.9 * len(labels) + 1.0, ncols=2,
                           nrows=len(labels), squeeze=False)
    geometry = babbling_space.console_geometry()
    centre, half = geometry["console_centre"], geometry["console_half"]
    caps = geometry["caps"]
    mesh = None
    n_rollouts = study["n_rollouts"]
    for row, label, count in zip(axes, labels, counts):
        for ax, stretch in zip(row, ("early", "all")):
            mesh = ax.pcolormesh(y_edges, x_edges, np.ma.masked_less(count[stretch], 1),
                                 norm=norm, cmap="viridis", zorder=1)
            ax.add_patch(matplotlib.patches.Rectangle(
                (centre[1] - half[1], centre[0] - half[0]), 2 * half[1], 2 * half[0],
                facecolor="none", edgecolor="#333333", linewidth=1, zorder=2))
            for cap in caps:
                ax.add_patch(matplotlib.patches.Circle(
                    (cap[1], cap[0]), geometry["cap_radius"], facecolor="none",
                    edgecolor="white", linewidth=0.8, zorder=2))
            goals = geometry["press_goals"]
            ax.scatter(goals[:, 1], goals[:, 0], marker="x", s=16, color="red",
                       linewidths=1, zorder=3)
            ax.set_xlim(centre[1] + 1.25 * half[1], centre[1] - 1.25 * half[1])
            ax.set_ylim(centre[0] - 2.2 * half[0], centre[0] + 2.2 * half[0])
            ax.set_aspect("equal")
            ax.set_xticks(caps[:, 1], [str(b) for b in range(len(caps))])
            ax.tick_params(axis="x", length=0)
            ax.set_yticks([])
            when = f"first {arms.EARLY}" if stretch == "early" else \
                f"all {n_rollouts}"
            ax.set_title(f"{label}: {when}")
    bar = fig.colorbar(mesh, ax=axes, location="bottom", shrink=0.7, aspect=30,
                       label="rollouts ending in the square centimetre (log scale)")
    bar.ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 3.0)))
    bar.ax.xaxis.set_major_formatter(matplotlib.ticker.StrMethodFormatter("{x:g}"))
    bar.ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    parts = []
    for label in labels:
        entry = pooled[label]
        n_seeds = len(entry["first_press"])
        shown = len(remedies_study.shown_buttons(label))
        parts.append(
            f"{label}: {int(entry['coverage']['early'].sum())} of the first "
            f"{n_seeds * (arms.EARLY - shown)} own rollouts of its {n_seeds} seeds "
            f"ended on the console, {int(entry['coverage']['all'].sum())} of all "
            f"{n_seeds * (n_rollouts - shown)}")
    return fig.describe(
        "Coverage maps of the console seen from above, the robot at the bottom and "
        "buttons 0 to 4 from its left to its right: where the robot's own rollouts "
        "ended with the finger on the console or a cap, early (left) and over the "
        f"whole run (right). {'; '.join(parts)}.")
