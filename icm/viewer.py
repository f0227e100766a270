"""The live iCub of the HTML book: the scenes' MJCF and the discrete actions' controls,
exported for MuJoCo's WebAssembly build in the reader's browser, and the views a
notebook shows.

Python computes what is hard, the arm's postures (inverse kinematics, `icub.Arm.solve`)
and the learners' runs; the page's one viewer, book/_static/icm-live.js, steps the
package's own MJCF with the exported controls, applies the tasks' rules and draws. A
motion is exported as the `icub.Arm.move` calls that make it: (joint targets, number
of 20 ms updates) pairs, joint targets None for a hold; the viewer interpolates the
actuators' targets along the same minimum-jerk profile, in the same floating-point
operations. The viewer and its scripts (three.js, MuJoCo, about 4 MB) load only when
the reader asks for the live view; until then, and where WebGL or WebAssembly is
missing, in print and in a Jupyter kernel, a view is a still of the scene rendered
from the model.
"""

import base64
import hashlib
import html
import io
import json
import os
import pathlib
import shutil
import xml.etree.ElementTree as ElementTree

import numpy as np

from icm import _book, _validate
from icm._settings import Names
from icm.envs._assets import asset_path

BROWSER_MUJOCO = "3.14.0"
"""The version of MuJoCo's WebAssembly build that the live views run in the reader's
browser (`@mujoco/mujoco`, vendored in book/_static/vendor; a test checks its lock
file); Python runs the `mujoco` package installed with icm."""
LIVE_SCENES = {}
"""The scenes the viewer shows, by name: each scenario's export for the browser and
the view it starts from, registered where the export is written (`register_scene`). The
browser side (book/_static/icm-live.js) steps the scenario's rules too."""
SCENES = Names(lambda: tuple(LIVE_SCENES))
"""The scenes the viewer shows (the names of `LIVE_SCENES`)."""
STATIC_FILES = ("icm-live.js", "icm.css", "vendor/three/three.min.js",
                "vendor/mujoco/mujoco.js", "vendor/mujoco/mujoco-wasm.js")
"""The files of the book's `_static` folder a live view needs (the viewer loads all but
icm.css on request)."""
BOOK_ENV = _book.STATIC_ENV
"""Set to "1" while the book is built (book/_ext/execute_book.py): views are then the
live viewer; otherwise (a Jupyter kernel, where the book's `_static` folder is not
served) they are the still with a note."""
POSTER_CAMERA = "front"
"""The camera of the still shown before the live view starts, and instead of it."""
POSTER_SIZE = (360, 480)
"""The still's height and width in pixels."""
VIEWS = {"buttons": {"camera": "front"},
         "rods": {"camera": "over_shoulder",
                  "orbit": {"distance": 0.85, "azimuth": -2.75, "elevation": 1.1}}}
"""Where the live view starts (the reader turns it): where one of the scene's cameras
is, turned to the body it targets, or elsewhere on the sphere around that body
("orbit": distance in m, azimuth and elevation in radians). The robot from the front at
the console; from behind its right shoulder at the rods, where the arrow keys then move
the hand the way they point."""


def register_scene(name):
    """Registers the decorated function (of no arguments, returning the scene's export:
    see `scene_export`) as the live view of scenario `name`, whose starting view is
    `VIEWS[name]`.

    Raises:
      ValueError: for a name registered already or without a view in `VIEWS`.
    """
    name = _validate.text("name", name)
    if name in LIVE_SCENES:
        raise ValueError(f"name must be a new scene, got {name!r}: registered already")
    _validate.one_of("name", name, tuple(VIEWS))

    def register(export):
        LIVE_SCENES[name] = _validate.function("export", export, allow_none=False)
        return export
    return register


DEFAULT_REPLAY_TRIALS = 10
"""Trials of the goal-oriented learner's run that `live_learner` replays."""
DEFAULT_REPLAY_EPISODES = 30
"""Episodes of the Q-learner's run that `live_rod_learner` replays: for the root seed 0,
they reach the first blue topple (episode 29)."""


