"""The simulated iCub: the model, the physics tasks, and their agreement with the
tabular twins."""

import unittest
import xml.etree.ElementTree as ElementTree

import mujoco
import numpy as np
import pytest
from dm_env import test_utils

import icm
from icm.envs import buttons, icub, rods

from test_bad_input import refused
from test_envs import _noisy_boxes


# --- the model --------------------------------------------------------------------

ICUB_RANGES_DEG = {  # ../shared/icub-facts.md, right arm, in the iCub's joint order
    "r_shoulder_pitch": (-95, 5), "r_shoulder_roll": (0, 160.8),
    "r_shoulder_yaw": (-37, 100), "r_elbow": (5.5, 106), "r_wrist_prosup": (-50, 50),
    "r_wrist_pitch": (-65, 10), "r_wrist_yaw": (-25, 25),
}


@pytest.fixture(scope="module", params=["buttons", "rods"])
def physics(request):
    module = buttons if request.param == "buttons" else rods
    return module.load_physics()


def test_arm_has_the_icub_joints_in_order_with_their_ranges(physics):
    model = physics.model
    hinge_names = [model.id2name(i, "joint") for i in range(model.njnt)
                   if model.jnt_type[i] == mujoco.mjtJoint.mjJNT_HINGE
                   and model.id2name(i, "joint").startswith("r_")]
    assert tuple(hinge_names) == icub.ARM_JOINTS
    for name, (low, high) in ICUB_RANGES_DEG.items():
        assert np.rad2deg(physics.named.model.jnt_range[name]) == pytest.approx([low, high])
        # Each joint has a position actuator whose targets span exactly that range.
        assert physics.named.model.actuator_ctrlrange[name] == pytest.approx(
            physics.named.model.jnt_range[name])
        assert model.actuator_gaintype[model.name2id(name, "actuator")] == 0  # fixed gain


def test_arm_links_have_icub_lengths(physics):
    physics.forward()
    x = physics.named.data.xpos
    assert np.linalg.norm(x["r_forearm"] - x["r_upper_arm"]) == pytest.approx(0.152)
    assert np.linalg.norm(x["r_hand"] - x["r_forearm"]) == pytest.approx(0.137)
    torso = physics.named.data.xpos["torso"]
    assert np.linalg.norm(x["r_upper_arm"] - torso) == pytest.approx(np.hypot(0.11, 0.17))


def test_every_scene_has_two_cameras_and_named_elements(physics):
    cameras = {physics.model.id2name(i, "camera") for i in range(physics.model.ncam)}
    assert {"over_shoulder", "side", "eyes"} <= cameras
    physics.named.data.site_xpos["fingertip"]  # named elements the code uses exist
    physics.named.data.xpos["head"]


def test_shared_look_lives_in_one_included_file():
    for scene in ("buttons.xml", "rods.xml"):
        root = ElementTree.parse(icub.asset_path(scene)).getroot()
        includes = [e.get("file") for e in root.iter("include")]
        assert "common.xml" in includes and "icub.xml" in includes
        assert root.find("asset") is None  # materials and textures only in common.xml


def test_rendering_works_headless():
    env = icm.envs.load("buttons", physics=True, seed=0)
    env.reset()
    pixels = env.physics.render(120, 160, camera_id="over_shoulder")
    assert pixels.shape == (120, 160, 3) and pixels.std() > 10


# --- buttons ------------------------------------------------------------------------

@pytest.fixture(scope="module")
def button_env():
    return buttons.PhysicsButtonConsole(seed=0, presses_per_trial=5)


@pytest.mark.parametrize("green", [0, 1, 3, 4])
def test_each_press_moves_only_its_button_and_opens_the_right_lid(button_env, green):
    env = button_env
    env.reset()
    env.task.lights = buttons.lights_for(env.red_button, green)
    env.physics.set_lights(env.task.lights)
    for button in range(buttons.N_BUTTONS):
        boxes = env.press(button)
        assert env.task.press_log == [button]
        assert env.task.deepest[button] > buttons.PRESS_DEPTH
        others = np.delete(env.task.deepest, button)
        assert others.max() < buttons.PRESS_DEPTH / 4, f"button {button} disturbed others"
        lids = np.rad2deg(env.physics.lid_angles())
        expected = buttons.press_outcome(env.task.lights, button)
        assert boxes.tolist() == expected.tolist()
        for i in range(2):
            if expected[i]:
                assert lids[i] >= 30.0  # observed with the lid open at least 30 degrees
            else:
                assert lids[i] < 5.0


def test_physics_button_observations_equal_the_tabular_twin():
    rng = np.random.RandomState(7)
    actions = rng.randint(buttons.N_BUTTONS, size=280)  # a quarter start new trials
    physics_env = icm.envs.load("buttons", physics=True, seed=3)
    tabular_env = icm.envs.load("buttons", physics=False, seed=3)
    a, b = physics_env.reset(), tabular_env.reset()
    presses = 0
    for action in actions:
        a, b = physics_env.step(action), tabular_env.step(action)
        assert a.step_type == b.step_type and a.discount == b.discount
        for key in ("lights", "boxes"):
            np.testing.assert_array_equal(a.observation[key], b.observation[key])
        presses += not a.first()
    assert presses >= 200


