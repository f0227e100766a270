"""Figures of the chapter "Which curiosity?": the interest signals compared on the
buttons and the rods, with and without noise, and the scenes with the noisy button and
the wobbly rod."""

import collections.abc
import textwrap

import numpy as np

from icm import _validate
from icm.envs import buttons, icub, rods
from icm.experiments import curiosity as _curiosity
from icm.experiments.curiosity import RewardComparison, SignalComparison
from icm.chapters import curiosity as chapters_curiosity
from icm.chapters.words import percent
from icm.experiments.rod_toppling import WELL_PREDICTED_ERROR
from icm.figures._common import (LINESTYLES, MARKERS, TASK_COLOURS, check_result, new_figure,
                                 legend_below, plot_mean_band, series_style)
from icm.figures.icub import check_camera, check_image_size, render
from icm.learners import interest

class _BySignal(collections.abc.Mapping):
    """{signal name: what `read` gives of its class}, for every signal registered in
    `icm.learners.interest.SIGNAL_CLASSES`, now (a signal registered later is in it)."""

    def __init__(self, read):
        self._read = read

    def __getitem__(self, name):
        return self._read(interest.SIGNAL_CLASSES[name])

    def __iter__(self):
        return iter(interest.SIGNAL_CLASSES)

    def __len__(self):
        return len(interest.SIGNAL_CLASSES)


SIGNAL_COLOURS = _BySignal(lambda signal: signal.COLOUR)
"""One colour per interest signal (or intrinsic reward): each signal's `COLOUR`."""
SIGNAL_STYLES = _BySignal(lambda signal: {"linestyle": signal.LINESTYLE,
                                          "marker": signal.MARKER})
"""And a line style and marker each (its `LINESTYLE` and `MARKER`), so that no two
differ by colour alone."""


def _signal_style(signal):
    return SIGNAL_STYLES.get(signal, {"linestyle": LINESTYLES[0], "marker": MARKERS[-1]})


WOBBLY_COLOUR = "#e6a817"
"""The wobbly rod's colour (as in assets/rods_wobbly.xml)."""
BLOCK = 10
"""Episodes per point in the rod curves: shares over blocks of this many episodes."""
MASTERED_SHARE = 0.95
"""A marker of `signal_mastery_figure` is hollow when fewer than this share of the
seeds master the task."""


def _label(name):
    return name.replace("_", " ")


def signal_mastery_figure(comparison, noisy=None):
    """When the predictor masters red and green, per signal and place of interest:
    the mean mastery trial over the seeds that master the task, with its 95% band, one
    panel per world (without the noisy button on the left). A hollow marker: fewer
    than `MASTERED_SHARE` of the seeds master the task (the share is written beside
    it).

    Args:
      comparison: a `SignalComparison`.
      noisy: the worlds to draw, a sequence of False (five buttons) and True (with the
        noisy button), among those the comparison ran; None for all of them.
    """
    check_result("comparison", comparison, SignalComparison,
                 "icm.experiments.run_signal_comparison")
    worlds = comparison.settings["noisy"]
    if noisy is not None:
        worlds = _curiosity.check_choices("noisy", noisy, tuple(worlds))
    fig, axes = new_figure(width=5.2 * len(worlds), height=4.2, ncols=len(worlds),
                           sharex=True, sharey=True, squeeze=False)
    right_end = 0.0
    rows = [(s, d) for s in comparison.settings["signals"]
            for d in comparison.settings["designs"]]
    for ax, noisy in zip(axes[0], worlds):
        for y, (signal, design) in enumerate(rows):
            numbers = comparison.numbers(signal, design, noisy)
            for offset, task in ((-0.15, "red"), (0.15, "green")):
                mean, low, high = numbers[f"{task}_mastery"]
                share = numbers[f"{task}_mastered"][0]
                colour = TASK_COLOURS[task]
                right_end = max(right_end, high)
                ax.errorbar(mean, y + offset, xerr=[[mean - low], [high - mean]],
                            fmt=series_style(task)["marker"],
                            color=colour, mfc=colour if share >= MASTERED_SHARE else "white",
                            markersize=6, capsize=2)
                if share < MASTERED_SHARE:
                    ax.annotate(f"{percent(share)} of seeds", (high, y + offset),
                                xytext=(4, -3), textcoords="offset points", fontsize=7,
                                color=colour)
        ax.set_yticks(range(len(rows)))
        ax.set_yticklabels([f"{_label(s)}, per {d}" for s, d in rows], fontsize=8)
        ax.set_xlabel("mastery trial")
        ax.grid(axis="x", alpha=0.3)
        # On two lines: on one, the two titles ran into each other ("100 seedswith").
        ax.set_title(("with the noisy button" if noisy else "five buttons") +
                     f",\n{comparison.settings['n_seeds']} seeds", fontsize=10)
    axes[0][0].set_xlim(0, 1.3 * right_end)  # the axes share x: room for every band
    axes[0][0].invert_yaxis()  # the axes share y: once for all
    for task in ("red", "green"):
        axes[0][0].plot([], [], series_style(task)["marker"], color=TASK_COLOURS[task],
                        label=f"{task} task")
    axes[0][0].legend(frameon=False, fontsize=8, loc="lower right")
    return fig