def scene_xml(scene):
    """The MJCF of `scene` as one text: every `<include file=...>` replaced by the
    contents of the included file's root element (MuJoCo's own include rule), comments
    dropped, so that `MjModel.from_xml_string` builds the same model without files.

    Args:
      scene: "buttons" or "rods".

    Raises:
      ValueError: for another scene.
    """
    scene = _validate.one_of("scene", scene, SCENES)
    root = ElementTree.parse(asset_path(f"{scene}.xml")).getroot()
    _resolve_includes(root, {f"{scene}.xml"})
    return ElementTree.tostring(root, encoding="unicode")


def _resolve_includes(element, open_files):
    for child in list(element):
        if child.tag != "include":
            _resolve_includes(child, open_files)
            continue
        name = child.get("file")
        if name in open_files:
            raise ValueError(f"the MJCF file {name} includes itself")
        included = ElementTree.parse(asset_path(name)).getroot()
        _resolve_includes(included, open_files | {name})
        position = list(element).index(child)
        element.remove(child)
        for offset, grandchild in enumerate(list(included)):
            element.insert(position + offset, grandchild)


def _arm_export(arm, postures):
    """The arm's names, ranges and timing, and `postures` clipped to the ranges (as
    `icub.Arm.move` clips every goal)."""
    from icm.envs import icub

    return ({"joints": list(icub.ARM_JOINTS), "lower": arm.lower.tolist(),
             "upper": arm.upper.tolist(), "substeps": icub.SUBSTEPS,
             "update_seconds": arm.physics.model.opt.timestep * icub.SUBSTEPS},
            {name: np.clip(q, arm.lower, arm.upper).tolist() for name, q in postures.items()})


def _segment(arm, q, seconds):
    """One `icub.Arm.move(q, seconds)` as exported: [joint targets or None, updates]."""
    goal = None if q is None else np.clip(q, arm.lower, arm.upper).tolist()
    return [goal, arm.n_updates(seconds)]


def _buttons_physics():
    from icm.envs import buttons, icub

    physics = buttons.load_physics()
    task = buttons.ButtonsTask(random=0)
    with physics.reset_context():
        task.initialize_episode(physics)
    return physics, icub.Arm(physics), task.motions(physics)


def scene_export(scene):
    """Everything the browser needs to run `scene` as the Python task runs it, as a dict
    of JSON values: the MJCF text, the names and constants of the rules, and the
    controls of every discrete action.

    For "buttons": "presses", one list of motion segments per button (the scripted
    primitive of `PhysicsButtonConsole`: reach, push, hold, lift, return), and the
    rules of `ButtonsTask` and `PhysicsButtonConsole.press` (press depth, lids). For
    "rods": "moves", keyed "column,row,action", the segments of `PhysicsRodTable.move`
    from each cell in each direction (via the midpoint, then settling), "cells", the
    arm's posture over each cell, and the rules (tilts, times).

    A segment is [joint targets (7) or None, updates]: `icub.Arm.move` to those
    targets (None: hold the current ones) in that many 20 ms updates.

    Args:
      scene: "buttons" or "rods".

    Raises:
      ValueError: for another scene.
    """
    scene = _validate.one_of("scene", scene, SCENES)
    return LIVE_SCENES[scene]()