def test_physics_buttons_pay_the_extrinsic_reward_like_the_twin():
    physics_env = icm.envs.load("buttons", physics=True, seed=1, rewarded_box="green")
    tabular_env = icm.envs.load("buttons", physics=False, seed=1, rewarded_box="green")
    physics_env.reset(), tabular_env.reset()
    for action in [0, 1, 2, 3, 4, 0, 1, 2, 3]:
        assert physics_env.step(action).reward == tabular_env.step(action).reward


# --- rods --------------------------------------------------------------------------

def test_stored_topple_map_has_twice_as_many_red_pairs_and_no_nudges():
    stored = rods.load_topple_map()
    counts = rods.topple_counts(stored)
    assert counts["blue"] >= 1 and counts["red"] >= 2 * counts["blue"]
    assert len(stored["topples"]) == 4 * len(stored["standable"])
    assert rods.DEFAULT_START_CELL in stored["standable"]


def test_stored_topple_map_equals_a_fresh_physics_measurement_of_every_pair():
    # Every standable cell and all 48 of its (cell, move) pairs, re-measured in physics.
    stored = rods.load_topple_map()
    fresh = rods.measure_topple_map()
    assert {tuple(c) for c in fresh["standable"]} == stored["standable"]
    assert len(fresh["pairs"]) == len(stored["topples"]) == 4 * len(stored["standable"]) == 48
    for pair in fresh["pairs"]:
        cell, action = tuple(pair["cell"]), pair["action"]
        assert pair["topples"] == stored["topples"][(cell, action)], (cell, action)
        assert tuple(pair["hand"]) == rods.next_cell(cell, action)
        assert pair["disturbance"] < 1e-3  # a rod that stays up is not nudged


@pytest.mark.parametrize("rules", [dict(max_moves=20), dict(max_moves=None, off_grid="end")],
                         ids=["time limit", "no limit, off the grid ends"])
def test_physics_rod_observations_equal_the_tabular_twin(rules):
    rng = np.random.RandomState(11)
    physics_env = icm.envs.load("rods", physics=True, **rules)
    tabular_env = icm.envs.load("rods", physics=False, **rules)
    physics_env.reset(), tabular_env.reset()
    topples = 0
    for action in rng.randint(4, size=300):
        a, b = physics_env.step(action), tabular_env.step(action)
        assert a.step_type == b.step_type and a.discount == b.discount
        for key in ("hand", "rods"):
            np.testing.assert_array_equal(a.observation[key], b.observation[key])
        topples += int(a.last() and a.discount == 0.0)
    assert topples >= 3  # the sequence exercised the topples, not only wandering


def test_rod_table_rules():
    env = icm.envs.load("rods", max_moves=5)
    step = env.reset()
    assert step.observation["hand"].tolist() == [0, 0]
    step = env.step(1)  # backward, off the grid: the hand stays
    assert step.observation["hand"].tolist() == [0, 0] and step.mid()
    for _ in range(4):
        step = env.step(2)  # left, off the grid
    assert step.last() and step.discount == 1.0  # time limit, not termination
    env = icm.envs.load("rods", start_cell=(2, 0))
    env.reset()
    step = env.step(0)  # forward into the red rod
    assert step.observation["rods"].tolist() == [1, 0]
    assert step.last() and step.discount == 0.0


def test_rod_table_rules_other_readings():
    # No time limit: a thousand moves off the grid, and the episode goes on.
    env = icm.envs.load("rods", max_moves=None)
    env.reset()
    for _ in range(1000):
        step = env.step(1)  # backward, off the grid
    assert step.mid() and step.observation["hand"].tolist() == [0, 0]
    # A move off the grid ends the episode, with no rod toppled, as a termination.
    env = icm.envs.load("rods", off_grid="end")
    env.reset()
    step = env.step(3)  # right, on the grid: goes on
    assert step.mid() and step.observation["hand"].tolist() == [1, 0]
    step = env.step(1)  # backward, off the grid
    assert step.last() and step.discount == 0.0
    assert step.observation["hand"].tolist() == [1, 0]
    assert step.observation["rods"].tolist() == [0, 0]
    assert env.step(0).first()  # a new episode, over the start cell
    assert [rods.leaves_grid((0, 0), a) for a in range(4)] == [False, True, True, False]
    assert [rods.leaves_grid((4, 2), a) for a in range(4)] == [True, False, False, True]


@pytest.mark.parametrize("kwargs, message", [
    (dict(start_cell=(2, 1)), "start_cell"),  # the red rod stands there
    (dict(start_cell=(5, 0)), "start_cell"),
    (dict(start_cell="corner"), "start_cell"),
    (dict(max_moves=0), "max_moves"),
    (dict(off_grid="wrap"), "off_grid"),
    (dict(colour="red"), "unknown argument"),
])
def test_bad_rod_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        icm.envs.load("rods", **kwargs)


# --- dm_control-style checks ---------------------------------------------------------

DISCRETE = [("buttons", True), ("rods", True), ("buttons", False), ("rods", False)]


@pytest.mark.parametrize("name, physics_flag", DISCRETE)
def test_observations_match_specs_and_are_finite(name, physics_flag):
    env = icm.envs.load(name, physics=physics_flag, seed=2)
    spec = env.observation_spec()
    rng = np.random.RandomState(0)
    step = env.reset()
    for _ in range(12):
        for key, value in step.observation.items():
            spec[key].validate(value)
            assert value.dtype == spec[key].dtype and np.all(np.isfinite(value))
        step = env.step(rng.randint(env.action_spec().num_values))


