"""The simulated iCub's pictures show what their captions say: the finger on the button
at the press, the hand and the rod at the topple, the whole robot in Figure 1, no
artefact on the elbow, and readable titles. Checked with MuJoCo's segmentation
rendering (which geom is the nearest surface in each pixel), at small sizes."""

import os
import re

os.environ.setdefault("MUJOCO_GL", "egl")  # before dm_control picks a renderer

import numpy as np  # noqa: E402
import pytest  # noqa: E402
import scipy.ndimage  # noqa: E402
from dm_control.mujoco import Camera, MovableCamera  # noqa: E402

import icm  # noqa: E402
from icm.envs import buttons, rods  # noqa: E402
from icm.figures import icub as figures_icub  # noqa: E402
from test_bad_input import refused  # noqa: E402

HEIGHT, WIDTH = 240, 320  # the animations' frame size
SEEN = 60
"""Pixels (of 320 x 240) a geom must fill to count as clearly seen: the finger (r_finger)
fills 125-180 of them from the close-up camera at the deepest point of a press,
15-35 from over the shoulder."""


def robot_geoms(physics):
    """Ids of the drawn geoms of the robot (the body "icub" and everything on it)."""
    model = physics.model
    robot = model.name2id("icub", "body")

    def on_robot(body):
        while body != 0:
            if body == robot:
                return True
            body = model.body_parentid[body]
        return False

    return [g for g in range(model.ngeom) if on_robot(model.geom_bodyid[g])
            and model.geom_group[g] < 3 and model.id2name(g, "geom") != "stool"]


def fingertip_pixel(physics, camera):
    """The (column, row) pixel where the fingertip site appears from `camera`."""
    matrix = Camera(physics, HEIGHT, WIDTH, camera).matrix
    x = matrix @ np.append(physics.named.data.site_xpos["fingertip"], 1.0)
    return int(round(x[0] / x[2])), int(round(x[1] / x[2]))


def deepest_press(button, seed=0):
    """The button scene at the deepest point of a press of `button`."""
    env = buttons.PhysicsButtonConsole(seed=seed)
    env.reset()
    states = []
    env.press(button, recorder=lambda p: states.append((p.button_depths()[button],
                                                         p.data.qpos.copy())))
    physics = env.physics
    physics.data.qpos[:] = max(states, key=lambda s: s[0])[1]
    physics.forward()
    return physics


@pytest.mark.parametrize("button", range(buttons.N_BUTTONS))
def test_the_close_up_sees_the_fingertip_on_the_button_it_presses(button):
    physics = deepest_press(button)
    seen = figures_icub.visible_geoms(physics, "close_up", HEIGHT, WIDTH)
    assert seen.get("r_finger", 0) >= SEEN, seen
    assert seen.get(f"button{button}_cap", 0) >= SEEN, seen
    # the point of contact itself: where the fingertip projects, the camera sees the
    # finger or the cap it touches, not the palm, the arm or another button
    column, row = fingertip_pixel(physics, "close_up")
    segmentation = physics.render(HEIGHT, WIDTH, camera_id="close_up", segmentation=True)
    around = segmentation[row - 1:row + 2, column - 1:column + 2, 0].ravel()
    names = {physics.model.id2name(int(g), "geom") for g in around if g >= 0}
    assert names & {"r_finger", f"button{button}_cap"}, names
    assert names <= {"r_finger", f"button{button}_cap", "console"}, names


def test_the_close_up_sees_the_hand_and_both_rods_through_a_topple():
    env = rods.PhysicsRodTable(start_cell=(2, 0))
    env.reset()
    states = []
    env.move(0, recorder=lambda p: states.append((p.rod_tilt("red"), p.data.qpos.copy())))
    tilts = np.array([tilt for tilt, _ in states])
    assert tilts[-1] > np.deg2rad(60)  # the move does topple the red rod
    physics = env.physics
    hit = int(np.argmax(tilts > np.deg2rad(5)))  # the hand has just hit the rod
    for moment in (0, hit, int(np.argmax(tilts > np.deg2rad(35))), len(states) - 1):
        physics.data.qpos[:] = states[moment][1]
        physics.forward()
        seen = figures_icub.visible_geoms(physics, "close_up", HEIGHT, WIDTH)
        for geom in ("r_finger", "r_palm", "red_rod", "blue_rod"):
            assert seen.get(geom, 0) >= SEEN, (moment, geom, seen)


