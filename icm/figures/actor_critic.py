"""Figures of the actor-critic chapter: Figures 3, 4 and 6, and what the learner presses."""

import ast
import inspect
import textwrap

import matplotlib.patches
import numpy as np

from icm import _validate
from icm.experiments import actor_critic_results as _actor_critic
from icm.experiments.actor_critic_results import ActorCriticResult
from icm.experiments.results import check_results
from icm.figures._common import (TASK_COLOURS, check_result, check_title, figure_and_axes,
                                 new_figure, plot_mean_band, series_style)
from icm.learners.actor_critic import ActorCritic

_AGENT_COLOUR = "#777777"
_BOX_COLOURS = {"Environment": "#dde7f3", "Actor": "#f3e6d0", "Critic": "#e8dff3",
                "Predictor": "#e2f0d9", "internal\nreward": "#f6dcdc"}
FIGURE4_METHODS = ("learn", "internal_reward", "td_error")
"""The methods of `ActorCritic` that Figure 4 shows: one step of the pseudo-code, and
the two formulas it uses."""


def _box(ax, xy, text, width=0.3, height=0.16):
    x, y = xy
    ax.add_patch(matplotlib.patches.FancyBboxPatch(
        (x - width / 2, y - height / 2), width, height, boxstyle="round,pad=0.02",
        facecolor=_BOX_COLOURS[text], edgecolor="#333333", linewidth=1.2))
    ax.text(x, y, text, ha="center", va="center", fontsize=10.5, weight="bold")


def _arrow(ax, start, end, label, offset=(0.0, 0.0), rad=0.0, colour="#333333"):
    ax.annotate("", xy=end, xytext=start,
                arrowprops=dict(arrowstyle="-|>", color=colour, linewidth=1.4,
                                shrinkA=2, shrinkB=2, connectionstyle=f"arc3,rad={rad}"))
    mid = ((start[0] + end[0]) / 2 + offset[0], (start[1] + end[1]) / 2 + offset[1])
    ax.text(*mid, label, ha="center", va="center", fontsize=8.5, color=colour,
            bbox=dict(boxstyle="round,pad=0.15", facecolor="white", edgecolor="none"))


def _agent_outline(ax, x0, x1, y0=0.03, y1=0.97):
    ax.add_patch(matplotlib.patches.FancyBboxPatch(
        (x0, y0), x1 - x0, y1 - y0, boxstyle="round,pad=0.01", facecolor="none",
        edgecolor=_AGENT_COLOUR, linewidth=1.2, linestyle="--"))
    ax.text(x1 - 0.02, y1 - 0.03, "agent", ha="right", va="top", fontsize=9,
            color=_AGENT_COLOUR, style="italic")


def _diagram_axes(ax, width):
    ax.set_xlim(0, width)
    ax.set_ylim(0, 1)
    ax.set_aspect("equal")
    ax.axis("off")


def _draw_extrinsic(ax):
    _diagram_axes(ax, 1.9)
    env, actor, critic = (0.25, 0.5), (1.35, 0.8), (1.35, 0.22)
    _agent_outline(ax, 0.95, 1.85)
    _box(ax, env, "Environment")
    _box(ax, actor, "Actor")
    _box(ax, critic, "Critic")
    _arrow(ax, (0.4, 0.56), (1.2, 0.8), "state s", (0, 0.05))
    _arrow(ax, (1.2, 0.86), (0.25, 0.58), "action a", (0.0, 0.16), rad=0.25)
    _arrow(ax, (0.4, 0.44), (1.2, 0.22), "reward r (a box opened),\nnext state s'",
           (-0.14, -0.11))
    _arrow(ax, (1.35, 0.3), (1.35, 0.72), "TD error δ", (0.0, 0.0))
    ax.set_title("(a) extrinsic reward: the environment pays for opening a box",
                 fontsize=10)