@pytest.mark.parametrize("name", ["buttons", "rods"])
def test_same_seed_same_physics_trajectory(name):
    def trajectory(seed):
        env = icm.envs.load(name, physics=True, seed=seed)
        rng = np.random.RandomState(5)
        env.reset()
        states = []
        for _ in range(8):
            step = env.step(rng.randint(env.action_spec().num_values))
            states.append(np.concatenate([env.physics.data.qpos, env.physics.data.qvel,
                                          *step.observation.values()]))
        return np.array(states)
    np.testing.assert_array_equal(trajectory(4), trajectory(4))
    if name == "buttons":  # the seed draws the layouts
        assert not np.array_equal(trajectory(4), trajectory(5))


def _unstable(physics):
    warnings = physics.data.warning
    return (warnings[mujoco.mjtWarning.mjWARN_BADQACC].number
            + warnings[mujoco.mjtWarning.mjWARN_BADQPOS].number
            + warnings[mujoco.mjtWarning.mjWARN_BADQVEL].number)


@pytest.mark.parametrize("name, n_actions", [("buttons", 1000), ("rods", 1000)])
def test_thousands_of_random_actions_stay_stable(name, n_actions):
    rng = np.random.RandomState(0)
    done = 0
    for seed in range(4):
        env = icm.envs.load(name, physics=True, seed=seed)
        env.reset()
        for _ in range(n_actions // 4):
            env.step(rng.randint(env.action_spec().num_values))
            done += 1
        state = np.concatenate([env.physics.data.qpos, env.physics.data.qvel])
        assert np.all(np.isfinite(state))
        assert _unstable(env.physics) == 0
    assert done == n_actions


@pytest.mark.parametrize("name", ["buttons", "rods"])
def test_continuous_tasks_conform_and_are_deterministic(name):
    def run(seed):
        env = icm.envs.load_continuous(name, seed=seed, time_limit=1.0)
        spec, action_spec = env.observation_spec(), env.action_spec()
        rng = np.random.RandomState(1)
        step = env.reset()
        observations = []
        while not step.last():
            for key, value in step.observation.items():
                spec[key].validate(value)
                assert np.all(np.isfinite(value))
            action = rng.uniform(action_spec.minimum, action_spec.maximum)
            step = env.step(action)
            observations.append(np.concatenate(list(step.observation.values())))
        assert _unstable(env.physics) == 0
        # 1 s at 20 ms per action, unless a flailing arm topples a rod first.
        assert len(observations) == 50 or (name == "rods" and step.discount == 0.0)
        return np.array(observations)
    np.testing.assert_array_equal(run(3), run(3))


def test_continuous_buttons_open_a_lid_when_the_arm_presses():
    env = icm.envs.load_continuous("buttons", seed=0, time_limit=4.0)
    env.reset()
    motions = env.task.motions(env.physics)
    green = int(np.flatnonzero(env.task.lights == buttons.GREEN)[0])
    for target, steps in [(motions.above[green], 25), (motions.down[green], 25),
                          (motions.above[green], 25)]:
        for _ in range(steps):
            step = env.step(target)
    assert env.task.press_log == [green]
    assert step.observation["lid_angles"][1] > np.deg2rad(30)
    assert step.observation["lid_angles"][0] < np.deg2rad(5)


# --- dm_env's own conformance tests on the physics environments ----------------------

class PhysicsButtonsDmEnvTest(test_utils.EnvironmentTestMixin, unittest.TestCase):
    def make_object_under_test(self):
        return icm.envs.load("buttons", physics=True, seed=0)

    def make_action_sequence(self):
        for action in np.random.RandomState(0).randint(5, size=12):
            yield np.int64(action)


class PhysicsRodsDmEnvTest(test_utils.EnvironmentTestMixin, unittest.TestCase):
    def make_object_under_test(self):
        return icm.envs.load("rods", physics=True, max_moves=6)

    def make_action_sequence(self):
        for action in np.random.RandomState(0).randint(4, size=20):
            yield np.int64(action)


class TabularRodsDmEnvTest(test_utils.EnvironmentTestMixin, unittest.TestCase):
    def make_object_under_test(self):
        return icm.envs.load("rods", max_moves=6)

    def make_action_sequence(self):
        for action in np.random.RandomState(0).randint(4, size=40):
            yield np.int64(action)


# --- the twins agree, as the book uses them -------------------------------------------

@pytest.mark.parametrize("name", ["buttons", "rods"])
def test_compare_twins_finds_agreement_and_would_find_a_difference(name):
    same = icm.envs.compare_twins(name, n_steps=60, seed=2, action_seed=3)
    assert same["steps"] == 60 and same["mismatches"] == 0
    if name == "buttons":  # a twin with other layouts must be caught
        other = icm.envs.compare_twins(name, n_steps=60, seed=2, action_seed=3, twin_seed=9)
        assert other["mismatches"] > 0


def test_goal_oriented_learner_gives_identical_results_on_the_physics_console():
    tabular = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=8, seed=5)
    physics = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=8, seed=5, physics=True)
    for field in ("interest", "prediction_error", "mastery_trial", "practice"):
        np.testing.assert_array_equal(getattr(tabular, field), getattr(physics, field))