@pytest.mark.parametrize("panel", ["a", "b"])
def test_figure1_frames_the_whole_robot_head_included(panel):
    if panel == "a":
        physics, button = figures_icub.press_moment(seed=0)
        shown = ("r_finger", f"button{button}_cap", "green_lid")
    else:
        physics = figures_icub.topple_moment()
        shown = ("r_finger", "red_rod", "blue_rod")
    height, width = 480, 640  # figure1's size
    segmentation = physics.render(height, width, camera_id="front", segmentation=True)
    robot = np.isin(segmentation[..., 0], robot_geoms(physics)) & (segmentation[..., 1] == 5)
    rows, columns = np.flatnonzero(robot.any(axis=1)), np.flatnonzero(robot.any(axis=0))
    margins = {"top": rows[0], "bottom": height - 1 - rows[-1], "left": columns[0],
               "right": width - 1 - columns[-1]}
    assert min(margins.values()) >= 8, margins  # not cut, and not touching the frame
    seen = figures_icub.visible_geoms(physics, "front", height, width)
    assert seen.get("head", 0) > 2000 and seen.get("face", 0) > 500, seen
    for geom in shown:
        assert seen.get(geom, 0) >= SEEN, (geom, seen)


def test_the_elbow_has_no_z_fighting():
    """Two coincident surfaces of different geoms draw as a stipple of both, broken into
    many fragments; a clean elbow is a few solid regions, from any side."""
    env = buttons.PhysicsButtonConsole(seed=0)
    env.reset()
    physics = env.physics
    physics.forward()
    elbow = physics.named.data.xpos["r_forearm"]
    model = physics.model
    arm_bodies = [model.name2id(b, "body") for b in ("r_upper_arm", "r_forearm")]
    arm = [g for g in range(model.ngeom) if model.geom_bodyid[g] in arm_bodies]
    for azimuth, elevation in [(200, -20), (250, -10), (120, -30), (300, 10)]:
        camera = MovableCamera(physics, HEIGHT, WIDTH)
        camera.set_pose(elbow, 0.18, azimuth, elevation)
        ids = camera.render(segmentation=True)[..., 0]
        fragments = {model.id2name(g, "geom"): scipy.ndimage.label(ids == g)[1]
                     for g in arm}
        assert max(fragments.values()) <= 3, (azimuth, elevation, fragments)


def test_no_two_drawn_round_surfaces_coincide():
    """The cause of a stipple, read from the model: a sphere or capsule end drawn at the
    centre and radius of another geom's (they z-fight)."""
    for physics in (buttons.load_physics(), rods.load_physics()):
        physics.forward()
        model, data = physics.model, physics.data
        spheres = []
        for g in range(model.ngeom):
            if model.geom_group[g] >= 3 or model.geom_rgba[g][3] == 0:
                continue
            radius, centre = model.geom_size[g][0], data.geom_xpos[g]
            if model.geom_type[g] == 2:  # sphere
                spheres.append((g, centre, radius))
            elif model.geom_type[g] == 3:  # capsule: its two rounded ends
                axis = data.geom_xmat[g].reshape(3, 3)[:, 2] * model.geom_size[g][1]
                spheres += [(g, centre + axis, radius), (g, centre - axis, radius)]
        clashes = [(model.id2name(a, "geom"), model.id2name(b, "geom"))
                   for i, (a, ca, ra) in enumerate(spheres) for b, cb, rb in spheres[i + 1:]
                   if a != b and np.linalg.norm(ca - cb) < 1e-6 and abs(ra - rb) < 1e-6]
        assert clashes == []


