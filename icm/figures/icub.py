"""Figures of the simulated iCub: Figure 1 rendered from the model, animations of a
press and a topple, a press's time series, and the measured topple map."""

import html as _html
import re
import textwrap

import matplotlib.animation
import matplotlib.patches
import mujoco
import numpy as np

from icm import _validate
from icm.envs import buttons, rods
from icm.figures._common import TASK_COLOURS, new_figure, series_style

ROD_COLOURS = {"red": TASK_COLOURS["red"], "blue": "#1f5fcc"}

CAMERA_TITLES = {"over_shoulder": "Over the shoulder", "side": "From the side",
                 "eyes": "Through the robot's eyes", "front": "From the front",
                 "close_up": "Close-up of the hand"}
"""Readable titles of the scenes' cameras, for figures."""


def camera_title(camera):
    """A readable title for the camera named `camera`: from `CAMERA_TITLES`, else the
    name with spaces for underscores and a capital first letter."""
    camera = _validate.text("camera", camera)
    return CAMERA_TITLES.get(camera, camera.replace("_", " ").capitalize())


def check_camera(physics, camera):
    """Returns `camera` if it names a camera of the scene of `physics`, else raises
    ValueError listing the scene's cameras."""
    from dm_control import mujoco as dm_mujoco

    _validate.instance("physics", physics, dm_mujoco.Physics, "a dm_control Physics")
    names = tuple(physics.model.id2name(i, "camera") for i in range(physics.model.ncam))
    return _validate.one_of("camera", camera, names)


def check_image_size(height, width):
    """(height, width) in pixels, each an integer in 16..the model's offscreen buffer
    (960 x 1280)."""
    return (_validate.integer("height", height, 16, 960),
            _validate.integer("width", width, 16, 1280))


def render(physics, camera, height=480, width=640):
    """An RGB image (height, width, 3) of `physics` seen from the named `camera`."""
    camera = check_camera(physics, camera)
    height, width = check_image_size(height, width)
    return physics.render(height, width, camera_id=camera)


def visible_geoms(physics, camera, height=240, width=320):
    """What the named `camera` sees of each geom: a dict {geom name: number of pixels
    in which that geom is the nearest surface}, from MuJoCo's segmentation rendering.
    Geoms hidden behind others, or outside the frame, are absent."""
    camera = check_camera(physics, camera)
    height, width = check_image_size(height, width)
    segmentation = physics.render(height, width, camera_id=camera, segmentation=True)
    ids = segmentation[..., 0][segmentation[..., 1] == mujoco.mjtObj.mjOBJ_GEOM]
    geoms, counts = np.unique(ids, return_counts=True)
    return {physics.model.id2name(int(g), "geom"): int(n) for g, n in zip(geoms, counts)}


def project(physics, camera, points, height=480, width=640):
    """Where world `points` (n, 3) appear in an image of `camera` (its size `height` x
    `width`): an array (n, 2) of (column, row) pixel coordinates, from dm_control's
    camera matrix."""
    from dm_control.mujoco import Camera

    camera = check_camera(physics, camera)
    height, width = check_image_size(height, width)
    points = np.atleast_2d(_validate.finite_array("points", points))
    if points.shape[1] != 3:
        raise ValueError(f"points must be an array (n, 3) of world positions, got shape "
                         f"{points.shape}")
    return _pixels(Camera(physics, height, width, camera_id=camera).matrix, points)


def _label(ax, xy, text, offset=(0, -40), fontsize=8):
    """Writes `text` in a white box near pixel `xy` of an image axis, with an arrow to it."""
    ax.annotate(text, xy=xy, xytext=offset, textcoords="offset points", ha="center",
                fontsize=fontsize, bbox=dict(boxstyle="round,pad=0.25", facecolor="white",
                                             edgecolor="#444444", linewidth=0.8),
                arrowprops=dict(arrowstyle="-|>", color="#222222", linewidth=1.2))