# --- the noisy button and the wobbly rod (chapter "Which curiosity?") -------------------

def _geometry(physics, kind, names):
    model = physics.model
    out = {}
    for name in names:
        i = model.name2id(name, kind)
        if kind == "body":
            out[name] = np.concatenate([model.body_pos[i], model.body_quat[i]])
        else:
            out[name] = np.concatenate([model.geom_pos[i], model.geom_size[i],
                                        [model.geom_type[i], model.geom_contype[i]]])
    return out


@pytest.mark.parametrize("module, flag", [(buttons, "noisy_button"), (rods, "wobbly_rod")])
def test_the_noisy_scenes_leave_every_original_body_and_geom_as_it_was(module, flag):
    plain, noisy = module.load_physics(), module.load_physics(**{flag: True})
    model = plain.model
    for kind, count in (("body", model.nbody), ("geom", model.ngeom)):
        names = [model.id2name(i, kind) for i in range(count) if model.id2name(i, kind)]
        before, after = _geometry(plain, kind, names), _geometry(noisy, kind, names)
        for name in names:
            np.testing.assert_array_equal(before[name], after[name], err_msg=name)
    assert noisy.model.nbody == model.nbody + 1 + (flag == "noisy_button")  # stand, button


def test_the_noisy_button_is_pressed_by_contact_and_opens_what_the_task_draws():
    env = buttons.PhysicsButtonConsole(seed=4, presses_per_trial=12, noisy_button=True)
    twin = buttons.ButtonConsole(seed=4, presses_per_trial=12, noisy_button=True)
    env.reset(), twin.reset()
    seen = set()
    for _ in range(9):
        boxes = env.press(buttons.NOISY_BUTTON)
        assert env.task.press_log == [buttons.NOISY_BUTTON]
        assert env.task.deepest[buttons.NOISY_BUTTON] > buttons.PRESS_DEPTH
        assert env.task.deepest[:buttons.N_BUTTONS].max() < buttons.PRESS_DEPTH / 4
        lids = env.physics.lid_angles() >= buttons.BOX_OPEN_ANGLE
        assert boxes.tolist() == lids.astype(int).tolist()
        expected = twin.step(buttons.NOISY_BUTTON).observation["boxes"]
        assert boxes.tolist() == expected.tolist()
        seen.add(tuple(boxes.tolist()))
    assert seen == {(1, 0), (0, 1), (0, 0)}  # all three outcomes in 9 presses, seed 4


def test_compare_twins_agrees_with_the_noisy_button():
    same = icm.envs.compare_twins("buttons", n_steps=60, seed=2, action_seed=3,
                                  noisy_button=True)
    assert same["steps"] == 60 and same["mismatches"] == 0
    other = icm.envs.compare_twins("buttons", n_steps=60, seed=2, action_seed=3, twin_seed=9,
                                   noisy_button=True)
    assert other["mismatches"] > 0


def _walk_beside_the_wobbly_rod(seed, twin_seed):
    """Steps both twins along column 0 back and forth (past the wobbly rod) and
    sideways; returns (steps that differ, wobbly topples seen)."""
    physics_env = icm.envs.load("rods", physics=True, seed=seed, wobbly_rod=True, max_moves=12)
    tabular_env = icm.envs.load("rods", seed=twin_seed, wobbly_rod=True, max_moves=12)
    physics_env.reset(), tabular_env.reset()
    differ = falls = 0
    for action in [0, 0, 1, 0, 1, 3, 0, 2, 0, 1, 0, 1] * 4:
        a, b = physics_env.step(action), tabular_env.step(action)
        differ += not (a.step_type == b.step_type and a.discount == b.discount and all(
            np.array_equal(a.observation[k], b.observation[k]) for k in a.observation))
        falls += int(a.observation["rods"][2])
    return differ, falls


def test_the_twins_agree_step_for_step_beside_the_wobbly_rod():
    differ, falls = _walk_beside_the_wobbly_rod(seed=6, twin_seed=6)
    assert differ == 0 and falls >= 3
    differ, _ = _walk_beside_the_wobbly_rod(seed=6, twin_seed=7)
    assert differ > 0


def test_stored_wobble_map_equals_a_fresh_physics_measurement():
    measured = rods.measure_wobble_map()
    stored = rods.load_topple_map()["topples"]
    beside = set()
    for pair in measured["pairs"]:
        cell, action = tuple(pair["cell"]), pair["action"]
        assert not pair["touched"], (cell, action)  # the arm never touches the wobbly rod
        assert pair["disturbance"] < 1e-3
        if pair["wobbles"]:
            beside.add((cell, action))
            assert stored[(cell, action)] is None and pair["topples"] in (None, "wobbly")
        else:
            assert pair["topples"] == stored[(cell, action)], (cell, action)
    assert beside == rods.load_wobble_map()