def test_camera_titles_are_readable():
    env = icm.envs.load("buttons", physics=True, seed=0)
    env.reset()
    cameras = [env.physics.model.id2name(i, "camera") for i in range(env.physics.model.ncam)]
    fig = icm.figures.cameras_figure(env.physics, cameras, height=48, width=64)
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == [figures_icub.camera_title(c) for c in cameras]
    assert "Over the shoulder" in titles and "Close-up of the hand" in titles
    assert not any("_" in title for title in titles), titles
    assert figures_icub.camera_title("top_down") == "Top down"


def test_visible_geoms_and_titles_refuse_bad_input():
    physics = buttons.load_physics()
    refused(lambda: figures_icub.visible_geoms(physics, "ceiling"), "camera", "'ceiling'",
            "value")
    refused(lambda: figures_icub.visible_geoms(physics, "side", height=4), "height", "4",
            "value")
    refused(lambda: figures_icub.visible_geoms("physics", "side"), "physics", "'physics'",
            "type")
    refused(lambda: figures_icub.camera_title(3), "camera", "3", "type")
    refused(lambda: figures_icub.topple_moment(action=9), "action", "9", "value")


# --- the continuous task's observation, in words (issue 43) -----------------------------

def test_the_observation_table_shows_units_words_and_no_negative_zero():
    observation = {
        "arm_joints": np.deg2rad([-26.7, 17.6, -4.1, 88.4, 0.5, -11.1, 1.8]),
        "fingertip": np.array([0.33, -0.13, 0.575]),
        "button_depths": np.array([-5.9e-6, 0.0, -0.0, 0.0143, 1e-7]),
        "lights": np.array([0.0, 0.0, 1.0, 2.0, 0.0]),
        "lid_angles": np.array([-0.0006, np.deg2rad(97.4)]),
        "made_up": np.array([-0.00001, 1.23456]),
    }
    table = icm.figures.observation_table(observation)
    rows = {line.split("|")[1].strip(" `"): line.split("|")[3:5]
            for line in table.splitlines()[2:]}
    assert re.search(r"-0\.0*(?![0-9])|-0\.0+\b", table) is None, table  # no -0.0, -0.000
    assert rows["button_depths"][0].strip() == "mm"
    assert rows["button_depths"][1].strip() == "0.0, 0.0, 0.0, 14.3, 0.0"
    assert rows["lights"][1].strip() == "0 (off), 0 (off), 1 (red), 2 (green), 0 (off)"
    assert rows["lights"][0].strip() == "0 off, 1 red, 2 green"
    assert rows["lid_angles"][1].strip() == "0.0, 97.4"
    assert rows["arm_joints"][1].strip() == "-26.7, 17.6, -4.1, 88.4, 0.5, -11.1, 1.8"
    assert rows["made_up"][1].strip() == "0.000, 1.235"  # shown as it is, 3 decimals
    assert figures_icub.shown_values([-0.04, -0.06], 1) == ["0.0", "-0.1"]
    refused(lambda: icm.figures.observation_table([1, 2]), "observation", "[1, 2]", "type")
    refused(lambda: icm.figures.observation_table({}), "observation", "{}", "type")
    refused(lambda: icm.figures.observation_table({**observation, "lights": [0, 3, 0, 0, 0]}),
            "observation['lights']", "3", "value")
    refused(lambda: icm.figures.observation_table({**observation, "lights": [0.5] * 5}),
            "observation['lights']", "0.5", "value")
    refused(lambda: icm.figures.observation_table({"fingertip": [np.nan, 0, 0]}),
            "observation['fingertip']", "nan", "value")


# --- the chapter read by a newcomer (issue 43, second reading) -------------------------