def press_moment(seed=0):
    """The button scene at the moment of Figure 1 (a): the finger holding the lit green
    button down and the green lid open.

    Runs the press primitive's reach and push on a `PhysicsButtonConsole` (seeded with
    `seed`, which draws the layout) and stops the physics once the green lid is open.

    Returns:
      (physics, button): the scene's physics at that moment and the pressed button.
    """
    env = buttons.PhysicsButtonConsole(seed=seed)
    env.reset()
    green = env.green_button
    physics, task, motions = env.physics, env.task, env.motions
    watch = lambda: task.update(physics) or False
    env.arm.move(motions.above[green], env.REACH_TIME, watch)
    env.arm.move(motions.down[green], env.PUSH_TIME, watch)
    env.arm.hold(1.5, lambda: task.update(physics) or physics.lid_angles()[1] > np.deg2rad(80))
    return physics, green


def topple_moment(start_cell=(2, 0), action=0):
    """The rod scene at the moment of Figure 1 (b): the hand has hit the red rod, which
    is falling (tilted past 35 degrees; if no rod tilts that far, the end of the move).

    Args:
      start_cell: the hand's cell before the move.
      action: the move (an index into `icm.envs.rods.ACTIONS`).

    Returns:
      The scene's physics at that moment.
    """
    env = rods.PhysicsRodTable(start_cell=start_cell)
    action = _validate.integer("action", action, 0, len(rods.ACTIONS) - 1)
    env.reset()
    caught = []

    def catch(physics):
        if not caught and physics.rod_tilt("red") > np.deg2rad(35):
            caught.append(physics.data.qpos.copy())

    env.move(action, recorder=catch)
    physics = env.physics
    if caught:  # what the camera sees depends on the positions alone
        physics.data.qpos[:] = caught[0]
        physics.forward()
    return physics


def pressing_green(seed=0, camera="front", height=480, width=640):
    """Renders the iCub pressing the lit green button, once the green box is open (the
    moment of `press_moment`)."""
    check_image_size(height, width)
    physics, _ = press_moment(seed)
    return render(physics, camera, height, width)


def toppling_rod(camera="front", height=480, width=640, start_cell=(2, 0), action=0):
    """Renders the iCub's hand toppling the red rod, caught while the rod falls (the
    moment of `topple_moment`)."""
    check_image_size(height, width)
    return render(topple_moment(start_cell, action), camera, height, width)


PRESS_VIEW = {"lookat": (0.35, -0.08, 0.6), "distance": 0.85, "azimuth": 210.0,
              "elevation": -28.0}
"""The free camera of Figure 1 (a) (MuJoCo's lookat, distance in metres, azimuth and
elevation in degrees): in front of the robot and to its right, where the open green
lid stands out against the table."""
ROD_VIEW = {"lookat": (0.25, -0.08, 0.65), "distance": 0.7, "azimuth": 115.0,
            "elevation": -16.0}
"""The free camera of Figure 1 (b): from the robot's right, across the rod's fall, so
that the falling rod is seen along its length, not end on (from the front it looks like
a small cube)."""


def _free_view(physics, view, height, width):
    """(image, camera matrix) of a free camera posed by `view` (as `ROD_VIEW`)."""
    from dm_control.mujoco import MovableCamera

    camera = MovableCamera(physics, height, width)
    camera.set_pose(np.array(view["lookat"], dtype=float), view["distance"], view["azimuth"],
                    view["elevation"])
    return camera.render(), camera.matrix


def _pixels(matrix, points):
    projected = np.column_stack([points, np.ones(len(points))]) @ matrix.T
    return projected[:, :2] / projected[:, 2:3]