@register_scene("buttons")
def _buttons_export():
    from icm.envs import buttons

    console = buttons.PhysicsButtonConsole
    physics, arm, motions = _buttons_physics()
    arm_info, postures = _arm_export(arm, {"home": motions.home})
    presses = [[_segment(arm, motions.above[b], console.REACH_TIME),
                _segment(arm, motions.down[b], console.PUSH_TIME),
                _segment(arm, None, console.HOLD_TIME),
                _segment(arm, motions.above[b], console.LIFT_TIME),
                _segment(arm, motions.home, console.RETURN_TIME)]
               for b in range(buttons.N_BUTTONS)]
    return {
        "scene": "buttons", "xml": scene_xml("buttons"), "view": VIEWS["buttons"],
        "arm": arm_info,
        "home": postures["home"],
        "rules": {
            "buttons": [f"button{b}" for b in range(buttons.N_BUTTONS)],
            "caps": [f"button{b}_cap" for b in range(buttons.N_BUTTONS)],
            "light_materials": ["light_off", "red", "green"],
            "lids": [f"{name}_lid" for name in buttons.BOX_NAMES],
            "press_depth": buttons.PRESS_DEPTH,
            "lid_open_angle": float(buttons.physics.LID_OPEN_ANGLE),
            "box_open_angle": float(buttons.physics.BOX_OPEN_ANGLE),
            "lid_open_time": buttons.physics.LID_OPEN_TIME,
            "lid_shut_angle": float(console.LID_SHUT_ANGLE),
            "lid_wait_updates": arm.n_updates(console.LID_WAIT),
            "red_button": buttons.DEFAULT_RED_BUTTON,
            "green_candidates": buttons.green_candidates(buttons.DEFAULT_RED_BUTTON),
        },
        "presses": presses,
    }


@register_scene("rods")
def _rods_export():
    from icm.envs import icub, rods

    table = rods.PhysicsRodTable
    physics = rods.load_physics()
    task = rods.RodsTask()
    with physics.reset_context():
        task.initialize_episode(physics)
    arm, motions = icub.Arm(physics), task.motions(physics)
    cells = [(c, r) for r in range(rods.N_ROWS) for c in range(rods.N_COLUMNS)]
    arm_info, postures = _arm_export(arm, {f"{c},{r}": motions.cells[(c, r)]
                                           for c, r in cells})
    moves = {}
    for cell in cells:
        for action in range(len(rods.ACTIONS)):
            target = rods.next_cell(cell, action)
            segments = []
            if target != cell:
                segments = [_segment(arm, motions.midpoints[(cell, target)], table.SEGMENT_TIME),
                            _segment(arm, motions.cells[target], table.SEGMENT_TIME)]
            segments.append(_segment(arm, None, table.SETTLE_TIME))
            moves[f"{cell[0]},{cell[1]},{action}"] = {"to": list(target), "segments": segments}
    return {
        "scene": "rods", "xml": scene_xml("rods"), "view": VIEWS["rods"],
        "arm": arm_info, "cells": postures,
        "rules": {
            "rods": list(rods.ROD_NAMES), "bodies": [f"{n}_rod" for n in rods.ROD_NAMES],
            "columns": rods.N_COLUMNS, "rows": rods.N_ROWS, "actions": list(rods.ACTIONS),
            "start_cell": list(rods.DEFAULT_START_CELL),
            "topple_tilt": float(rods.TOPPLE_TILT), "tipping_tilt": float(table.TIPPING_TILT),
            "rest_speed": table.REST_SPEED, "fall_updates": arm.n_updates(table.FALL_TIME),
        },
        "moves": moves,
    }


def learner_replay(n_trials=DEFAULT_REPLAY_TRIALS, seed=0):
    """The first `n_trials` trials of run 0 of `run_goal_oriented(seed=seed)` (the
    paper's settings, the tabular console), press by press, for the browser to replay.

    The run is the same as `run_goal_oriented(n_seeds=1, n_trials=n_trials,
    seed=seed)`'s, recorded on the way (the tests check it).

    Args:
      n_trials: trials to replay (>= 1).
      seed: the root seed, as in `run_goal_oriented`.

    Returns:
      A dict: "seed" (the integer root seed), "trials", one dict per trial with
      "lights" (5 values: 0 off, 1 red, 2 green), "presses" (buttons), "boxes" (the
      boxes open after each press, [red, green]) and "interest" (interest in the red
      and the green task after the trial).
    """
    from icm.envs import buttons
    from icm.experiments import goal_oriented as experiment

    trials = []

    def record(trial, layout, actions, effects):
        if trial == len(trials):
            trials.append({"layout": int(layout[0]), "actions": [], "effects": []})
        trials[trial]["actions"].append(int(actions[0]))
        trials[trial]["effects"].append(int(effects[0]))

    result, = experiment.run_goal_oriented_grid(
        [{}], n_seeds=1, n_trials=n_trials, seed=seed, progress=False, observe=record)
    red = result.settings["red_button"]
    layouts = buttons.layouts(red)
    trials = [{"lights": layouts[trial["layout"]].tolist(),
               "presses": trial["actions"],
               "boxes": [list(buttons.EFFECTS[e]) for e in trial["effects"]],
               "interest": result.interest[0, t].tolist()}
              for t, trial in enumerate(trials)]
    return {"seed": result.settings["seed"], "trials": trials}


