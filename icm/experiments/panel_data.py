"""The interactive panels' numbers: one library call per panel setting, and the grid of
settings that the book precomputes for its kernel-free (static HTML) panels.

A panel is one of the paper's figures redrawn for a chosen setting of its sliders:

- ``"figure5"``: the goal-oriented learner's interest in each task (epsilon, window,
  new-task factor); the same runs give the epsilon x window sweep of the mastery gap;
- ``"figure6"``: the actor-critic's prediction error on each task (actor and critic
  learning rates, temperature, variant);
- ``"figure7"``: the curious Q-learner's error left on each rod and where it plays
  (epsilon, alpha, gamma, predictor learning rate).

`panel_curves_for` is the one call behind a panel: the live ipywidgets panel
(`icm.widgets`) makes it for whatever setting the sliders show, and `compute_grid`
makes it for every setting of the panel's grid, so the book's static panels show the
same numbers as the live ones wherever the grid has the setting.

The book's grids take about 50 s of CPU together, which every build of the book would
otherwise spend again, so each is kept in assets/ (assets/panel_figure5.npz, ...),
with what it was computed from (`spec_record`) and the versions that computed it:
`precompute` reads a panel's file when what it records is the panel's spec, and
computes the grid otherwise. `python -m icm.experiments.panel_grids` writes the files
again (after a change to a learner, an experiment or a panel, commit them); a test
reruns some settings of each grid and expects the file's numbers, exactly.
"""

import dataclasses
import functools
import inspect
import itertools
import json
import platform

import numpy as np

from icm import _validate
from icm.store import ASSETS
from icm.experiments import actor_critic as _actor_critic
from icm.experiments import actor_critic_results, goal_oriented_results
from icm.experiments import goal_oriented as _goal_oriented
from icm.experiments import rod_toppling as _rod_toppling
from icm.experiments.progress import progress_bar
from icm.stats import PANEL_RESAMPLES, bootstrap_band, every_nth


@dataclasses.dataclass(frozen=True)
class PanelSpec:
    """What a panel runs and which settings its sliders offer.

    The sliders and choices are settings of the run function's learner
    (`icm._settings.Setting`): their grids, live ranges, labels and defaults come
    from there.

    Attributes:
      title: what the panel shows, for headings.
      run: the experiment (`run_goal_oriented`, ...), made with
        `icm._settings.with_settings`.
      grid_run: its many-settings form (`run_goal_oriented_grid`, ...), or None if it
        has none (then the settings run one by one).
      curves: the experiment's `panel_curves` (result -> curves dict).
      slider_names: the learner's settings offered as sliders (each with a `Slider`).
      choice_names: the learner's settings offered as choices.
      fixed: the run's other arguments (seeds, trials, root seed).
      every: the static panel keeps every `every`-th point of each curve (and the
        last): enough for the eye, a smaller page, and fewer bands to compute (a kept
        point's numbers are those of the live panel).
      grids: values that replace some controls' grids (the book's panels have none; a
        smaller grid for a test or a quick sketch), {name: values}.
    """

    title: str
    run: object
    grid_run: object
    curves: object
    slider_names: tuple
    choice_names: tuple
    fixed: dict
    every: int = 1
    grids: dict = dataclasses.field(default_factory=dict)

    def setting(self, name):
        """The `icm._settings.Setting` of control `name`."""
        return self.run.settings_class.spec(name)

    @property
    def sliders(self):
        """{setting: the static panel's grid of values} of the sliders."""
        return {name: tuple(self.grids.get(name, self.setting(name).slider.grid))
                for name in self.slider_names}

    @property
    def choices(self):
        """{setting: options} of the choices, the default first."""
        out = {}
        for name in self.choice_names:
            spec = self.setting(name)
            options = (spec.default,) + tuple(c for c in spec.choices if c != spec.default)
            out[name] = tuple(self.grids.get(name, options))
        return out

    @property
    def defaults(self):
        """The library's default of every slider and choice."""
        return {name: self.setting(name).default for name in self.controls}

    @property
    def controls(self):
        """Names of the sliders and choices, in order."""
        return tuple(self.slider_names) + tuple(self.choice_names)

    def settings(self):
        """Every setting of the grid, as dicts, in a fixed order."""
        names = self.controls
        values = [self.sliders[n] for n in self.sliders] + [self.choices[n]
                                                             for n in self.choices]
        return [dict(zip(names, combo)) for combo in itertools.product(*values)]