def figure1(seed=0):
    """Figure 1, rebuilt from the model: (a) the iCub pushing the green button, the
    green box open (seen from `PRESS_VIEW`); (b) the iCub's hand toppling the red rod,
    seen from the robot's right (`ROD_VIEW`). Labels point at what each panel is about:
    the open green lid and the shut red box, the falling red rod and the standing blue
    one."""
    height, width = 480, 640
    fig, (left, right) = new_figure(width=11, height=4.4, ncols=2)
    physics, _ = press_moment(seed)
    image, matrix = _free_view(physics, PRESS_VIEW, height, width)
    left.imshow(image)
    lid, box = _pixels(matrix, [physics.named.data.geom_xpos["green_lid"],
                                physics.named.data.geom_xpos["red_lid"]])
    _label(left, lid, "green lid: open", offset=(10, 55))
    _label(left, box, "red box: shut", offset=(40, -40))
    rod_physics = topple_moment()
    image, matrix = _free_view(rod_physics, ROD_VIEW, height, width)
    right.imshow(image)
    red, blue = _pixels(matrix, [rod_physics.named.data.xpos[f"{name}_rod"]
                                 for name in rods.ROD_NAMES])
    _label(right, red, "red rod: falling", offset=(-115, -20))
    _label(right, blue, "blue rod: standing", offset=(55, 60))
    for ax, title in [(left, "(a) pressing the green button opens the green box"),
                      (right, "(b) the hand topples the red rod")]:
        ax.set_title(textwrap.fill(title, 32), fontsize=10)
        ax.axis("off")
    return fig.describe("The paper's Figure 1, rendered from the model: (a) the iCub's "
                        "finger holds the lit green button down and the green box's lid is "
                        "open, the red box shut; (b) seen from the robot's right, its hand "
                        "has moved into the red rod, which falls, the blue rod standing.")


def cameras_figure(physics, cameras, height=240, width=320, number_buttons=False):
    """The scene of `physics` from each of `cameras`, side by side.

    Args:
      physics: a scene's physics.
      cameras: the names of its cameras to show, a non-empty list.
      height, width: each image's size in pixels.
      number_buttons: write each button's number above it (the button scene only),
        in each view where the buttons are far enough apart for the numbers to be read.
    """
    if isinstance(cameras, str) or not isinstance(cameras, (list, tuple)) or not cameras:
        raise _validate.ArgumentTypeError(f"cameras must be a non-empty list of camera "
                                          f"names, got {_validate.show(cameras)}")
    for camera in cameras:
        check_camera(physics, camera)
    number_buttons = _validate.boolean("number_buttons", number_buttons)
    if number_buttons and not isinstance(physics, buttons.ButtonsPhysics):
        raise ValueError(f"number_buttons needs the button scene's physics, got "
                         f"{type(physics).__name__}")
    fig, axes = new_figure(width=3.2 * len(cameras), height=2.7, ncols=len(cameras))
    for ax, camera in zip(np.atleast_1d(axes), cameras):
        ax.imshow(render(physics, camera, height, width))
        ax.set_title(camera_title(camera), fontsize=9)
        ax.axis("off")
        if number_buttons:
            physics.forward()
            caps = [physics.named.data.geom_xpos[f"button{b}_cap"] + [0.0, 0.0, 0.03]
                    for b in range(buttons.N_BUTTONS)]
            pixels = project(physics, camera, caps, height, width)
            if np.linalg.norm(np.diff(pixels, axis=0), axis=1).min() < 0.06 * width:
                continue  # the buttons seen end on: the numbers would overlap
            for b, (column, row) in enumerate(pixels):
                if 0 <= column < width and 0 <= row < height:
                    ax.text(column, row, str(b), ha="center", va="bottom", fontsize=8,
                            fontweight="bold", bbox=dict(boxstyle="round,pad=0.12",
                                                         facecolor="white", linewidth=0,
                                                         alpha=0.85))
    return fig