def test_learners_give_identical_results_on_the_noisy_physics():
    tabular = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=5, seed=5, noisy_button=True,
                                                interest_per="region", progress=False)
    physics = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=5, seed=5, noisy_button=True,
                                                interest_per="region", physics=True,
                                                progress=False)
    for field in ("interest", "prediction_error", "mastery_trial", "practice", "button_share"):
        np.testing.assert_array_equal(getattr(tabular, field), getattr(physics, field))
    settings = dict(n_seeds=2, n_episodes=6, max_moves=8, seed=3, wobbly_rod=True,
                    reward="learning_progress", start_cell=(0, 1), progress=False)
    tabular = icm.experiments.run_rod_toppling(**settings)
    physics = icm.experiments.run_rod_toppling(physics=True, **settings)
    assert (tabular.toppled == 2).any()
    for field in ("toppled", "episode_length", "prediction_error", "q_table"):
        np.testing.assert_array_equal(getattr(tabular, field), getattr(physics, field))


def test_rod_learner_gives_identical_results_on_the_physics_without_a_time_limit():
    settings = dict(n_seeds=2, n_episodes=5, max_moves=None, off_grid="end", seed=3,
                    progress=False)
    tabular = icm.experiments.run_rod_toppling(**settings)
    physics = icm.experiments.run_rod_toppling(physics=True, **settings)
    assert tabular.edge_ended_share() > 0
    for field in ("toppled", "episode_length", "edge_moves", "prediction_error", "q_table"):
        np.testing.assert_array_equal(getattr(tabular, field), getattr(physics, field))


# --- the physics thresholds, each tried on both sides ------------------------------------

def _tilt_rod(physics, name, degrees, azimuth=0.0):
    """Puts rod `name` at rest, tilted by hand `degrees` from upright, its top leaning
    towards `azimuth` degrees (0: away from the robot, along +x; 90: along +y), its
    base resting on the table by the corner it leans over.

    Args:
      physics: a `RodsPhysics`, its episode initialised (the rods stand upright).
      name: "red" or "blue".
      degrees: the tilt from upright.
      azimuth: the direction the top leans to, in degrees about the vertical.
    """
    model = physics.model
    joint = model.name2id(f"{name}_rod", "joint")
    qpos, dof = model.jnt_qposadr[joint], model.jnt_dofadr[joint]
    half = model.geom_size[model.name2id(f"{name}_rod", "geom")]
    lean = np.array([np.cos(np.deg2rad(azimuth)), np.sin(np.deg2rad(azimuth)), 0.0])
    quat = np.zeros(4)
    mujoco.mju_axisAngle2Quat(quat, np.cross([0.0, 0.0, 1.0], lean), np.deg2rad(degrees))
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, quat)
    # The corner of the base it leans over stays where it was: the rod pivots on it.
    corner = np.array([np.copysign(half[0], lean[0]), np.copysign(half[1], lean[1]), -half[2]])
    upright = model.qpos0[qpos:qpos + 3]
    physics.data.qpos[qpos:qpos + 3] = upright + corner - rotation.reshape(3, 3) @ corner
    physics.data.qpos[qpos + 3:qpos + 7] = quat
    physics.data.qvel[dof:dof + 6] = 0.0
    physics.forward()


@pytest.fixture(scope="module")
def rod_scene():
    physics = rods.load_physics()
    return physics, rods.RodsTask()


@pytest.mark.parametrize("rod", rods.ROD_NAMES)
@pytest.mark.parametrize("degrees, toppled", [(40, False), (50, True), (70, True)])
def test_a_rod_tilted_by_hand_counts_as_toppled_past_45_degrees(rod_scene, rod, degrees,
                                                                toppled):
    physics, task = rod_scene
    with physics.reset_context():
        task.initialize_episode(physics)
    _tilt_rod(physics, rod, degrees, azimuth=30.0)  # an oblique lean: no axis is special
    assert np.rad2deg(physics.rod_tilt(rod)) == pytest.approx(degrees)
    expected = [int(toppled and name == rod) for name in rods.ROD_NAMES]
    assert physics.rods_toppled().tolist() == expected
    assert task.get_termination(physics) == (0.0 if toppled else None)


def _step_beside_a_tipping_rod(degrees, **velocity):
    """Tilts the red rod by hand (`_tilt_rod`) at the start of an episode, then takes a
    step that does not move the hand (backward from cell (0, 0), off the grid): only
    the physics runs, for as long as the step waits for the rod.

    Args:
      degrees: the red rod's tilt before the step.
      **velocity: optional "up" (m/s) and "spin" (rad/s about the rod's long axis):
        the rod is thrown.

    Returns:
      (the step, the `PhysicsRodTable`, simulated seconds the step took).
    """
    env = rods.PhysicsRodTable(start_cell=(0, 0))
    env.reset()
    physics = env.physics
    _tilt_rod(physics, "red", degrees)
    dof = physics.model.jnt_dofadr[physics.model.name2id("red_rod", "joint")]
    physics.data.qvel[dof + 2] = velocity.get("up", 0.0)
    physics.data.qvel[dof + 5] = velocity.get("spin", 0.0)
    start = physics.data.time
    step = env.step(1)
    return step, env, physics.data.time - start