def _draw_intrinsic(ax):
    _diagram_axes(ax, 1.9)
    env, actor, predictor = (0.25, 0.5), (1.05, 0.82), (1.05, 0.5)
    reward, critic = (1.05, 0.16), (1.62, 0.5)
    _agent_outline(ax, 0.75, 1.85)
    _box(ax, env, "Environment")
    _box(ax, actor, "Actor")
    _box(ax, predictor, "Predictor")
    _box(ax, reward, "internal\nreward", height=0.18)
    _box(ax, critic, "Critic", width=0.28)
    _arrow(ax, (0.4, 0.56), (0.9, 0.82), "state s", (-0.03, 0.05))
    _arrow(ax, (0.9, 0.88), (0.25, 0.58), "action a", (-0.04, 0.15), rad=0.25)
    _arrow(ax, (1.05, 0.74), (1.05, 0.58), "s, a", (0.07, 0.0))
    _arrow(ax, (1.05, 0.42), (1.05, 0.25), "predicted\nboxes", (0.12, 0.0))
    _arrow(ax, (0.4, 0.44), (0.9, 0.16), "observed\nboxes", (-0.04, -0.03))
    _arrow(ax, (1.2, 0.2), (1.55, 0.42), "r = 1 if\nwrong", (0.1, -0.02))
    _arrow(ax, (1.55, 0.58), (1.2, 0.82), "TD error δ", (0.1, 0.03))
    ax.set_title("(b) intrinsic reward: the agent pays itself for a wrong prediction",
                 fontsize=10)


def figure3():
    """Figure 3: the actor-critic architecture with (a) an extrinsic reward, paid by
    the environment, and (b) an intrinsic reward, computed inside the agent from its
    predictor's errors. The critic turns the reward into a TD error that trains both
    itself and the actor.

    Returns:
      The `Figure`, two panels one above the other.
    """
    fig, (top, bottom) = new_figure(width=7.5, height=7.6, nrows=2)
    _draw_extrinsic(top)
    _draw_intrinsic(bottom)
    return fig


def _method_source(name):
    """The source of `ActorCritic.<name>`, dedented, without its docstring."""
    source = textwrap.dedent(inspect.getsource(getattr(ActorCritic, name)))
    lines = source.splitlines()
    function = ast.parse(source).body[0]
    first = function.body[0]
    if (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
            and isinstance(first.value.value, str)):
        del lines[first.lineno - 1:first.end_lineno]
    return "\n".join(lines)


class CodeListing:
    """Source code shown as text a reader can select and copy: Jupyter and the book
    show it as a highlighted Python code block (Markdown), with a caption.

    Attributes:
      code: the source.
      caption: what it is.
      name: a label to refer to it from the text (``{numref}`name```), or None.
    """

    def __init__(self, code, caption, name=None):
        self.code = _validate.text("code", code)
        self.caption = _validate.text("caption", caption)
        self.name = None if name is None else _validate.text("name", name)

    def _repr_markdown_(self):
        fence = "````"  # longer than any run of backticks in Python source
        options = [f":caption: {' '.join(self.caption.split())}"]
        if self.name is not None:
            options.append(f":name: {self.name}")
        return "\n".join([f"{fence}{{code-block}} python", *options, "", self.code, fence])

    def __repr__(self):
        return self.code


def figure4(methods=FIGURE4_METHODS, caption=None, name=None):
    """Figure 4: the update of the intrinsic actor-critic, as the library runs it, as
    text.

    The code is read from `icm.learners.actor_critic.ActorCritic` with
    `inspect.getsource` when it is shown (docstrings left out), so it can never drift
    from the code.

    Args:
      methods: names of `ActorCritic` methods to show, in order.
      caption: the listing's caption (default: says where the code comes from).
      name: a label for cross-references, or None.

    Returns:
      A `CodeListing`.
    """
    if isinstance(methods, str) or not isinstance(methods, (tuple, list)) or not methods:
        raise _validate.ArgumentTypeError(f"methods must be a non-empty tuple of ActorCritic "
                                          f"method names, got {_validate.show(methods)}")
    for method in methods:
        if not isinstance(method, str) or not callable(getattr(ActorCritic, method, None)):
            raise ValueError(f"methods must name methods of ActorCritic (e.g. "
                             f"{', '.join(FIGURE4_METHODS)}), got {method!r}")
    code = "\n\n".join(_method_source(method) for method in methods)
    if caption is None:
        caption = ("ActorCritic in icm/learners/actor_critic.py, read from the source "
                   "(docstrings left out)")
    return CodeListing(code, caption, name)