def rod_replay(n_episodes=DEFAULT_REPLAY_EPISODES, seed=0):
    """The first `n_episodes` episodes of run 0 of `run_rod_toppling(seed=seed)` (the
    paper's settings, the tabular twin), move by move, for the browser to replay.

    The run is the same as `run_rod_toppling(n_seeds=1, n_episodes=n_episodes,
    seed=seed)`'s, recorded on the way (the tests check it).

    Args:
      n_episodes: episodes to replay (>= 1).
      seed: the root seed, as in `run_rod_toppling`.

    Returns:
      A dict: "seed", "start_cell", and "episodes", one dict per episode with
      "actions" (moves, indices of `icm.envs.rods.ACTIONS`), "cells" (the cell
      before each move), "toppled" ("red", "blue" or None) and "errors" (the
      predictor's absolute errors on each rod summed over the episode: the intrinsic
      reward the robot was paid).
    """
    from icm import _validate
    from icm.envs import rods
    from icm.experiments import rod_toppling as experiment
    from icm.experiments._seeding import run_seeds
    from icm.learners import q_learning

    # run_rod_toppling's defaults, its seeds and the library's (the paper's) settings.
    n_episodes = _validate.integer_at_least("n_episodes", n_episodes, 1)
    seed = _validate.root_seed("seed", seed)
    start_cell, max_moves = rods.DEFAULT_START_CELL, rods.DEFAULT_MAX_MOVES
    learner = q_learning.QLearnerSettings()
    (env_seed, agent_seed), = run_seeds(seed, 1, 2)
    recorded = []

    def record(rows, cells, actions, next_cells, toppled):
        recorded.append((int(cells[0]), int(actions[0]), int(next_cells[0]),
                         int(toppled[0])))

    env = rods.RodTableBatch(1, start_cell, False, [env_seed])
    agent = q_learning.QLearner.from_settings(experiment.N_STATES, experiment.N_ACTIONS,
                                              len(rods.ROD_NAMES), learner, agent_seed)
    played = experiment.play_episodes(env, [agent], n_episodes, max_moves, observe=record)
    episodes, moves = [], iter(recorded)
    for e in range(n_episodes):
        length = int(played["length"][0, e])
        taken = [next(moves) for _ in range(length)]
        toppled = int(played["toppled"][0, e])
        episodes.append({"cells": [list(rods.number_cell(m[0])) for m in taken],
                         "actions": [m[1] for m in taken],
                         "toppled": rods.ROD_NAMES[toppled] if toppled >= 0 else None,
                         "errors": played["errors"][0, e].tolist()})
    return {"seed": seed, "start_cell": list(start_cell), "episodes": episodes}