def test_a_tipping_rod_is_waited_for_until_it_lies_still():
    # Tilted 25 degrees, past its balance (atan(1.2 / 3.5) = 19 degrees), the red rod
    # falls; it is still moving when the 0.3 s of settling are over.
    step, env, elapsed = _step_beside_a_tipping_rod(25.0)
    assert step.observation["rods"].tolist() == [1, 0]
    assert step.last() and step.discount == 0.0
    # The step returns once the rod lies still on the table: after the settling time,
    # well before the longest wait is over.
    assert np.rad2deg(env.physics.rod_tilt("red")) == pytest.approx(90.0, abs=2.0)
    assert np.abs(env.physics.named.data.qvel[["red_rod", "blue_rod"]]).max() < 0.05
    assert 0.3 < elapsed < 0.6


def test_a_tipping_rod_is_waited_for_one_second_at_most():
    # A rod that does not come to rest (thrown up, spinning, tilted 30 degrees): the
    # step settles 0.3 s, then waits 1 s for it, and no longer.
    step, env, elapsed = _step_beside_a_tipping_rod(30.0, up=8.0, spin=5.0)
    assert elapsed == pytest.approx(0.3 + 1.0, abs=1e-9)
    assert np.abs(env.physics.named.data.qvel["red_rod"]).max() > 1.0  # still flying
    assert step.mid() and step.observation["rods"].tolist() == [0, 0]  # at 30 degrees


def test_a_light_touch_of_a_few_millimetres_is_not_a_press():
    # The red button pushed by a movement that ends with the fingertip on its cap's top
    # (it goes in 3 to 5 mm) or 1.4 cm below it (about 1 cm: a press, past 8 mm).
    env = buttons.PhysicsButtonConsole(seed=0, presses_per_trial=1)
    physics, motions, red = env.physics, env.motions, env.red_button
    arm = icub.Arm(physics)
    cap = physics.named.data.geom_xpos[f"button{red}_cap"].copy()
    top = cap[2] + physics.named.model.geom_size[f"button{red}_cap"][1]
    for below, pressed in ((0.0, False), (0.002, False), (0.014, True)):
        down = arm.solve([cap[0], cap[1], top - below], start=motions.above[red])
        motion = [(motions.above[red], 0.45), (down, 0.3), (down, 0.15),
                  (motions.above[red], 0.25), (motions.home, 0.45)]
        env.press_motions = buttons.physics.check_press_motions([motion] * buttons.N_BUTTONS)
        env.reset()
        boxes = env.press(red)
        depth = env.task.deepest[red]
        if pressed:
            assert 0.009 < depth < 0.012, below
            assert env.task.press_log == [red] and boxes.tolist() == [1, 0]
        else:
            assert 0.002 < depth < 0.005, below  # touched, and pushed in a little
            assert env.task.press_log == [] and boxes.tolist() == [0, 0]
            assert np.all(env.physics.lid_angles() < np.deg2rad(3))


@pytest.mark.parametrize("depth_mm, pressed", [(3, False), (6, False), (9, True), (12, True)])
def test_a_button_pushed_in_by_hand_is_pressed_past_8_mm(depth_mm, pressed):
    physics = buttons.load_physics()
    task = buttons.ButtonsTask(random=0)
    with physics.reset_context():
        task.initialize_episode(physics)
    red = task.red_button
    physics.named.data.qpos[f"button{red}"] = -depth_mm / 1000
    task.update(physics)
    assert task.press_log == ([red] if pressed else [])
    assert physics.data.ctrl[physics.model.name2id("red_lid", "actuator")] == \
        (pytest.approx(buttons.LID_OPEN_ANGLE) if pressed else 0.0)


def test_each_press_of_the_physics_noisy_button_opens_what_its_own_draw_says():
    # As on the tabular console (test_envs): one draw per trial, then one per press.
    seed, presses = 3, 3
    draws = np.random.default_rng(seed).random(2 * (1 + presses)).reshape(2, 1 + presses)
    expected = [_noisy_boxes(u) for trial in draws for u in trial[1:]]
    assert len(set(expected)) == 3
    env = buttons.PhysicsButtonConsole(seed=seed, presses_per_trial=presses, noisy_button=True)
    env.reset()
    seen = []
    while len(seen) < len(expected):
        step = env.step(buttons.NOISY_BUTTON)
        if not step.first():
            seen.append(tuple(step.observation["boxes"].tolist()))
    assert seen == expected


# --- what the chapter "The simulated iCub" states -------------------------------------

def test_body_dimensions_are_read_from_the_model():
    physics = buttons.load_physics()
    found = icub.body_dimensions(physics)
    assert found["torso_lean"] == pytest.approx(25.0)  # euler="0 25 0" in assets/icub.xml
    assert found["upper_arm"] == pytest.approx(0.152) and found["forearm"] == pytest.approx(0.137)
    assert found["arm_joints"] == 7
    # Measured another way: the elbow's and the wrist's joints, in the world.
    data = physics.data
    shoulder, elbow, wrist = (data.xanchor[physics.model.joint(n).id]
                              for n in ("r_shoulder_pitch", "r_elbow", "r_wrist_pitch"))
    assert np.linalg.norm(elbow - shoulder) == pytest.approx(found["upper_arm"], abs=0.02)
    assert np.linalg.norm(wrist - elbow) == pytest.approx(found["forearm"], abs=1e-6)


