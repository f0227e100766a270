"""The views a notebook shows: a still of the scene rendered from the model, and in the
HTML book the live viewer (book/_static/icm-live.js) that starts on request; and a page
of views (`write_page`). See `icm.viewer`."""

import base64
import hashlib
import html
import io
import json
import os
import pathlib
import shutil

from icm import _book, _validate
from icm.viewer.replays import (DEFAULT_REPLAY_EPISODES, DEFAULT_REPLAY_TRIALS, formed_presses,
                                learner_replay, rod_replay)
from icm.viewer.scenes import SCENES, scene_export

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