def formed_presses(babbling, run=0):
    """The presses that goal babbling formed in run `run` of `babbling`, as the
    browser performs them: for each button, the movement `run_goal_babbling` learned
    for it (reach its joint targets, hold, return home: `goal_babbling.REACH_TIME`,
    `HOLD_TIME`, `RETRACT_TIME`), in a trial where that button is lit red, as
    `GoalBabblingResult.buttons_pressed` tests it.

    Args:
      babbling: a `GoalBabblingResult` (from `icm.experiments.run_goal_babbling`).
      run: which of its runs (0 .. n_seeds - 1).

    Returns:
      A dict: "run", "strategy", "presses" (one list of segments per button, as in
      `scene_export`), "lights" (the layout of each button's trial) and "pressed"
      (whether Python found that the movement presses its button alone and opens the
      red box).

    Raises:
      ValueError: if `babbling` is not a `GoalBabblingResult` or `run` not one of its
        runs.
    """
    from icm.envs import buttons
    from icm.experiments import goal_babbling

    _validate.instance("babbling", babbling, goal_babbling.GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    run = _validate.integer("run", run, 0, babbling.n_seeds - 1)
    _, arm, motions = _buttons_physics()
    presses = [[_segment(arm, q, goal_babbling.REACH_TIME),
                _segment(arm, q, goal_babbling.HOLD_TIME),
                _segment(arm, motions.home, goal_babbling.RETRACT_TIME)]
               for q in babbling.press_movements[run]]
    lights = [buttons.lights_for(b, buttons.green_candidates(b)[0]).tolist()
              for b in range(buttons.N_BUTTONS)]
    return {"run": run, "strategy": babbling.strategy, "presses": presses, "lights": lights,
            "pressed": [bool(p) for p in babbling.buttons_pressed[run]]}


def _poster(scene):
    """A JPEG still of `scene` from `POSTER_CAMERA`, at the moment of Figure 1: the
    green button held down and its box open, or the red rod falling."""
    from PIL import Image

    from icm.figures import icub as icub_figures

    physics = icub_figures.press_moment(seed=0)[0] if scene == "buttons" \
        else icub_figures.topple_moment()
    image = icub_figures.render(physics, POSTER_CAMERA, *POSTER_SIZE)
    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, "JPEG", quality=80, optimize=True)
    return buffer.getvalue()


_POSTER_ALT = {
    "buttons": "The simulated iCub at the button console, its finger holding the lit green "
               "button down, the green box open.",
    "rods": "The simulated iCub's hand moving into the red rod on the rod table; the rod is "
            "falling.",
}

_TITLES = {
    "scene": "the {scene} scene",
    "learner": "the goal-oriented learner's first trials",
    "rod_learner": "the Q-learner's first episodes",
    "formed": "the presses the robot formed",
}


class LiveView:
    """A live 3D view of the simulated iCub, for a notebook cell (`live_scene`,
    `live_learner`, `live_rod_learner`, `live_formed_presses` make them).

    In the HTML book it is the still of the scene with a button that starts the live
    view (book/_static/icm-live.js and the scripts it loads, only then); where the
    browser lacks WebGL or WebAssembly, and in print, the still stays, with a note. In
    a Jupyter kernel (the book's `_static` folder is not served there) and in a PDF it
    is the still with a note.

    Args:
      data: the view's data, as JSON values: `scene_export` plus "mode" and, for a
        replay, "replay".
      poster: the still, JPEG bytes.
      alt: the still's text alternative.
      live: True for the live viewer, False for the still with a note, None for the
        live viewer while the book is built (`BOOK_ENV` is "1") and the still
        elsewhere.
      static_path: where the page finds the book's `_static` folder, if the page does
        not say (Sphinx pages give `data-content_root`; default "_static/").

    Attributes:
      data, poster, alt, live, static_path: as given (live resolved).
      html: the view's HTML.
    """

    def __init__(self, data, poster, alt, live=None, static_path=None):
        self.data = _validate.instance("data", data, dict)
        if data.get("scene") not in SCENES or data.get("mode") not in _TITLES:
            raise ValueError(f"data must be a view's data with a scene ({', '.join(SCENES)}) "
                             f"and a mode ({', '.join(_TITLES)}), got "
                             f"{_validate.show(data)}")
        self.poster = _validate.instance("poster", poster, bytes, "JPEG bytes")
        self.alt = _validate.text("alt", alt)
        self.live, self.static_path = _check_view_arguments(live, static_path)
        self.html = self._html()

    @property
    def title(self):
        """What the view shows, in words."""
        return _TITLES[self.data["mode"]].format(scene=self.data["scene"])

    def _html(self):
        payload = json.dumps(self.data, separators=(",", ":"), sort_keys=True)
        view_id = "icm-live-" + hashlib.sha1(payload.encode()).hexdigest()[:10]
        image = base64.b64encode(self.poster).decode()
        still = (f'<img class="icm-live-poster" src="data:image/jpeg;base64,{image}" '
                 f'alt="{html.escape(self.alt)}" width="{POSTER_SIZE[1]}" '
                 f'height="{POSTER_SIZE[0]}">')
        if not self.live:
            return (f'<figure class="icm-live icm-live-still">{still}<figcaption '
                    f'class="icm-live-note">A still of {html.escape(self.title)}, rendered '
                    "from the model. In the HTML book this is a live 3D view, run by "
                    "MuJoCo in the reader's browser; it needs the book's scripts, which "
                    "a notebook server does not serve.</figcaption></figure>")
        data = payload.replace("</", "<\\/")
        title = html.escape(self.title)
        return (
            f'<div class="icm-live" id="{view_id}" data-title="{title}" '
            f'data-static="{html.escape(self.static_path)}">'
            f'<div class="icm-live-stage">{still}</div>'
            f'<p class="icm-live-note" id="{view_id}-note">A still of {title}. The live 3D '
            "view runs MuJoCo (WebAssembly) in your browser; its scripts, about 4 MB, load "
            "when you start it.</p>"
            '<p class="icm-live-print">In the HTML version of this book, this is a live 3D '
            "view.</p>"
            '<button type="button" class="icm-live-start" hidden>Start the live view</button>'
            f'<script type="application/json" class="icm-live-data">{data}</script>'
            f"<script>{_BOOTSTRAP.replace('VIEW_ID', view_id)}</script></div>")

    def _repr_html_(self):
        return self.html

    def _repr_mimebundle_(self, include=None, exclude=None):
        return {"text/html": self.html,
                "image/jpeg": base64.b64encode(self.poster).decode(),
                "text/plain": f"<live view of {self.title}>"}