def _fingertip_at(physics, angles):
    """The fingertip's world position with the right arm at `angles` (degrees, by joint
    name; the others 0), from forward kinematics on a copy of the physics' data."""
    import mujoco

    from icm.envs import icub

    arm = icub.Arm(physics)
    data = mujoco.MjData(physics.model.ptr)
    data.qpos[:] = physics.data.qpos
    data.qpos[arm.qpos_index] = [np.deg2rad(angles.get(name, 0.0)) for name in icub.ARM_JOINTS]
    mujoco.mj_kinematics(physics.model.ptr, data)
    return data.site_xpos[arm.site_id].copy()


def test_the_joint_table_says_which_way_each_joint_turns():
    """JOINT_MOTIONS's words, on the model (x forward, y to the robot's left, z up)."""
    from icm.chapters import simulated_icub as chapter

    physics = buttons.load_physics()
    physics.forward()
    shoulder = physics.named.data.xpos["r_upper_arm"]
    hanging = _fingertip_at(physics, {})
    # every angle 0: the arm hangs straight along the torso, which leans forward (so the
    # hand is below the shoulder and a little behind it)
    along = (hanging - shoulder) / np.linalg.norm(hanging - shoulder)
    torso_down = -physics.named.data.xmat["torso"].reshape(3, 3)[:, 2]
    assert np.degrees(np.arccos(np.clip(along @ torso_down, -1, 1))) < 2
    assert hanging[2] < shoulder[2] - 0.25 and hanging[0] < shoulder[0]
    move = lambda angles, base={}: _fingertip_at(physics, {**base, **angles}) - \
        _fingertip_at(physics, base)
    pitch = move({"r_shoulder_pitch": -30})
    assert pitch[0] > 0.05 and move({"r_shoulder_pitch": 30})[0] < 0  # forward, back
    assert move({"r_shoulder_roll": 30})[1] < -0.05  # sideways, away from the body
    assert move({"r_elbow": 30})[0] > 0.03  # bends: the forearm comes forward
    bent = {"r_elbow": 90}
    assert move({"r_shoulder_yaw": 30}, bent)[1] < -0.03  # the forearm swings out
    wrist = move({"r_wrist_pitch": -30}, bent)
    elbow = move({"r_elbow": 100}, bent)
    assert wrist[2] > 0 and elbow[2] > 0  # both bend the same way: up
    assert move({"r_wrist_yaw": 20}, bent)[1] > 0  # towards the robot's left
    table = chapter.joint_table(physics)
    assert all(chapter.JOINT_MOTIONS[name] in table for name in chapter.JOINT_MOTIONS)
    refused(lambda: chapter.joint_table("physics"), "physics", "'physics'", "type")


def test_the_buttons_are_numbered_from_the_robots_left():
    env = icm.envs.load("buttons", physics=True, seed=0)
    env.reset()
    physics = env.physics
    caps = [physics.named.data.geom_xpos[f"button{b}_cap"] for b in range(buttons.N_BUTTONS)]
    assert all(np.diff([cap[1] for cap in caps]) < 0)  # y falls: from the robot's left
    columns = figures_icub.project(physics, "eyes", caps, HEIGHT, WIDTH)[:, 0]
    assert all(np.diff(columns) > 10)  # left to right through its eyes
    # project agrees with the camera matrix the tests use for the fingertip
    tip = figures_icub.project(physics, "close_up", physics.named.data.site_xpos["fingertip"],
                               HEIGHT, WIDTH)[0]
    assert tuple(np.round(tip).astype(int)) == fingertip_pixel(physics, "close_up")
    fig = icm.figures.cameras_figure(physics, ["side", "eyes"], number_buttons=True)
    side, eyes = fig.axes
    assert [t.get_text() for t in eyes.texts] == [str(b) for b in range(buttons.N_BUTTONS)]
    assert len(side.texts) == 0  # seen end on: numbers would overlap, none written
    refused(lambda: icm.figures.cameras_figure(rods.load_physics(), ["eyes"],
                                               number_buttons=True), "number_buttons",
            "RodsPhysics", "value")