def test_the_twins_claims_hold_on_other_seeds_and_fail_when_they_should():
    from icm.chapters import simulated_icub as chapter

    button_check = icm.envs.compare_twins("buttons", n_steps=20, seed=4, action_seed=5)
    rod_check = icm.envs.compare_twins("rods", n_steps=40, seed=4, action_seed=5)
    topple_map = rods.load_topple_map()
    run = dict(n_seeds=2, n_trials=4, seed=4, progress=False)
    physics_run = icm.experiments.run_goal_oriented(physics=True, **run)
    tabular_run = icm.experiments.run_goal_oriented(**run)
    found = chapter.claims(button_check, rod_check, topple_map, physics_run, tabular_run)
    assert set(found) == set(chapter.CLAIMS) and all(found.values()), found
    other = icm.experiments.run_goal_oriented(**{**run, "seed": 5})
    wrong = chapter.claims({**button_check, "mismatches": 1}, rod_check,
                           {**topple_map, "topples": {**topple_map["topples"],
                                                      chapter.FOREARM_PAIR: None}},
                           physics_run, other)
    assert [name for name, held in wrong.items() if not held] == [
        "buttons_agree", "learner_same", "forearm_topples_red"]
    refused(lambda: chapter.claims([], rod_check, topple_map, physics_run, tabular_run),
            "button_check", "[]", "type")


def test_each_physics_has_a_model_of_its_own_and_a_changed_scene_is_compiled_again(tmp_path):
    # The scene is compiled once per process and each physics gets a copy of the model:
    # lighting the caps of one console changes no other console's.
    first, second = buttons.load_physics(), buttons.load_physics()
    assert first.model.ptr is not second.model.ptr
    first.set_lights([1, 2, 0, 0, 0])
    second.set_lights([0, 0, 0, 0, 0])
    assert first.named.model.geom_matid["button0_cap"] != \
        second.named.model.geom_matid["button0_cap"]
    third = buttons.load_physics()  # the compiled model itself was left unlit
    compiled = mujoco.MjModel.from_xml_path(str(icub.asset_path("buttons.xml")))
    assert third.named.model.geom_matid["button0_cap"] == compiled.geom("button0_cap").matid
    # A scene file that changes is compiled afresh.
    scene = tmp_path / "scene.xml"
    scene.write_text('<mujoco><worldbody><geom name="g" type="sphere" size="0.1"/>'
                     '</worldbody></mujoco>')
    assert icub._compiled_scene(str(scene)).ngeom == 1
    scene.write_text('<mujoco><worldbody><geom name="g" type="sphere" size="0.1"/>'
                     '<geom name="h" type="sphere" size="0.2"/></worldbody></mujoco>')
    assert icub._compiled_scene(str(scene)).ngeom == 2


# --- what the chapter "The simulated iCub" explains (issue 43) -------------------------

def test_a_button_at_rest_reads_a_depth_of_zero_not_minus_zero():
    # A depth is minus the button joint's position; negating a resting 0.0 gave -0.0,
    # which an observation printed as "-0.".
    env = buttons.PhysicsButtonConsole(seed=0)
    env.reset()
    depths = env.physics.button_depths()
    assert np.all(depths == 0.0) and not np.signbit(depths).any(), depths
    assert not np.signbit(env.physics.button_depth(0))
    step = icm.envs.load_continuous("buttons", seed=0).reset()
    assert not np.signbit(step.observation["button_depths"]).any()


@pytest.mark.parametrize("n_steps, whole", [(24, True), (22, False)])
def test_compare_twins_counts_the_steps_that_begin_a_trial(n_steps, whole):
    from icm.chapters import simulated_icub as chapter

    check = icm.envs.compare_twins("buttons", n_steps=n_steps, seed=3, action_seed=4)
    per_trial = buttons.DEFAULT_PRESSES_PER_TRIAL + 1  # the presses, and a step to begin
    assert check["ended"] == n_steps // per_trial
    assert check["episodes"] == check["ended"] + 1
    assert check["acted"] == n_steps - (check["episodes"] - 1)  # less those that began one
    trials = chapter.trial_steps(check)
    assert trials["presses"] == check["acted"] and trials["begun"] == check["episodes"]
    held = chapter.claims(check, {**check, "mismatches": 0}, rods.load_topple_map(),
                          *_two_tiny_runs())["button_steps_make_trials"]
    assert held == whole  # 22 steps end in the middle of a trial: the sentence is false
    refused(lambda: chapter.trial_steps({"steps": 3}), "button_check", "steps", "type")
    refused(lambda: chapter.trial_steps(check, presses_per_trial=0), "presses_per_trial",
            "0", "value")


def test_rod_episodes_end_by_a_topple_or_at_the_move_limit():
    from icm.chapters import simulated_icub as chapter

    check = icm.envs.compare_twins("rods", n_steps=60, seed=0, action_seed=2, max_moves=5)
    ends = chapter.rod_episode_ends(check)
    assert ends["topples"] == check["terminations"] > 0 and ends["limits"] > 0
    assert ends["moves"] + ends["begun"] - 1 == check["steps"]
    assert ends["ended"] in (ends["begun"] - 1, ends["begun"])


_TINY_RUNS = []


def _two_tiny_runs():
    """The same small goal-oriented run on the physics and on the twin (made once)."""
    if not _TINY_RUNS:
        run = dict(n_seeds=2, n_trials=4, seed=4, progress=False)
        _TINY_RUNS.extend([icm.experiments.run_goal_oriented(physics=True, **run),
                           icm.experiments.run_goal_oriented(**run)])
    return _TINY_RUNS