def record_press(seed=0, button=None, camera=None, frame_every=2, height=240, width=320):
    """Runs one press on the simulated iCub and records it.

    Args:
      seed: the environment's seed (it draws the layout).
      button: the button to press; default the lit green one.
      camera: if given, also render a frame from this camera every `frame_every`
        control updates (40 ms of simulated time at 2).

    Returns:
      A dict of arrays: "time" (s since the press started, at the end of each update
      of the motors' targets), "depth" (the pressed button's depth, mm), "other"
      (deepest of the other buttons, mm), "lids" (red and green lid angles, degrees),
      "fingertip" (m), "frames" (list of images), and "button", "boxes" (the
      observation after the press), "lights".
    """
    frame_every = _validate.integer("frame_every", frame_every, 1)
    env = buttons.PhysicsButtonConsole(seed=seed)
    env.reset()
    if camera is not None:
        check_camera(env.physics, camera)
        check_image_size(height, width)
    button = env.green_button if button is None else \
        _validate.integer("button", button, 0, buttons.N_BUTTONS - 1)
    log = {"time": [], "depth": [], "other": [], "lids": [], "fingertip": [], "frames": []}

    def recorder(physics):
        depths = physics.button_depths() * 1000
        log["time"].append(physics.data.time)
        log["depth"].append(depths[button])
        log["other"].append(np.delete(depths, button).max())
        log["lids"].append(np.rad2deg(physics.lid_angles()))
        log["fingertip"].append(physics.fingertip_position())
        if camera is not None and len(log["time"]) % frame_every == 1:
            log["frames"].append(render(physics, camera, height, width))
            log["frame_index"].append(len(log["time"]) - 1)

    log["frame_index"] = []
    started = env.physics.data.time
    boxes = env.press(button, recorder=recorder)
    out = {key: np.array(value) for key, value in log.items() if key != "frames"}
    out["time"] = out["time"] - started  # the first update ends 20 ms after the start
    out.update(frames=log["frames"], button=button, boxes=boxes, lights=env.lights)
    out["captions"] = [f"t = {out['time'][i]:.2f} s, button {button} in "
                       f"{max(out['depth'][i], 0.0):.1f} mm\nlids: red "
                       f"{max(out['lids'][i, 0], 0.0):.0f} deg, green "
                       f"{max(out['lids'][i, 1], 0.0):.0f} deg" for i in out["frame_index"]]
    return out


def record_move(start_cell=(2, 0), action=0, camera=None, frame_every=2, height=240,
                width=320):
    """Runs one move of the hand on the rod table and records the rods' tilts (degrees)
    and, if `camera` is given, frames. Returns a dict like `record_press`."""
    frame_every = _validate.integer("frame_every", frame_every, 1)
    env = rods.PhysicsRodTable(start_cell=start_cell)
    env.reset()
    if camera is not None:
        check_camera(env.physics, camera)
        check_image_size(height, width)
    log = {"time": [], "tilts": [], "frames": [], "frame_index": []}

    def recorder(physics):
        log["time"].append(physics.data.time)
        log["tilts"].append(np.rad2deg(physics.rod_tilts()))
        if camera is not None and len(log["time"]) % frame_every == 1:
            log["frames"].append(render(physics, camera, height, width))
            log["frame_index"].append(len(log["time"]) - 1)

    toppled = env.move(action, recorder=recorder)
    time = np.array(log["time"]) - log["time"][0]
    tilts = np.array(log["tilts"])
    captions = [f"t = {time[i]:.2f} s\ntilt: red rod {tilts[i, 0]:.0f} deg, blue rod "
                f"{tilts[i, 1]:.0f} deg" for i in log["frame_index"]]
    return {"time": time, "tilts": tilts, "frames": log["frames"], "captions": captions,
            "toppled": toppled}


OBSERVATION_ENTRIES = {
    "arm_joints": ("the arm's joint angles, in the order of the joints' table",
                   "degrees", np.rad2deg, 1),
    "fingertip": ("where the fingertip is: forward, to the robot's left, and up, from the "
                  "floor under the robot's seat", "m", None, 3),
    "button_depths": ("how far each button is pushed in, from button 0 on",
                      "mm", lambda metres: 1000 * metres, 1),
    "lights": ("each button's light, from button 0 on", "code", None, 0),
    "lid_angles": ("how far each lid has opened: red, then green", "degrees",
                   np.rad2deg, 1),
    "rod_tilts": ("each rod's tilt from upright, in the scene's order of rods",
                  "degrees", np.rad2deg, 1),
    "rod_positions": ("the rods' centres, one rod after the other, each forward, left "
                      "and up", "m", None, 3),
}
"""How `observation_table` shows each entry of the continuous tasks' observations: its
meaning in words, its unit, the conversion from the observation's unit (radians,
metres) and the decimals shown."""
LIGHT_WORDS = {buttons.OFF: "off", buttons.RED: "red", buttons.GREEN: "green"}
"""The lights' codes in an observation, in words."""


