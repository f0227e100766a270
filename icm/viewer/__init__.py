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

The package holds three modules: `scenes` (the exports, and `register_scene`, where a
scenario's live view registers), `replays` (the runs replayed) and `live` (the views
and the page). Every public name is importable from here, e.g. `icm.viewer.live_scene`.
"""

from icm.store import asset_path  # noqa: F401 (the scenes' files)
from icm.viewer.scenes import (BROWSER_MUJOCO, LIVE_SCENES, SCENES, VIEWS, register_scene,
                               scene_export, scene_xml)
from icm.viewer.replays import (DEFAULT_REPLAY_EPISODES, DEFAULT_REPLAY_TRIALS, formed_presses,
                                learner_replay, rod_replay)
from icm.viewer.live import (BOOK_ENV, POSTER_CAMERA, POSTER_SIZE, STATIC_FILES, LiveView,
                             live_formed_presses, live_learner, live_rod_learner, live_scene,
                             write_page)

__all__ = ["BOOK_ENV", "BROWSER_MUJOCO", "DEFAULT_REPLAY_EPISODES", "DEFAULT_REPLAY_TRIALS",
           "LIVE_SCENES", "LiveView", "POSTER_CAMERA", "POSTER_SIZE", "SCENES", "STATIC_FILES",
           "VIEWS", "formed_presses", "learner_replay", "live_formed_presses", "live_learner",
           "live_rod_learner", "live_scene", "register_scene", "rod_replay", "scene_export",
           "scene_xml", "write_page"]