def _check_view_arguments(live, static_path):
    """(live, static_path) of a `LiveView`, checked, with their defaults resolved."""
    live = None if live is None else _validate.boolean("live", live)
    static_path = "_static/" if static_path is None \
        else _validate.text("static_path", static_path)
    return (os.environ.get(BOOK_ENV) == "1" if live is None else live), static_path


# Shows the start button (so that without JavaScript the still and its note are all
# there is) and, on a click, loads the viewer once per page and starts this view.
_BOOTSTRAP = """(function () {
  var box = document.getElementById("VIEW_ID");
  var button = box.querySelector(".icm-live-start");
  button.hidden = false;
  button.addEventListener("click", function () {
    var root = document.documentElement.getAttribute("data-content_root");
    var base = root !== null ? root + "_static/" : box.getAttribute("data-static");
    button.disabled = true;
    button.textContent = "Loading the live view...";
    if (window.icmLive) { window.icmLive.start(box, base); return; }
    var script = document.createElement("script");
    script.src = base + "icm-live.js";
    script.onload = function () { window.icmLive.start(box, base); };
    script.onerror = function () { button.textContent = "The live view could not be loaded"; };
    document.head.appendChild(script);
  });
})();"""


def _view(data, scene, live, static_path):
    return LiveView(data, _poster(scene), _POSTER_ALT[scene], live, static_path)


def live_scene(scene, live=None, static_path=None):
    """The live view of a scene, for the reader to act in: on the button console, pick
    a button and the iCub presses it; on the rod table, move the hand over the grid
    (arrow keys or buttons). The same rules as the Python tasks decide what opens and
    what falls, the same physics (MuJoCo 3.14 in WebAssembly) moves it.

    Args:
      scene: "buttons" or "rods".
      live, static_path: see `LiveView`.

    Returns:
      A `LiveView`.
    """
    _check_view_arguments(live, static_path)
    data = dict(scene_export(scene), mode="scene")
    return _view(data, data["scene"], live, static_path)