def shown_values(values, decimals):
    """`values` rounded to `decimals` as text, with no negative zero: a value that
    rounds to zero reads "0.0", never "-0.0" (a button resting a few micrometres above
    its stop has a depth of about -0.006 mm, which rounds to zero)."""
    values = _validate.finite_array("values", values)
    decimals = _validate.integer("decimals", decimals, 0, 12)
    rounded = np.round(values, decimals) + 0.0  # -0.0 + 0.0 is 0.0
    return [f"{v:.{decimals}f}" for v in np.ravel(rounded)]


def observation_table(observation):
    """A continuous task's observation as a Markdown table a reader can follow: each
    entry with what it holds, its unit and its values, angles in degrees, depths in
    millimetres, the lights' codes with their words, and no negative zeros.

    Args:
      observation: a dict {entry name: array of numbers}, as in the `observation` of a
        time step of `icm.envs.load_continuous(name)`. Entries not in
        `OBSERVATION_ENTRIES` are shown as they are, to 3 decimals.

    Returns:
      A Markdown string (display it with `IPython.display.Markdown`).

    Raises:
      TypeError, ValueError: for an observation that is not a non-empty dict of finite
        numbers, or lights that are not codes of `LIGHT_WORDS`.
    """
    if not isinstance(observation, dict) or not observation or \
            not all(isinstance(k, str) for k in observation):
        raise _validate.ArgumentTypeError(f"observation must be a non-empty dict of named "
                                          f"arrays (a time step's observation), got "
                                          f"{_validate.show(observation)}")
    lines = ["| entry | what it holds | unit | values |", "|---|---|---|---|"]
    for name, value in observation.items():
        value = _validate.finite_array(f"observation[{name!r}]", value)
        meaning, unit, convert, decimals = OBSERVATION_ENTRIES.get(
            name, ("", "as observed", None, 3))
        if name == "lights":
            codes = [int(c) for c in np.ravel(value)]
            if any(c not in LIGHT_WORDS or c != v for c, v in zip(codes, np.ravel(value))):
                raise ValueError(f"observation['lights'] must hold light codes "
                                 f"{sorted(LIGHT_WORDS)}, got {_validate.show(value)}")
            shown = ", ".join(f"{c} ({LIGHT_WORDS[c]})" for c in codes)
            unit = ", ".join(f"{c} {word}" for c, word in LIGHT_WORDS.items())
        else:
            shown = ", ".join(shown_values(value if convert is None else convert(value),
                                           decimals))
        lines.append(f"| `{name}` | {meaning} | {unit} | {shown} |")
    return "\n".join(lines)


def press_trace_figure(record):
    """The pressed button's depth and the lids' angles against time during one press
    (`record`: as returned by `record_press`)."""
    needed = ("time", "depth", "other", "lids", "button")
    if not isinstance(record, dict) or not all(k in record for k in needed):
        raise _validate.ArgumentTypeError(f"record must be the dict of record_press (with "
                                          f"{', '.join(needed)}), got {_validate.show(record)}")
    fig, (top, bottom) = new_figure(width=7.5, height=4.6, nrows=2, sharex=True)
    top.plot(record["time"], record["depth"], color="black", linewidth=2,
             label=f"button {record['button']} (pressed)")
    top.plot(record["time"], record["other"], color="grey", linestyle="--",
             label="deepest of the other buttons")
    top.axhline(buttons.PRESS_DEPTH * 1000, color="#888888", linewidth=0.8)
    top.text(record["time"][0], buttons.PRESS_DEPTH * 1000, "press threshold",
             va="bottom", ha="left", fontsize=8, color="#555555")
    top.set_ylabel("depth (mm)")
    # Upper left, over the wait before the press: at the upper right the legend lay
    # on the release of the button (2 points of its curve, at the PNG's 110 dpi).
    top.legend(frameon=False, fontsize=8, loc="upper left")
    for i, name in enumerate(buttons.BOX_NAMES):
        bottom.plot(record["time"], record["lids"][:, i], color=TASK_COLOURS[name],
                    linewidth=2, label=f"{name} lid",
                    linestyle=series_style(name)["linestyle"])
    bottom.axhline(np.rad2deg(buttons.BOX_OPEN_ANGLE), color="#888888", linewidth=0.8)
    bottom.text(record["time"][-1], np.rad2deg(buttons.BOX_OPEN_ANGLE), "counts as open",
                va="bottom", ha="right", fontsize=8, color="#555555")
    bottom.set_ylabel("lid angle (degrees)")
    bottom.set_xlabel("time since the start of the press (s)")
    bottom.legend(frameon=False, fontsize=8, loc="center left")
    return fig