PANEL_SEEDS = 100
"""Runs behind each curve of the button panels (figures 5 and 6)."""
PANEL_TRIALS = 60
"""Trials per run of the actor-critic's panel (figure 6; its chapter runs
`actor_critic.CHAPTER_TRIALS`); figure 5's panel runs its chapter's
`goal_oriented.CHAPTER_TRIALS`."""

PANELS = {
    "figure5": PanelSpec(
        title="Figure 5: interest in each task",
        run=_goal_oriented.run_goal_oriented,
        grid_run=_goal_oriented.run_goal_oriented_grid, curves=goal_oriented_results.panel_curves,
        slider_names=("epsilon", "window", "new_task_factor"), choice_names=(),
        fixed={"n_seeds": PANEL_SEEDS, "n_trials": _goal_oriented.CHAPTER_TRIALS, "seed": 0}),
    "figure6": PanelSpec(
        title="Figure 6: the actor-critic's prediction error",
        run=_actor_critic.run_actor_critic,
        grid_run=_actor_critic.run_actor_critic_grid, curves=actor_critic_results.panel_curves,
        slider_names=("lr_actor", "lr_critic", "temperature"), choice_names=("variant",),
        fixed={"n_seeds": PANEL_SEEDS, "n_trials": PANEL_TRIALS, "seed": 0}),
    "figure7": PanelSpec(
        title="Figure 7: what is left to learn about each rod",
        run=_rod_toppling.run_rod_toppling, grid_run=None,
        curves=_rod_toppling.panel_curves,
        slider_names=("epsilon", "alpha", "gamma", "predictor_lr"), choice_names=(),
        fixed={"n_seeds": 100, "n_episodes": 150, "seed": 0}, every=3),
}
"""The panels, by name. Each slider's grid is its setting's `Slider.grid` (5 evenly
spaced values around the library's default); every run has 100 seeds."""


def spec(name):
    """The `PanelSpec` of panel `name` (one of `PANELS`).

    Raises:
      ValueError: for an unknown name, listing the known ones.
    """
    return PANELS[_validate.one_of("name", name, tuple(PANELS))]


def _check_setting(panel, setting, fixed):
    if not isinstance(setting, dict):
        raise _validate.ArgumentTypeError(f"settings must be a list of dicts of control "
                                          f"values, got the entry {_validate.show(setting)}")
    allowed = panel.controls
    for key in setting:
        if key not in allowed:
            raise ValueError(f"{key!r} is not a control of the {panel.title!r} panel; its "
                             f"controls are {', '.join(allowed)}")
    for key in fixed:
        if key in allowed or key == "progress":
            raise ValueError(f"{key!r} cannot be held fixed in this panel (it is one of "
                             f"its controls, or the progress bar)")
    return {**panel.defaults, **setting}, {**panel.fixed, **fixed}


ROWS_PER_BATCH = 5000
"""Rows (settings x seeds) run together by `panel_runs`: large enough to spread the
per-step overhead, small enough to keep the batch's records in a few tens of MB."""