def test_figure1b_sees_the_falling_rod_along_its_length_and_the_whole_robot():
    physics = figures_icub.topple_moment()
    from dm_control.mujoco import MovableCamera

    view = figures_icub.ROD_VIEW
    camera = MovableCamera(physics, 480, 640)
    camera.set_pose(np.array(view["lookat"]), view["distance"], view["azimuth"],
                    view["elevation"])
    def red_rod(segmentation):
        """The red rod's pixels and how elongated they are: the ratio of the long to the
        short axis of their spread (about 1 for a square blob)."""
        red = (segmentation[..., 0] == physics.model.name2id("red_rod", "geom")) & \
            (segmentation[..., 1] == 5)
        spread = np.linalg.eigvalsh(np.cov(np.vstack(np.nonzero(red))))
        return red.sum(), np.sqrt(spread[1] / spread[0])

    segmentation = camera.render(segmentation=True)
    ids, kinds = segmentation[..., 0], segmentation[..., 1]
    pixels, elongation = red_rod(segmentation)
    assert pixels >= 4 * SEEN
    # the falling rod's image is long (it is end on from the front, where it looked like
    # a small cube: 1.4 when measured)
    front = red_rod(physics.render(480, 640, camera_id="front", segmentation=True))[1]
    assert elongation >= 2.5 and elongation > 1.5 * front, (elongation, front)
    robot = np.isin(ids, robot_geoms(physics)) & (kinds == 5)
    rows = np.flatnonzero(robot.any(axis=1))
    assert rows[0] >= 8  # the head in frame
    # (a): the open green lid and the shut red box in view, and the whole robot
    physics, _ = figures_icub.press_moment(seed=0)
    view = figures_icub.PRESS_VIEW
    camera = MovableCamera(physics, 480, 640)
    camera.set_pose(np.array(view["lookat"]), view["distance"], view["azimuth"],
                    view["elevation"])
    seen = {physics.model.id2name(int(g), "geom"): n for g, n in zip(*np.unique(
        camera.render(segmentation=True)[..., 0], return_counts=True)) if g >= 0}
    assert seen.get("green_lid", 0) >= 10 * SEEN and seen.get("red_lid", 0) >= 10 * SEEN, seen
    assert physics.lid_angles()[1] > np.deg2rad(80)
    assert seen.get("head", 0) > 2000 and seen.get("face", 0) > 500, seen


def test_a_recorded_press_is_timed_from_its_start_and_lasts_its_phases():
    from icm.chapters import simulated_icub

    press = figures_icub.record_press(seed=0)
    update = buttons.load_physics().model.opt.timestep * 10
    assert np.isclose(press["time"][0], update)  # the first update ends 20 ms in
    assert np.allclose(np.diff(press["time"]), update)
    assert np.isclose(press["time"][-1], sum(simulated_icub.press_phases().values()))


def test_the_eyes_see_the_hand_and_both_rods_through_the_chapters_topple():
    env = rods.PhysicsRodTable(start_cell=(2, 0))
    env.reset()
    states = []
    env.move(rods.ACTIONS.index("forward"),
             recorder=lambda p: states.append((p.rod_tilt("red"), p.data.qpos.copy())))
    tilts = np.array([tilt for tilt, _ in states])
    physics = env.physics
    for moment in (0, int(np.argmax(tilts > np.deg2rad(5))), len(states) - 1):
        physics.data.qpos[:] = states[moment][1]
        physics.forward()
        seen = figures_icub.visible_geoms(physics, "eyes", HEIGHT, WIDTH)
        for geom in ("r_finger", "red_rod", "blue_rod"):
            assert seen.get(geom, 0) >= SEEN, (moment, geom, seen)
    # the chapter's words: the rod rocks past flat, then settles near it
    assert np.rad2deg(tilts.max()) > 90 and abs(np.rad2deg(tilts[-1]) - 90) < 5