def animation(frames, captions=None, fps=12):
    """A matplotlib animation of rendered `frames`, each with its caption.

    Args:
      frames: RGB arrays of equal size.
      captions: one line of text per frame (e.g. the time and what the sensors read).
      fps: frames per second when played.

    Returns:
      A `matplotlib.animation.FuncAnimation`; in a notebook, show it with
      `IPython.display.HTML(animation.to_jshtml())`, a player with play, pause and
      step buttons that needs no video codec and no network.
    """
    if not isinstance(frames, (list, tuple)) or not frames or not all(
            isinstance(f, np.ndarray) and f.ndim == 3 and f.shape == frames[0].shape
            for f in frames):
        raise _validate.ArgumentTypeError(f"frames must be a non-empty list of RGB images of "
                                          f"one size, got {_validate.show(frames)}")
    if captions is not None and (not isinstance(captions, (list, tuple))
                                 or len(captions) != len(frames)):
        raise ValueError(f"captions must be None or one caption per frame "
                         f"({len(frames)}), got {_validate.show(captions)}")
    fps = _validate.real("fps", fps, 0.0, 120.0, low_open=True)
    height, width = frames[0].shape[:2]
    fig, ax = new_figure(width=width / 80, height=height / 80 + 0.5)
    ax.axis("off")
    image = ax.imshow(frames[0])
    # 16 screen px at the player's 100 dpi: readable where the frames are shown.
    title = ax.set_title(captions[0] if captions else "", fontsize=11.5, family="monospace")

    def draw(i):
        image.set_data(frames[i])
        if captions:
            title.set_text(captions[i])
        return image, title

    return matplotlib.animation.FuncAnimation(fig, draw, frames=len(frames),
                                              interval=1000 / fps, blit=False)