DESIGN_STYLES = {"task": {"colour": "#1b6ca8", "linestyle": "-", "marker": "o"},
                 "region": {"colour": "#d95f02", "linestyle": "--", "marker": "s"}}
"""How `noisy_share_figure` draws each place of interest, the same in every panel."""


def _noisy_share(result):
    """[seed, trial]: the share of each trial's presses on the noisy button."""
    return result.button_share[:, :, buttons.NOISY_BUTTON]


def _chance_line(ax):
    ax.axhline(chapters_curiosity.CHANCE_SHARE, color="black", linestyle=":", linewidth=1.2,
               label="chance, 1 in 6", zorder=3)


def noisy_share_figure(comparison):
    """The share of each trial's presses on the noisy button, one panel per signal,
    each with interest per task and per region (mean over seeds, 95% band); the dotted
    line is chance, 1/6. Small multiples, so that per task (where the four signals
    overlap near chance) and per region can be told apart in each.

    Args:
      comparison: a `SignalComparison` with runs with the noisy button.
    """
    check_result("comparison", comparison, SignalComparison,
                 "icm.experiments.run_signal_comparison")
    if True not in comparison.settings["noisy"]:
        raise ValueError("comparison must hold runs with the noisy button (noisy=(..., True))")
    signals, designs = comparison.settings["signals"], comparison.settings["designs"]
    ncols = min(2, len(signals))
    nrows = -(-len(signals) // ncols)
    fig, axes = new_figure(width=4.2 * ncols, height=2.9 * nrows, ncols=ncols, nrows=nrows,
                           sharex=True, sharey=True, squeeze=False)
    for k, ax in enumerate(axes.flat):
        if k >= len(signals):
            ax.axis("off")
            continue
        signal = signals[k]
        for design in designs:
            style = DESIGN_STYLES[design]
            plot_mean_band(ax, _noisy_share(comparison.results[(signal, design, True)]),
                           style["colour"], f"interest per {design}",
                           linestyle=style["linestyle"], marker=style["marker"])
        _chance_line(ax)
        ax.set(xlim=(1, comparison.settings["n_trials"]), ylim=(0, 1))
        ax.set_title(_label(signal), fontsize=10)
        if k % ncols == 0:
            ax.set_ylabel("share of presses\non the noisy button")
        if k // ncols == nrows - 1:
            ax.set_xlabel("trial")
    axes[0][0].legend(frameon=False, fontsize=8, loc="upper left")
    return fig


def noisy_share_curves(runs, title=None):
    """The share of each trial's presses on the noisy button for a few runs on the
    console with the noisy button, one curve each (mean over seeds, 95% band); the
    dotted line is chance, 1/6. A run labelled with a signal's name is drawn in that
    signal's colour and style; another (a student's signal) in black.

    Args:
      runs: {label: GoalOrientedResult with the noisy button}.
      title: the axes' title, or None.
    """
    if not isinstance(runs, dict) or not runs:
        raise _validate.ArgumentTypeError(
            f"runs must be a non-empty dict {{label: GoalOrientedResult}}, got "
            f"{_validate.show(runs)}")
    from icm.experiments.goal_oriented_results import GoalOrientedResult

    fig, ax = new_figure(width=6.0, height=3.4)
    for label, result in runs.items():
        _validate.instance(f"runs[{label!r}]", result, GoalOrientedResult,
                           "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
        if result.button_share.shape[2] <= buttons.NOISY_BUTTON:
            raise ValueError(f"runs[{label!r}] must be a run with the noisy button "
                             f"(noisy_button=True)")
        colour = SIGNAL_COLOURS[label] if label in SIGNAL_COLOURS else "black"
        style = _signal_style(label) if label in SIGNAL_COLOURS else \
            {"linestyle": "-", "marker": None}
        plot_mean_band(ax, _noisy_share(result), colour, _label(str(label)), **style)
    _chance_line(ax)
    ax.set(xlabel="trial", ylabel="share of presses\non the noisy button", ylim=(0, 1),
           xlim=(1, max(r.n_trials for r in runs.values())))
    if title is not None:
        ax.set_title(_validate.text("title", title), fontsize=10)
    # Under the axes: inside, it covered a curve that climbs to the top left.
    legend_below(ax, ncols=2, fontsize=8)
    return fig


def _block_shares(result, index):
    """[seed, block]: the share of each block of `BLOCK` episodes ending with rod
    `index` toppled (-1: none)."""
    n_blocks = result.n_episodes // BLOCK
    hits = (result.toppled[:, :n_blocks * BLOCK] == index).astype(float)
    return hits.reshape(result.n_seeds, n_blocks, BLOCK).mean(axis=2)


def wobbly_rod_figure(comparison):
    """The rods with the wobbly rod, per intrinsic reward: the share of episodes that
    end with the wobbly rod toppled (top), and the largest error the predictor would
    still make on a move that topples the red rod (bottom; a grey line at
    `WELL_PREDICTED_ERROR`, below which red is predicted well), against episode (mean
    over seeds, 95% band; shares over blocks of `BLOCK` episodes).

    Args:
      comparison: a `RewardComparison` with runs with the wobbly rod.
    """
    check_result("comparison", comparison, RewardComparison,
                 "icm.experiments.run_reward_comparison")
    if True not in comparison.settings["wobbly"]:
        raise ValueError("comparison must hold runs with the wobbly rod (wobbly=(..., True))")
    fig, (top, bottom) = new_figure(width=6.7, height=7.6, nrows=2)
    for reward in comparison.settings["rewards"]:
        result = comparison.results[(reward, True)]
        colour = SIGNAL_COLOURS[reward]
        shares = _block_shares(result, result.rod_names.index(rods.WOBBLY))
        x = BLOCK * np.arange(shares.shape[1]) + (BLOCK + 1) / 2
        plot_mean_band(top, shares, colour, _label(reward), x=x, **_signal_style(reward))
        plot_mean_band(bottom, result.rod_error[:, :, 0], colour, _label(reward),
                       **_signal_style(reward))
    n = comparison.settings["n_seeds"]
    top.set(xlabel="episode", ylabel="share of episodes\nending at the wobbly rod",
             ylim=(0, 1), xlim=(1, comparison.settings["n_episodes"]))
    top.set_title(f"Where the episodes end (blocks of {BLOCK} episodes), {n} seeds",
                  fontsize=10)
    legend_below(top, ncols=2)
    # A thin solid grey line, labelled on the axes: a dashed one read as prediction
    # error's line style.
    bottom.axhline(WELL_PREDICTED_ERROR, color="0.45", linestyle="-", linewidth=0.8,
                   zorder=1)
    bottom.annotate(f"{WELL_PREDICTED_ERROR:g}: below it, red is predicted well",
                    (0.36, WELL_PREDICTED_ERROR), xycoords=("axes fraction", "data"),
                    xytext=(0, 3), textcoords="offset points", ha="left",
                    va="bottom", fontsize=8, color="0.3")
    bottom.set(xlabel="episode", ylabel="largest error left on a move\nthat topples red",
               ylim=(0, 1.02), xlim=(1, comparison.settings["n_episodes"]))
    bottom.set_title(f"What is learned about the red rod, {n} seeds", fontsize=10)
    return fig


def coin_flip_figure(curves):
    """What each signal pays, try after try, for a pair whose outcome is a fair coin
    (solid) and for one whose outcome never changes (dashed): the curves of
    `icm.experiments.coin_rewards.outcome_rewards` (mean over seeds, 95% band).

    Args:
      curves: {(signal, "coin" | "sure"): rewards [seed, try]}.
    """
    if not isinstance(curves, dict) or not curves:
        raise _validate.ArgumentTypeError(
            f"curves must be a non-empty dict {{(signal, 'coin' | 'sure'): array}}, got "
            f"{_validate.show(curves)}")
    for key in curves:
        if not (isinstance(key, tuple) and len(key) == 2 and isinstance(key[0], str)
                and key[1] in ("coin", "sure")):
            raise ValueError(f"curves must be keyed by (signal, 'coin' | 'sure'), got the "
                             f"key {key!r}")
    fig, ax = new_figure(width=6.6, height=3.7)
    for (signal, kind), values in curves.items():
        values = _validate.finite_array(f"curves[{(signal, kind)!r}]", values, ndim=2)
        plot_mean_band(ax, values, SIGNAL_COLOURS.get(signal, "black"),
                       f"{_label(signal)}, {'fair coin' if kind == 'coin' else 'sure outcome'}",
                       linestyle="-" if kind == "coin" else "--",
                       marker=_signal_style(signal)["marker"])
    ax.set(xlabel="try of the pair", ylabel="reward paid (mean over seeds)",
           xlim=(1, max(v.shape[1] for v in curves.values())))
    ax.set_ylim(bottom=0)
    ax.set_title("What a noisy and a learnable outcome pay", fontsize=10)
    ax.legend(frameon=False, fontsize=7, ncol=2)
    return fig


def noisy_scenes(camera="front", height=360, width=480):
    """Two images from the simulated scenes beyond the paper: the iCub pressing the
    noisy button (blue, on its stand at the robot's right of the console), and the wobbly
    rod (yellow, beside the grid, at the robot's left) falling as the hand passes it, backward from cell (0, 2). The
    first seed whose draw topples the wobbly rod is used (a rod that stands shows
    nothing).

    Only the few postures these motions need are solved (the discrete environments
    solve all of theirs, which takes seconds); the tasks watching the button and the
    rod are those of the environments."""
    height, width = check_image_size(height, width)
    physics = buttons.load_physics(noisy_button=True)
    check_camera(physics, camera)
    task = buttons.ButtonsTask(noisy_button=True, random=0)
    arm = icub.Arm(physics)
    cap = physics.named.data.geom_xpos[f"button{buttons.NOISY_BUTTON}_cap"].copy()
    top = cap[2] + physics.named.model.geom_size[f"button{buttons.NOISY_BUTTON}_cap"][1]
    home = arm.solve(buttons.ButtonMotions.HOME)
    above = arm.solve([cap[0], cap[1], top + buttons.ButtonMotions.ABOVE], start=home)
    down = arm.solve([cap[0], cap[1], top + buttons.ButtonMotions.DOWN], start=above)
    with physics.reset_context():
        arm.place(home)
    task.lights = buttons.lights_for(task.red_button, buttons.green_candidates(task.red_button)[0])
    physics.set_lights(task.lights)
    watch = lambda: task.update(physics) or False
    console = buttons.PhysicsButtonConsole
    arm.move(above, console.REACH_TIME, watch)
    arm.move(down, console.PUSH_TIME, watch)
    arm.hold(0.3, watch)
    press = render(physics, camera, height, width)

    physics = rods.load_physics(wobbly_rod=True)
    arm = icub.Arm(physics)
    physics.forward()
    lift = np.array([0.0, 0.0, rods.HAND_HEIGHT])
    start, end = physics.cell_centre((0, 2)), physics.cell_centre((0, 1))
    pointing = rods.GridMotions.POINTING
    q_start = arm.solve(start + lift, pointing=pointing)
    q_mid = arm.solve((start + end) / 2 + lift, start=q_start, pointing=pointing)
    q_end = arm.solve(end + lift, start=q_mid, pointing=pointing)
    table = rods.PhysicsRodTable
    for seed in range(20):
        task = rods.RodsTask(start_cell=(0, 2), wobbly_rod=True, random=seed)
        with physics.reset_context():
            physics.stand_rods()
            arm.place(q_start)
        task.begin_move()
        frames = []

        def watch():
            task.update(physics)
            if not frames and physics.rod_tilt(rods.WOBBLY) > np.deg2rad(35):
                frames.append(render(physics, camera, height, width))
            return bool(frames)

        arm.move(q_mid, table.SEGMENT_TIME, watch) or arm.move(q_end, table.SEGMENT_TIME, watch) \
            or arm.hold(table.FALL_TIME, watch)
        if frames:
            return press, frames[0]
    raise RuntimeError("the wobbly rod stood in 20 seeds")  # 1 chance in a million


def scenes_figure(camera="front"):
    """The two scenes of `noisy_scenes`, side by side."""
    press, fall = noisy_scenes(camera)
    fig, (left, right) = new_figure(width=10, height=3.9, ncols=2)
    for ax, image, title in [(left, press, "(a) a press of the noisy button (blue), at random"),
                             (right, fall, "(b) the wobbly rod (yellow) falls, at random")]:
        ax.imshow(image)
        ax.set_title(textwrap.fill(title, 30), fontsize=10)
        ax.axis("off")
    return fig.describe("Two renderings of the simulated iCub: (a) its finger presses the "
                        "noisy button, the blue one on its own stand at the robot's right "
                        "of the console; (b) the wobbly yellow rod falls as the hand "
                        "passes it.")