def panel_runs(name, settings, fixed=None, progress=False):
    """Runs panel `name`'s experiment at each of `settings`, yielding the results in
    order. Settings run together, as rows of one batch (the experiment's grid form,
    which gives each setting the numbers of its separate run), `ROWS_PER_BATCH` rows
    at a time.

    Args:
      name: a panel of `PANELS`.
      settings: a list of dicts of slider and choice values; a control left out takes
        its default.
      fixed: a dict of the run's other arguments, replacing the panel's (e.g.
        {"n_seeds": 20}); None keeps the panel's 100 seeds.
      progress: show a progress bar over the settings.

    Yields:
      The experiment's result for each setting.

    Raises:
      ValueError: for an unknown panel, a setting that is not one of its controls, or
        a value the experiment refuses.
    """
    panel = spec(name)
    if fixed is not None and not isinstance(fixed, dict):
        raise _validate.ArgumentTypeError(f"fixed must be a dict of the run's other "
                                          f"arguments or None, got {_validate.show(fixed)}")
    if not isinstance(settings, (list, tuple)) or not settings:
        raise _validate.ArgumentTypeError(f"settings must be a non-empty list of dicts, got "
                                          f"{_validate.show(settings)}")
    checked = [_check_setting(panel, s, fixed or {}) for s in settings]
    run_fixed = checked[0][1]
    _validate.integer_at_least("fixed['n_seeds']", run_fixed.get("n_seeds", 1), 1)
    _validate.boolean("progress", progress)
    full = [setting for setting, _ in checked]
    per_batch = 1 if panel.grid_run is None else \
        max(1, ROWS_PER_BATCH // run_fixed.get("n_seeds", 1))
    # Checked above, here; run below, as the caller iterates.
    return _run_in_batches(panel, full, run_fixed, per_batch, progress)


def _run_in_batches(panel, full, run_fixed, per_batch, progress):
    """The generator of `panel_runs`: its settings run `per_batch` at a time."""
    bar = progress_bar(None, len(full), panel.title.split(':')[0] + ', grid of settings',
                       progress, unit="setting")
    for start in range(0, len(full), per_batch):
        chunk = full[start:start + per_batch]
        if panel.grid_run is None:
            results = [panel.run(**chunk[0], **run_fixed, progress=False)]
        else:
            results = panel.grid_run(chunk, **run_fixed, progress=False)
        if bar is not None:
            bar.update(len(chunk))
        yield from results
    if bar is not None:
        bar.close()


def panel_run(name, fixed=None, **setting):
    """Runs panel `name`'s experiment at one `setting` (`panel_runs` of one setting).

    Args:
      name: a panel of `PANELS`.
      fixed: a dict of the run's other arguments, replacing the panel's (e.g.
        {"n_seeds": 20}); None keeps the panel's 100 seeds.
      **setting: slider and choice values; a control left out takes its default.

    Returns:
      The experiment's result.
    """
    return next(panel_runs(name, [setting], fixed))


def panel_curves_for(name, fixed=None, **setting):
    """What panel `name` draws at `setting`: the experiment's `panel_curves` of
    `panel_run(name, fixed, **setting)`. The live panels call this; `precompute` calls
    the same `panel_runs` and `panel_curves` for every setting of the grid (keeping
    every `every`-th point), so the two show the same numbers for the same setting (a
    test checks it)."""
    return spec(name).curves(panel_run(name, fixed, **setting))


def sweep_cell(result):
    """The epsilon x window sweep's numbers for one goal-oriented result: the share of
    seeds that master red first, and the mean mastery gap (green - red, over the seeds
    that master both) with its 95% percentile-bootstrap band.

    Returns:
      {"red_first": share, "gap": mean, "gap_low": low, "gap_high": high, "gap_seeds":
      how many seeds mastered both}; the gap numbers are NaN if no seed did.
    """
    _validate.instance("result", result, goal_oriented_results.GoalOrientedResult,
                       "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    red, green = result.mastery_trial[:, 0], result.mastery_trial[:, 1]
    both = (red >= 1) & (green >= 1)
    out = {"red_first": result.red_first_fraction(), "gap_seeds": int(both.sum())}
    if both.any():
        mean, low, high = bootstrap_band((green - red)[both].astype(float),
                                         resamples=PANEL_RESAMPLES)
        out.update(gap=float(mean), gap_low=float(low), gap_high=float(high))
    else:
        out.update(gap=float("nan"), gap_low=float("nan"), gap_high=float("nan"))
    return out


@dataclasses.dataclass(frozen=True)
class PanelGrid:
    """A panel's curves at every setting of its grid.

    Attributes:
      name: the panel (a key of `PANELS`).
      settings: the grid's settings, dicts of slider and choice values.
      curves: for each setting, what `panel_curves_for` returns, thinned to the
        panel's `every`.
      cells: for "figure5", each setting's `sweep_cell` (else None).
    """

    name: str
    settings: tuple
    curves: tuple
    cells: tuple = None

    def __post_init__(self):
        spec(self.name)  # a panel of PANELS, else a ValueError naming them
        for field in ("settings", "curves"):
            if not isinstance(getattr(self, field), (tuple, list)):
                raise _validate.ArgumentTypeError(
                    f"{field} must be a tuple, got {_validate.show(getattr(self, field))}")
        if len(self.curves) != len(self.settings) or (
                self.cells is not None and len(self.cells) != len(self.settings)):
            raise ValueError(f"curves (and cells) must have one entry per setting "
                             f"({len(self.settings)}), got {len(self.curves)}")

    @property
    def spec(self):
        """The panel's `PanelSpec`."""
        return spec(self.name)

    def index(self, **setting):
        """Position of `setting` (every control given) in the grid.

        Raises:
          ValueError: if the grid has no such setting.
        """
        for i, s in enumerate(self.settings):
            if s.keys() == setting.keys() and all(_same(s[k], setting[k]) for k in s):
                return i
        raise ValueError(f"the {self.name} grid has no setting {setting}; its values are "
                         f"{ {**self.spec.sliders, **self.spec.choices} }")


def _same(a, b):
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return _validate.is_real(b) and abs(a - b) < 1e-9


def compute_grid(name, progress=True):
    """Runs panel `name` at every setting of its grid (100 seeds each), as the live panel
    would: `panel_runs` and the panel's `curves` (thinned to its `every`), and for
    "figure5" each setting's `sweep_cell`. This is what the stored grids hold
    (`precompute` reads them); it takes from 5 s (figure5) to 25 s (figure7).

    Args:
      name: a panel of `PANELS`.
      progress: show a progress bar over the settings.

    Returns:
      A `PanelGrid`.

    Raises:
      ValueError: for an unknown panel name.
    """
    panel = spec(name)
    progress = _validate.boolean("progress", progress)
    settings = panel.settings()
    curves, cells = [], []
    for result in panel_runs(name, settings, progress=progress):
        curves.append(panel.curves(result, every=panel.every))
        if name == "figure5":
            cells.append(sweep_cell(result))
    return PanelGrid(name=name, settings=tuple(settings), curves=tuple(curves),
                     cells=tuple(cells) if cells else None)


@functools.lru_cache(maxsize=4)
def _precompute(name, progress):
    stored = load_grid(name)
    return compute_grid(name, progress) if stored is None else stored


def precompute(name, progress=True):
    """The numbers of the book's static panel `name`: its curves (and, for "figure5",
    the sweep's cells) at every setting of its grid, 100 seeds each, as the live panel
    computes them.

    They come from the panel's file in assets/ (`grid_path`), which
    `python -m icm.experiments.panel_grids` wrote with `compute_grid`, when the file
    records the panel's spec as it is now (`spec_record`: the same settings, fixed
    arguments, `every`, and defaults of the run's other arguments); a test reruns
    some of its settings and expects its numbers, exactly. Otherwise (no file, or a
    panel changed since, e.g. a smaller grid for a test) they are computed again with
    `compute_grid`, 5 to 25 s.

    The result is kept for the rest of the session (a chapter that shows Figure 5's
    panel and the sweep reads the grid once).

    Args:
      name: a panel of `PANELS`.
      progress: show a progress bar over the settings, if they are computed.

    Returns:
      A `PanelGrid`.

    Raises:
      ValueError: for an unknown panel name.
    """
    spec(name)
    return _precompute(name, _validate.boolean("progress", progress))


# --- the stored grids -------------------------------------------------------------

GRID_FILE = "panel_{name}.npz"
"""The file in assets/ that holds a panel's grid (`name`: a key of `PANELS`)."""


def grid_path(name, folder=None):
    """The path of panel `name`'s grid file (`GRID_FILE`) in `folder` (default:
    assets/); it may not exist."""
    name = _validate.one_of("name", name, tuple(PANELS))
    return (ASSETS if folder is None else folder) / GRID_FILE.format(name=name)


def _as_json(value):
    """`value` as JSON gives it back (tuples become lists), for comparisons."""
    return json.loads(json.dumps(value))


def spec_record(name):
    """What panel `name`'s grid is computed from, as JSON values: the run and curves
    functions (their dotted names), the grid's settings in order, the fixed arguments,
    `every`, and the defaults of the run's other arguments (learner settings
    included; not its hooks, `observe` and `make_env`, which see or build a run without
    changing its numbers). A stored grid is read only if the record it was written with
    equals this one."""
    panel = spec(name)
    others = {key: parameter.default
              for key, parameter in inspect.signature(panel.run).parameters.items()
              if key not in ("progress", "settings", "observe", "make_env")
              and key not in panel.fixed}
    return _as_json({"run": f"{panel.run.__module__}.{panel.run.__name__}",
                     "curves": f"{panel.curves.__module__}.{panel.curves.__name__}",
                     "settings": panel.settings(), "fixed": panel.fixed,
                     "every": panel.every, "defaults": others})


def versions():
    """The versions that compute the grids: Python, NumPy and Numba, and the machine's
    kind."""
    import numba
    return {"python": platform.python_version(), "numpy": np.__version__,
            "numba": numba.__version__, "machine": platform.machine()}


def _template(curves):
    """A setting's curves without their arrays (the part every setting of a grid
    shares): "x" None and each group's "series" the list of its names."""
    return {**curves, "x": None,
            "groups": [{**group, "series": list(group["series"])} for group in curves["groups"]]}


def save_grid(grid, path):
    """Writes `grid` (a `PanelGrid` of its panel's spec as it is now) to the .npz file
    `path`, every number as computed (the bands float64), with `spec_record` and
    `versions()`.

    Raises:
      ValueError: if the grid's settings are not its panel's, or its settings' curves
        differ in their labels or series.
    """
    _validate.instance("grid", grid, PanelGrid, "a PanelGrid (from compute_grid)")
    record = spec_record(grid.name)
    if _as_json(list(grid.settings)) != record["settings"]:
        raise ValueError(f"grid must hold the settings of the {grid.name} panel as it is "
                         f"now (PANELS[{grid.name!r}].settings()), in order")
    template = _as_json(_template(grid.curves[0]))
    if any(_as_json(_template(c)) != template for c in grid.curves):
        raise ValueError("grid: every setting's curves must have the same labels and series")
    arrays = {"x": np.stack([np.asarray(c["x"]) for c in grid.curves])}
    for g, group in enumerate(template["groups"]):
        for series in group["series"]:
            arrays[f"series/{g}/{series}"] = np.stack(
                [np.stack(c["groups"][g]["series"][series]) for c in grid.curves])
    cell_keys = [] if grid.cells is None else list(grid.cells[0])
    for key in cell_keys:
        arrays[f"cells/{key}"] = np.array([cell[key] for cell in grid.cells])
    about = {"panel": grid.name, "spec": record, "template": template,
             "cells": None if grid.cells is None else cell_keys, "versions": versions()}
    arrays["about"] = np.array(json.dumps(about))
    np.savez_compressed(path, **arrays)


def stored_about(name, path=None):
    """What panel `name`'s grid file (default `grid_path(name)`) records: {"panel",
    "spec" (its `spec_record`), "template" (the curves' labels), "cells" (the sweep
    cells' keys, or None), "versions"}; None if there is no file."""
    path = grid_path(name) if path is None else path
    try:
        with np.load(path, allow_pickle=False) as stored:
            return json.loads(str(stored["about"]))
    except FileNotFoundError:
        return None


def load_grid(name, path=None):
    """Panel `name`'s grid as its file (default `grid_path(name)`) holds it, a
    `PanelGrid` equal to `compute_grid(name)`'s, or None if there is no file or it
    records another spec than the panel's now (`spec_record`)."""
    path = grid_path(name) if path is None else path
    about = stored_about(name, path)
    if about is None or about["panel"] != name or about["spec"] != spec_record(name):
        return None
    template = about["template"]
    with np.load(path, allow_pickle=False) as stored:
        arrays = {key: stored[key] for key in stored.files if key != "about"}
    curves = []
    for i in range(len(about["spec"]["settings"])):
        groups = [{**group, "series": {series: tuple(arrays[f"series/{g}/{series}"][i])
                                       for series in group["series"]}}
                  for g, group in enumerate(template["groups"])]
        curves.append({**template, "x": arrays["x"][i], "groups": groups})
    cells = None
    if about["cells"] is not None:
        columns = [arrays[f"cells/{key}"].tolist() for key in about["cells"]]
        cells = tuple(dict(zip(about["cells"], row)) for row in zip(*columns))
    return PanelGrid(name=name, settings=tuple(about["spec"]["settings"]),
                     curves=tuple(curves), cells=cells)


def thin(curves, every):
    """`curves` with every `every`-th point of each series kept (and the last)."""
    keep = every_nth(len(curves["x"]), every)
    groups = [{**g, "series": {k: tuple(np.asarray(a)[keep] for a in band)
                               for k, band in g["series"].items()}}
              for g in curves["groups"]]
    return {**curves, "x": np.asarray(curves["x"])[keep], "groups": groups}


def sweep_summary(grid):
    """The numbers the book quotes about the epsilon x window sweep of the Figure 5
    grid.

    Returns:
      A dict: "settings", "runs" (settings x seeds); "red_first" (share of all runs
      that master red first) and "red_first_lowest" (the lowest share of any
      setting); "gap_lowest", "gap_highest" (the range of the settings' mean gaps);
      "windows" (the grid's windows) and "default_gaps" (the mean gap at each window,
      at the default epsilon and new-task factor); "longer_window_larger" (in how many
      (epsilon, new-task factor) pairs the longest window gives a larger mean gap than
      the shortest) out of "pairs".
    """
    _validate.instance("grid", grid, PanelGrid,
                       "a PanelGrid (from icm.experiments.panel_data.precompute)")
    if grid.cells is None:
        raise ValueError(f"grid must be the figure5 grid, got the {grid.name} grid")
    spec_ = grid.spec
    n_seeds = spec_.fixed["n_seeds"]
    shares = np.array([c["red_first"] for c in grid.cells])
    gaps = np.array([c["gap"] for c in grid.cells])
    windows = spec_.sliders["window"]

    def gap(**setting):
        return grid.cells[grid.index(**setting)]["gap"]

    defaults = {k: spec_.defaults[k] for k in ("epsilon", "new_task_factor")}
    pairs = [(e, f) for e in spec_.sliders["epsilon"] for f in spec_.sliders["new_task_factor"]]
    larger = sum(gap(epsilon=e, window=windows[-1], new_task_factor=f)
                 > gap(epsilon=e, window=windows[0], new_task_factor=f) for e, f in pairs)
    return {"settings": len(grid.settings), "runs": len(grid.settings) * n_seeds,
            "red_first": float(shares.mean()), "red_first_lowest": float(shares.min()),
            "gap_lowest": float(np.nanmin(gaps)), "gap_highest": float(np.nanmax(gaps)),
            "windows": tuple(windows),
            "default_gaps": tuple(gap(window=w, **defaults) for w in windows),
            "longer_window_larger": int(larger), "pairs": len(pairs)}