def topple_map_figure(topple_map=None):
    """The measured topple map on the 5 x 3 grid: an arrow for every move that topples
    a rod, coloured by the rod; the rods' cells and the cells where the hand cannot
    rest with the rods standing are marked.

    Args:
      topple_map: as returned by `icm.envs.rods.load_topple_map()` (default: that).
    """
    if topple_map is not None and (not isinstance(topple_map, dict)
                                   or not {"standable", "topples"} <= set(topple_map)):
        raise _validate.ArgumentTypeError(f"topple_map must be None or a map as "
                                          f"icm.envs.rods.load_topple_map returns it, got "
                                          f"{_validate.show(topple_map)}")
    topple_map = rods.load_topple_map() if topple_map is None else topple_map
    fig, ax = new_figure(width=6.4, height=4.4)
    physics = rods.load_physics()
    physics.forward()
    rod_cells = {}
    for name in rods.ROD_NAMES:
        position = physics.named.data.xpos[f"{name}_rod"][:2]
        rod_cells[name] = min(
            ((c, r) for c in range(rods.N_COLUMNS) for r in range(rods.N_ROWS)),
            key=lambda cell: np.linalg.norm(physics.cell_centre(cell)[:2] - position))
    for column in range(rods.N_COLUMNS):
        for row in range(rods.N_ROWS):
            cell = (column, row)
            standable = cell in topple_map["standable"]
            ax.add_patch(matplotlib.patches.Rectangle(
                (column - 0.45, row - 0.45), 0.9, 0.9, facecolor="#f4f4f4" if standable
                else "white", edgecolor="#bbbbbb", hatch=None if standable else "///"))
            ax.text(column - 0.4, row - 0.4, f"{column},{row}", fontsize=7, color="#999999")
    for name, (column, row) in rod_cells.items():
        ax.add_patch(matplotlib.patches.Rectangle((column - 0.1, row - 0.1), 0.2, 0.2,
                                                  facecolor=ROD_COLOURS[name]))
        ax.text(column, row + 0.22, f"{name} rod", ha="center", fontsize=8,
                color=ROD_COLOURS[name])
    for (cell, action), rod in topple_map["topples"].items():
        if rod is None:
            continue
        target = rods.next_cell(cell, action)
        ax.annotate("", xy=(cell[0] + 0.7 * (target[0] - cell[0]), cell[1] + 0.7 * (target[1] - cell[1])),
                    xytext=cell, arrowprops=dict(arrowstyle="-|>", color=ROD_COLOURS[rod],
                                                 linewidth=2.2, shrinkA=4))
    ax.set_xlim(-0.6, rods.N_COLUMNS - 0.4)
    ax.set_ylim(-0.6, rods.N_ROWS - 0.4)
    ax.set_aspect("equal")
    ax.set_xticks(range(rods.N_COLUMNS), [f"col {c}" for c in range(rods.N_COLUMNS)])
    ax.set_yticks(range(rods.N_ROWS), ["row 0 (near)", "row 1", "row 2 (far)"])
    ax.tick_params(length=0)
    for spine in ax.spines.values():
        spine.set_visible(False)
    counts = rods.topple_counts(topple_map)
    ax.set_title(f"Moves that topple a rod, measured in physics: red {counts['red']}, "
                 f"blue {counts['blue']}", fontsize=10)
    return fig


def animation_html(frames, captions=None, fps=12, description=None):
    """`animation(frames, captions, fps)` as an HTML player (JPEG frames embedded in the
    page, play/pause/step buttons, no video codec or network needed), usable by every
    reader: the frame has alternative text (`description`, by default made from the
    first and last captions), the frame slider a name, and under the player the
    captions of the frames are listed in words (a text alternative, folded).

    Matplotlib's player links its button icons (Font Awesome) from a CDN; the link is
    dropped, so that the page needs no network: the book's theme ships Font Awesome.
    Its repetition-mode form is not made a landmark (two players on a page would be
    two landmarks of the same name): its name moves to a fieldset.
    """
    if description is not None:
        description = _validate.text("description", description)
    with matplotlib.rc_context({"animation.frame_format": "jpeg"}):
        html = animation(frames, captions, fps).to_jshtml()
    html = re.sub(r"<link[^>]*font-awesome[^>]*>", "", html)
    lines = [" ".join(c.split()) for c in captions] if captions else []
    if description is None:
        description = (f"An animation of {len(frames)} frames of the simulated iCub"
                       + (f", from \"{lines[0]}\" to \"{lines[-1]}\"" if lines else "") + ".")
    alt = _html.escape(description, quote=True)
    html = re.sub(r'<img id="(_anim_img\w+)">', rf'<img id="\1" alt="{alt}">', html)
    html = re.sub(r'(<input id="_anim_slider\w+" type="range")',
                  r'\1 aria-label="Frame of the animation"', html)
    html = re.sub(r'<form title="Repetition mode" aria-label="Repetition mode" ([^>]*)>',
                  r'<form \1><fieldset class="icm-anim-mode"><legend class="visually-hidden">'
                  r'Repetition mode</legend>', html)
    html = html.replace("</form>", "</fieldset></form>")
    if lines:
        items = "".join(f"<li>{_html.escape(line)}</li>" for line in lines)
        html += (f'<details class="icm-anim-text"><summary>The {len(lines)} frames in '
                 f'words</summary><ol>{items}</ol></details>')
    return html
