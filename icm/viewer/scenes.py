"""The scenes of the live iCub, exported for MuJoCo's WebAssembly build in the reader's
browser: each scene's MJCF as one text, the names and constants of its rules and the
controls of its discrete actions (see `icm.viewer`). A scenario's export registers
itself here (`register_scene`)."""

import xml.etree.ElementTree as ElementTree

import numpy as np

from icm import _validate
from icm._settings import Names
from icm.store import asset_path

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


def segment(arm, q, seconds):
    """One `icub.Arm.move(q, seconds)` as exported: [joint targets or None, updates]."""
    goal = None if q is None else np.clip(q, arm.lower, arm.upper).tolist()
    return [goal, arm.n_updates(seconds)]


def buttons_physics():
    """The button scene's physics at the start of an episode: (physics, its
    `icub.Arm`, the scripted motions of `ButtonsTask`)."""
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
    physics, arm, motions = buttons_physics()
    arm_info, postures = _arm_export(arm, {"home": motions.home})
    presses = [[segment(arm, motions.above[b], console.REACH_TIME),
                segment(arm, motions.down[b], console.PUSH_TIME),
                segment(arm, None, console.HOLD_TIME),
                segment(arm, motions.above[b], console.LIFT_TIME),
                segment(arm, motions.home, console.RETURN_TIME)]
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
                segments = [segment(arm, motions.midpoints[(cell, target)], table.SEGMENT_TIME),
                            segment(arm, motions.cells[target], table.SEGMENT_TIME)]
            segments.append(segment(arm, None, table.SETTLE_TIME))
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