def test_interest_stays_under_the_largest_prediction_error():
    import dataclasses

    from icm.chapters import simulated_icub as chapter

    assert chapter.interest_ceiling() == pytest.approx(np.sqrt(2.0))
    runs = _two_tiny_runs()
    check = icm.envs.compare_twins("buttons", n_steps=8, seed=4, action_seed=5)
    topple_map = rods.load_topple_map()
    assert chapter.claims(check, check, topple_map, *runs)["interest_under_ceiling"]
    for run in runs:
        assert 0.0 < chapter.interest_band_top(run) <= run.interest.max() + 1e-12
    # An interest past the ceiling (one seed at 1.5) breaks the claim.
    raised = runs[1].interest.copy()
    raised[0, 1, 0] = 1.5
    over = dataclasses.replace(runs[1], interest=raised)
    assert not chapter.claims(check, check, topple_map, runs[0], over)[
        "interest_under_ceiling"]
    refused(lambda: chapter.interest_band_top("run"), "result", "run", "type")
    # The mean curves' top: one seed at 1.5 on red's second trial lifts red's mean there
    # by (1.5 - its value before) / seeds.
    means = runs[1].interest.mean(axis=0)
    assert chapter.interest_mean_top(runs[1]) == pytest.approx(float(means.max()))
    assert chapter.interest_mean_top(over) == pytest.approx(
        max(float(means.max()), means[1, 0] + (1.5 - runs[1].interest[0, 1, 0])
            / runs[1].n_seeds))
    refused(lambda: chapter.interest_mean_top("run"), "result", "run", "type")


def test_gravity_compensation_holds_the_arm_where_inverse_kinematics_aims_it():
    from icm.chapters import simulated_icub as chapter

    held = chapter.hold_above_red(seed=0, seconds=1.0)
    assert np.linalg.norm(held["fingertip"] - held["aimed"]) < 1e-4  # 0.1 mm
    assert np.array_equal(held["fingertip"], held["observation"]["fingertip"])
    sagging = chapter.hold_above_red(seed=0, seconds=1.0, gravity_compensation=False)
    assert held["fingertip"][2] - sagging["fingertip"][2] > 1e-3  # hangs lower, > 1 mm
    assert np.array_equal(held["targets"], sagging["targets"])
    refused(lambda: chapter.hold_above_red(gravity_compensation="no"),
            "gravity_compensation", "no", "type")
    refused(lambda: chapter.hold_above_red(seconds=0), "seconds", "0", "value")


def test_a_press_lasts_its_phases_and_the_claims_fail_when_it_does_not():
    from icm.chapters import simulated_icub as chapter

    phases = chapter.press_phases()
    assert list(phases) == list(chapter.PRESS_PHASES)
    console = buttons.PhysicsButtonConsole
    update = 0.02
    # each phase as run: the duration asked, to the nearest whole update
    for seconds, asked in zip(phases.values(), (console.REACH_TIME, console.PUSH_TIME,
                                                console.HOLD_TIME, console.LIFT_TIME,
                                                console.RETURN_TIME)):
        assert abs(seconds - asked) <= update / 2 + 1e-12
        assert seconds / update == pytest.approx(round(seconds / update))
    press = icm.figures.record_press(seed=3, button=1)  # an unlit button: no lid opens
    claims = chapter.press_claims(press)
    assert claims["press_is_its_phases"] and not claims["lid_opens_during_press"]
    lit = icm.figures.record_press(seed=3)
    assert chapter.press_claims(lit) == {name: True for name in chapter.PRESS_CLAIMS}
    late = dict(lit, time=lit["time"] + update)  # a press one update longer
    assert not chapter.press_claims(late)["press_is_its_phases"]
    refused(lambda: chapter.press_claims({"time": []}), "press", "time", "type")


def test_a_mean_over_few_seeds_peaks_higher_and_the_claims_fail_when_it_should():
    from icm.chapters import simulated_icub as chapter

    wide = icm.experiments.run_goal_oriented(n_seeds=40, n_trials=20, seed=7)
    few = icm.experiments.run_goal_oriented(n_seeds=4, n_trials=10, seed=7)
    assert chapter.peak_claims(wide, few) == {"icub_seeds_are_the_first": True}
    other = icm.experiments.run_goal_oriented(n_seeds=4, n_trials=10, seed=8)
    assert not chapter.peak_claims(wide, other)["icub_seeds_are_the_first"]
    peaks = chapter.interest_peaks(wide)
    red = wide.interest[:, :, 0]
    # the mean's peak is at most the mean of the seeds' own peaks
    assert peaks["mean_peak"] <= peaks["seed_peak"] + 1e-12
    assert peaks["mean_peak"] == pytest.approx(red.mean(axis=0).max())
    assert 1 <= peaks["first_peak_trial"] <= peaks["last_peak_trial"] <= wide.n_trials
    low, high = peaks["quartile_trials"]
    assert peaks["first_peak_trial"] <= low <= high <= peaks["last_peak_trial"]
    assert peaks["started"] == int((wide.interest[:, 0, :] > 0).any(axis=1).sum())
    refused(lambda: chapter.interest_peaks("run"), "result", "run", "type")
    refused(lambda: chapter.peak_claims(wide, "run"), "few_run", "run", "type")