def figure6(result, ax=None, title=None):
    """Figure 6: section 4.1's prediction error against trial, red and green, each
    seed as a thin line, with the mean over seeds and its 95% band.

    Args:
      result: an `ActorCriticResult`.
      ax: draw into this axes instead of a new figure.
      title: the axes title; default says the reward, the variant and the seeds.

    Returns:
      The `Figure`.
    """
    check_result("result", result, ActorCriticResult, "icm.experiments.run_actor_critic")
    check_title(title)
    fig, ax = figure_and_axes(ax)
    for i, task in enumerate(_actor_critic.TASKS):
        plot_mean_band(ax, result.prediction_error[:, :, i], TASK_COLOURS[task],
                       f"only {task} lit, press it (mean)", per_seed=True,
                       **series_style(task))
    ax.set_xlabel("trial")
    ax.set_ylabel("prediction error (Euclidean)")
    ax.set_xlim(1, result.n_trials)
    ax.set_ylim(-0.02, np.sqrt(2) + 0.05)
    if title is None:
        settings = result.settings
        title = (f"Prediction error, {settings['reward']} reward, variant "
                 f"\"{settings['variant']}\", {result.n_seeds} seeds, 95% band")
    ax.set_title(title, fontsize=10)
    ax.legend(frameon=False)
    return fig


def figure6_grid(results, ncols=2):
    """Figure 6 for several results, `ncols` panels a row, on shared axes.

    Args:
      results: a dict {panel title: ActorCriticResult}.
      ncols: panels per row.
    """
    check_results("results", results, ActorCriticResult)
    ncols = _validate.integer("ncols", ncols, 1, 10)
    nrows = -(-len(results) // ncols)
    fig, axes = new_figure(width=4.8 * ncols, height=3.5 * nrows, ncols=ncols, nrows=nrows,
                           sharex=True, sharey=True, squeeze=False)
    for i, (ax, (title, result)) in enumerate(zip(axes.ravel(), results.items())):
        figure6(result, ax=ax, title=title)
        col = i % ncols
        if i > 0:
            ax.get_legend().remove()  # one legend is enough
        if i + ncols < len(results):  # a panel below carries the trial axis
            ax.set_xlabel("")
        else:
            ax.xaxis.set_tick_params(labelbottom=True)
        if col > 0:
            ax.set_ylabel("")
    for ax in axes.ravel()[len(results):]:
        ax.axis("off")
    return fig


def practice_figure(results):
    """What the learner does: the share of presses that opened each box, per trial
    (mean over seeds, 95% band), one panel per result, with the 1-in-5 of chance.

    Args:
      results: a dict {panel title: ActorCriticResult}.
    """
    check_results("results", results, ActorCriticResult)
    # One panel under the other, at the width of the page: side by side, three panels
    # would be shrunk to unreadable text in the book.
    fig, axes = new_figure(width=7.2, height=0.4 + 2.3 * len(results), nrows=len(results),
                           sharex=True, squeeze=False)
    for ax, (title, result) in zip(axes[:, 0], results.items()):
        presses = result.settings["presses_per_trial"]
        for i, task in enumerate(_actor_critic.TASKS):
            plot_mean_band(ax, result.practice[:, :, i] / presses, TASK_COLOURS[task],
                           f"opened the {task} box", **series_style(task))
        ax.axhline(0.2, color="#999999", linestyle=":", linewidth=1, label="chance (1 in 5)")
        ax.set(xlim=(1, result.n_trials), ylim=(0, 1), ylabel="share of presses")
        ax.set_title(title, fontsize=11, loc="left")
    axes[-1, 0].set_xlabel("trial (mean over seeds, 95% band)")
    axes[0, 0].legend(frameon=False, loc="upper right", fontsize=9, ncols=3)
    return fig