def live_learner(n_trials=DEFAULT_REPLAY_TRIALS, seed=0, live=None, static_path=None):
    """The goal-oriented learner's first trials (`learner_replay`) replayed in the
    browser's physics, with the lights, the presses and the interest in each task.

    Args:
      n_trials, seed: see `learner_replay`.
      live, static_path: see `LiveView`.

    Returns:
      A `LiveView`.
    """
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    _check_view_arguments(live, static_path)
    data = dict(scene_export("buttons"), mode="learner",
                replay=learner_replay(n_trials, seed))
    return _view(data, "buttons", live, static_path)


def live_rod_learner(n_episodes=DEFAULT_REPLAY_EPISODES, seed=0, live=None, static_path=None):
    """The Q-learner's first episodes on the rods (`rod_replay`) replayed in the
    browser's physics, with each episode's prediction errors.

    Args:
      n_episodes, seed: see `rod_replay`.
      live, static_path: see `LiveView`.

    Returns:
      A `LiveView`.
    """
    n_episodes = _validate.integer_at_least("n_episodes", n_episodes, 1)
    _check_view_arguments(live, static_path)
    data = dict(scene_export("rods"), mode="rod_learner", replay=rod_replay(n_episodes, seed))
    return _view(data, "rods", live, static_path)


def live_formed_presses(babbling, run=0, live=None, static_path=None):
    """The presses goal babbling formed (`formed_presses`), performed in the browser's
    physics: the reader picks a button and the iCub makes its own movement for it.

    Args:
      babbling, run: see `formed_presses`.
      live, static_path: see `LiveView`.

    Returns:
      A `LiveView`.
    """
    _check_view_arguments(live, static_path)
    data = dict(scene_export("buttons"), mode="formed", replay=formed_presses(babbling, run))
    return _view(data, "buttons", live, static_path)


def write_page(folder, views, static_dir, title="The live iCub"):
    """Writes a page with `views` and the files they need into `folder`: index.html and
    a `_static` folder copied from `static_dir` (the book's, book/_static). For trying
    the viewer without building the book, and for the tests.

    Args:
      folder: the folder to write (created if missing).
      views: a list of `LiveView` (made with live=True).
      static_dir: the book's `_static` folder.
      title: the page's title.

    Returns:
      The path of index.html.

    Raises:
      ValueError: for a view that is not a live `LiveView`, or a `static_dir` without
        the viewer's files.
    """
    folder = pathlib.Path(_validate.instance("folder", folder, (str, os.PathLike),
                                             "a path"))
    static_dir = pathlib.Path(_validate.instance("static_dir", static_dir,
                                                 (str, os.PathLike), "a path"))
    if isinstance(views, (str, bytes)) or not isinstance(views, (list, tuple)) or not views:
        raise _validate.ArgumentTypeError(f"views must be a non-empty list of LiveView, got "
                                          f"{_validate.show(views)}")
    for i, view in enumerate(views):
        _validate.instance(f"views[{i}]", view, LiveView)
        if not view.live:
            raise ValueError(f"views[{i}] must be a live view (made with live=True), got the "
                             "still")
    missing = [name for name in STATIC_FILES if not (static_dir / name).is_file()]
    if missing:
        raise ValueError(f"static_dir {str(static_dir)!r} lacks the viewer's files "
                         f"{', '.join(missing)} (the book's _static folder has them)")
    for name in STATIC_FILES:
        (folder / "_static" / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(static_dir / name, folder / "_static" / name)
    body = "\n".join(f"<section><h2>{html.escape(view.title.capitalize())}</h2>{view.html}"
                     "</section>" for view in views)
    path = folder / "index.html"
    path.write_text(
        f'<!DOCTYPE html>\n<html lang="en" data-content_root="./"><head><meta charset="utf-8">'
        f'<title>{html.escape(_validate.text("title", title))}</title>'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        '<link rel="stylesheet" href="_static/icm.css"></head>'
        f'<body><main class="bd-article" style="max-width: 52rem; margin: auto">'
        f"<h1>{html.escape(title)}</h1>\n{body}\n</main></body></html>\n")
    return path
