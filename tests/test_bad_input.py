"""Bad input is refused by icm itself, with a message that names the argument, shows the
value and says what is allowed: a ValueError for a wrong value, an ArgumentTypeError (a
TypeError that is also a ValueError) for a wrong type. Grouped by module.

Every case checks where the error was raised: inside the icm package, not deep in
numpy, dm_control or argparse.
"""

import collections
import pathlib
import re

import numpy as np
import pytest

import icm
from icm import _validate, stats
from icm.envs import buttons, icub, rods
from icm.experiments import rod_toppling
from icm.learners import (ActorCritic, GoalOrientedAgent, LearningProgressInterest,
                          LinearPredictor, NearestNeighbourPredictor, QLearner,
                          least_squares_slope, softmax)

ICM_DIR = pathlib.Path(icm.__file__).resolve().parent
NAN, INF = float("nan"), float("inf")


def refused(call, name, shown, kind):
    """Runs `call` and checks it is refused as described: `kind` "type" (an
    ArgumentTypeError) or "value" (a ValueError that is not a TypeError), a message
    holding the argument `name` and the value as `shown`, raised inside icm."""
    with pytest.raises(ValueError) as info:
        call()
    error, message = info.value, str(info.value)
    if kind == "type":
        assert isinstance(error, _validate.ArgumentTypeError), f"not a type error: {message}"
        assert isinstance(error, TypeError)
    else:
        assert not isinstance(error, TypeError), f"a type error for a bad value: {message}"
    # The name as a word of its own ("level", not "XXlevelXX" nor "sublevel").
    assert re.search(rf"(?<!\w){re.escape(name)}(?!\w)", message), \
        f"the message does not name {name!r}: {message}"
    assert shown in message, f"the message does not show {shown!r}: {message}"
    where = pathlib.Path(info.traceback[-1].path).resolve()
    assert ICM_DIR in where.parents, f"raised outside icm, in {where}: {message}"


def obs(lights=(0, 0, 1, 2, 0), boxes=(0, 0)):
    return collections.OrderedDict(lights=np.array(lights), boxes=np.array(boxes))


# --- icm._validate: the rules every module uses -----------------------------------------

def test_numpy_scalars_and_0d_arrays_are_accepted_as_numbers():
    assert _validate.integer("n", np.int32(3), 1) == 3
    assert _validate.integer("n", np.array(4), 1) == 4
    assert _validate.real("x", np.float32(0.5), 0, 1) == 0.5
    assert _validate.real("x", np.array(0.25), 0, 1) == 0.25
    assert _validate.learning_rate("lr", np.float64(1.0)) == 1.0


@pytest.mark.parametrize("value, kind", [(True, "type"), (np.bool_(False), "type"),
                                         (2.0, "type"), ("3", "type"), (None, "type"),
                                         (np.array([1, 2]), "type"), (-1, "value")])
def test_integers_refuse_bools_floats_strings_and_out_of_range(value, kind):
    refused(lambda: _validate.integer("n_things", value, 0, 9), "n_things",
            _validate.show(value), kind)


@pytest.mark.parametrize("value, kind", [(NAN, "value"), (INF, "value"), ("0.1", "type"),
                                         (True, "type"), (1.5, "value")])
def test_reals_refuse_nan_infinity_strings_bools_and_out_of_range(value, kind):
    refused(lambda: _validate.real("rate", value, 0, 1), "rate", repr(value), kind)


@pytest.mark.parametrize("seed, kind", [(-1, "value"), (2**63, "value"), (1.5, "type"),
                                        ("7", "type"), (np.random.RandomState(0), "type")])
def test_one_seed_rule_everywhere(seed, kind):
    shown = _validate.show(seed)
    refused(lambda: _validate.generator("seed", seed), "seed", shown, kind)
    refused(lambda: _validate.root_seed("seed", seed), "seed", shown, kind)
    refused(lambda: icm.envs.load("buttons", seed=seed), "seed", shown, kind)
    refused(lambda: GoalOrientedAgent(5, seed=seed), "seed", shown, kind)
    refused(lambda: icm.experiments.run_goal_oriented(n_seeds=1, n_trials=1, seed=seed,
                                                      progress=False), "seed", shown, kind)


def test_a_generator_or_none_is_a_seed_and_the_run_records_the_integer_it_used():
    rng = np.random.default_rng(3)
    a = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=3, seed=rng, progress=False)
    again = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=3, seed=a.settings["seed"],
                                              progress=False)
    np.testing.assert_array_equal(a.interest, again.interest)
    fresh = icm.experiments.run_goal_oriented(n_seeds=1, n_trials=2, seed=None, progress=False)
    assert isinstance(fresh.settings["seed"], int)
    env = icm.envs.load("buttons", seed=np.random.default_rng(0))
    assert env.reset().first()


def test_one_of_tells_a_wrong_type_from_a_wrong_value():
    refused(lambda: _validate.one_of("reading", "sideways", ("progress", "literal")),
            "reading", "'sideways'", "value")
    refused(lambda: _validate.one_of("reading", 3, ("progress", "literal")), "reading", "3",
            "type")
    refused(lambda: _validate.one_of("reading", ["progress"], ("progress", "literal")),
            "reading", "['progress']", "type")


def test_runs_too_large_for_memory_say_how_much_they_need():
    for call in (lambda: icm.experiments.run_goal_oriented(n_seeds=10**9, progress=False),
                 lambda: icm.experiments.run_actor_critic(n_seeds=10**9, progress=False),
                 lambda: icm.experiments.run_rod_toppling(n_seeds=10**9, progress=False)):
        with pytest.raises(ValueError, match=r"would need about [\d.]+ (TB|PB|GB) of memory"):
            call()


# --- icm.envs ----------------------------------------------------------------------------

@pytest.fixture(scope="module")
def tabular_buttons():
    env = icm.envs.load("buttons", seed=0)
    env.reset()
    return env


@pytest.fixture(scope="module")
def physics_buttons():
    env = icm.envs.load("buttons", physics=True, seed=0)
    env.reset()
    return env


@pytest.fixture(scope="module")
def physics_rods():
    env = icm.envs.load("rods", physics=True)
    env.reset()
    return env


@pytest.mark.parametrize("action, shown, kind", [
    (-1, "-1", "value"), (5, "5", "value"), (2.0, "2.0", "type"), (2.7, "2.7", "type"),
    (True, "True", "type"), ("1", "'1'", "type"), (None, "None", "type"),
    (np.array([1, 2]), "array([1, 2]", "type"), (np.float64(1.0), "1.0", "type")])
def test_button_actions(tabular_buttons, action, shown, kind):
    refused(lambda: tabular_buttons.step(action), "action", shown, kind)


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda: icm.envs.load(3), "name", "3", "type"),
    (lambda: icm.envs.load("levers"), "levers", "'levers'", "value"),
    (lambda: icm.envs.load("buttons", physics=1), "physics", "1", "type"),
    (lambda: icm.envs.load("buttons", red_button=-1), "red_button", "-1", "value"),
    (lambda: icm.envs.load("buttons", red_button=2.0), "red_button", "2.0", "type"),
    (lambda: icm.envs.load("buttons", presses_per_trial=0), "presses_per_trial", "0", "value"),
    (lambda: icm.envs.load("buttons", rewarded_box="blue"), "rewarded_box", "'blue'", "value"),
    (lambda: icm.envs.load("buttons", rewarded_box=1), "rewarded_box", "1", "type"),
    (lambda: icm.envs.load("buttons", colour="red"), "colour", "colour", "value"),
    (lambda: buttons.press_outcome([0, 0, 1, 2, 0], 7), "button", "7", "value"),
    (lambda: buttons.press_outcome([0, 0, 1, 2, 0], -1), "button", "-1", "value"),
    (lambda: buttons.press_outcome([0, 0, 1, 3, 0], 1), "lights", "3", "value"),
    (lambda: buttons.press_outcome([0, NAN, 1, 2, 0], 1), "lights", "nan", "value"),
    (lambda: buttons.press_outcome([0, 1, 2], 1), "lights", "(3,)", "value"),
    (lambda: buttons.lights_for(2, 2), "green_button", "2", "value"),
    (lambda: buttons.lights_for(2, 9), "green_button", "9", "value"),
    (lambda: buttons.layouts(red_button=5), "red_button", "5", "value"),
    (lambda: buttons.draw_green(np.random.RandomState(0), 2), "random", "RandomState", "type"),
    (lambda: buttons.extrinsic_reward([1, 0], "blue"), "rewarded_box", "'blue'", "value"),
    (lambda: buttons.extrinsic_reward([1, NAN], "red"), "boxes", "nan", "value"),
    (lambda: icm.envs.load("buttons").reseed(-2), "seed", "-2", "value"),
    (lambda: icm.envs.compare_twins("buttons", n_steps=0), "n_steps", "0", "value"),
    (lambda: icm.envs.compare_twins("buttons", seed=None), "seed", "None", "type"),
    (lambda: icm.envs.compare_twins("buttons", action_seed=-1), "action_seed", "-1", "value"),
])
def test_button_environment_arguments(call, name, shown, kind):
    refused(call, name, shown, kind)


@pytest.mark.parametrize("action, shown, kind", [
    (-1, "-1", "value"), (4, "4", "value"), (0.0, "0.0", "type"), (True, "True", "type")])
def test_rod_actions(action, shown, kind):
    env = icm.envs.load("rods")
    env.reset()
    refused(lambda: env.step(action), "action", shown, kind)
    refused(lambda: rods.next_cell((0, 0), action), "action", shown, kind)


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda: icm.envs.load("rods", start_cell=(2, 1)), "start_cell", "(2, 1)", "value"),
    (lambda: icm.envs.load("rods", start_cell=(5, 0)), "start_cell", "(5, 0)", "value"),
    (lambda: icm.envs.load("rods", start_cell=(0.0, 0)), "start_cell", "(0.0, 0)", "type"),
    (lambda: icm.envs.load("rods", start_cell="corner"), "start_cell", "'corner'", "type"),
    (lambda: icm.envs.load("rods", start_cell=(0, 0, 0)), "start_cell", "(0, 0, 0)", "type"),
    (lambda: icm.envs.load("rods", max_moves=0), "max_moves", "0", "value"),
    (lambda: icm.envs.load("rods", max_moves=2.5), "max_moves", "2.5", "type"),
    (lambda: icm.envs.load("rods", off_grid="wrap"), "off_grid", "'wrap'", "value"),
    (lambda: icm.envs.load("rods", physics=True, off_grid=1), "off_grid", "1", "type"),
    (lambda: rods.leaves_grid((0, 3), 0), "cell", "(0, 3)", "value"),
    (lambda: icm.envs.load("rods", seed=-1), "seed", "-1", "value"),
    (lambda: rods.next_cell((9, 0), 0), "cell", "(9, 0)", "value"),
    (lambda: rods.check_start_cell((3, 2), rods.load_topple_map()["standable"]),
     "start_cell", "(3, 2)", "value"),
])
def test_rod_environment_arguments(call, name, shown, kind):
    refused(call, name, shown, kind)


def test_physics_primitives_refuse_bad_buttons_moves_and_recorders(physics_buttons,
                                                                   physics_rods):
    refused(lambda: physics_buttons.press(-1), "button", "-1", "value")
    refused(lambda: physics_buttons.press(5), "button", "5", "value")
    refused(lambda: physics_buttons.press(1, recorder="log"), "recorder", "'log'", "type")
    refused(lambda: physics_buttons.physics.button_depth(5), "button", "5", "value")
    refused(lambda: physics_buttons.physics.set_lid_targets(NAN, 0.0), "red", "nan", "value")
    refused(lambda: physics_buttons.physics.set_lights([0, 0, 1, 2, 9]), "lights", "9",
            "value")
    refused(lambda: physics_rods.move(4), "action", "4", "value")
    refused(lambda: physics_rods.move(-1), "action", "-1", "value")
    refused(lambda: physics_rods.physics.rod_tilt("green"), "name", "'green'", "value")
    refused(lambda: physics_rods.physics.cell_centre((5, 5)), "cell", "(5, 5)", "value")
    refused(lambda: rods.measure_pair(physics_rods, (0, 0), 7), "action", "7", "value")
    refused(lambda: rods.measure_topple_map(cells="all"), "cells", "'all'", "type")


@pytest.mark.parametrize("name", ["buttons", "rods"])
@pytest.mark.parametrize("time_limit, shown, kind", [
    (0, "0", "value"), (-1.0, "-1.0", "value"), (NAN, "nan", "value"), ("10", "'10'", "type")])
def test_continuous_tasks_refuse_bad_time_limits(name, time_limit, shown, kind):
    refused(lambda: icm.envs.load_continuous(name, time_limit=time_limit), "time_limit",
            shown, kind)


@pytest.fixture(scope="module")
def continuous_buttons():
    env = icm.envs.load_continuous("buttons", seed=0, time_limit=5.0)
    env.reset()
    return env


@pytest.mark.parametrize("action, name, shown, kind", [
    (np.zeros(6), "action", "(6,)", "value"),
    (np.zeros((7, 1)), "action", "(7, 1)", "value"),
    (np.full(7, NAN), "action", "nan", "value"),
    (np.full(7, INF), "action", "inf", "value"),
    (np.array([0.0, 0.0, 0.0, 9.0, 0.0, 0.0, 0.0]), "r_elbow", "9.0", "value"),
    (np.array([-3.0, 0.3, 0.0, 1.0, 0.0, 0.0, 0.0]), "r_shoulder_pitch", "-3.0", "value"),
    ("reach", "action", "'reach'", "type"),
    (np.full(7, 0.5 + 0.1j), "action", "0.5+0.1j", "type"),  # complex: was read as 0.5
    ([0.0, 0.3, 0.0, 1.0, 0.0, 0.0, "0.1"], "action", "'0.1'", "type"),  # was read as 0.1
    (np.array(["0.1"] * 7), "action", "'0.1'", "type"),
])
def test_continuous_actions_of_the_wrong_shape_non_finite_or_outside_the_spec(
        continuous_buttons, action, name, shown, kind):
    refused(lambda: continuous_buttons.step(action), name, shown, kind)


def test_continuous_actions_inside_the_spec_are_accepted(continuous_buttons):
    spec = continuous_buttons.action_spec()
    continuous_buttons.step((spec.minimum + spec.maximum) / 2)
    continuous_buttons.step(list(spec.minimum))  # a list, on the bounds


def test_continuous_rods_refuse_a_start_cell_where_a_rod_stands():
    refused(lambda: icm.envs.load_continuous("rods", start_cell=(2, 1)), "start_cell",
            "(2, 1)", "value")


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda arm: arm.solve([0.3, NAN, 0.5]), "target", "nan", "value"),
    (lambda arm: arm.solve([0.3, 0.5]), "target", "(2,)", "value"),
    (lambda arm: arm.solve([0.3, -0.1, 0.6], pointing=[0, 0, 0]), "pointing", "0", "value"),
    (lambda arm: arm.solve([0.3, -0.1, 0.6], iterations=0), "iterations", "0", "value"),
    (lambda arm: arm.move(np.zeros(7), duration=0), "duration", "0", "value"),
    (lambda arm: arm.move(np.zeros(7), duration=NAN), "duration", "nan", "value"),
    (lambda arm: arm.move(np.zeros(5), duration=1.0), "q_target", "(5,)", "value"),
    (lambda arm: arm.move(np.zeros(7), duration=1.0, monitor=3), "monitor", "3", "type"),
    (lambda arm: arm.place([0.0] * 6 + [NAN]), "q", "nan", "value"),
])
def test_arm_motions(physics_buttons, call, name, shown, kind):
    refused(lambda: call(icub.Arm(physics_buttons.physics)), name, shown, kind)


def test_arm_needs_a_physics_and_minimum_jerk_finite_numbers():
    refused(lambda: icub.Arm("buttons.xml"), "physics", "'buttons.xml'", "type")
    refused(lambda: icub.minimum_jerk([0.5, NAN]), "fraction", "nan", "value")


@pytest.mark.parametrize("name, physics", [("buttons", False), ("buttons", True),
                                           ("rods", False)])
@pytest.mark.parametrize("action, shown, kind", [
    (2.7, "2.7", "type"), (-0.5, "-0.5", "type"), (True, "True", "type"),
    (2.0, "2.0", "type"), (-1, "-1", "value"), (9, "9", "value"),
    (np.array([1]), "array([1]", "type")])
def test_gymnasium_adapter_refuses_non_integral_boolean_and_out_of_range_actions(
        name, physics, action, shown, kind):
    env = icm.envs.as_gymnasium(icm.envs.load(name, physics=physics, seed=0))
    env.reset(seed=0)
    refused(lambda: env.step(action), "action", shown, kind)


def test_gymnasium_adapter_arguments():
    refused(lambda: icm.envs.as_gymnasium("buttons"), "env", "'buttons'", "type")
    refused(lambda: icm.envs.as_gymnasium(icm.envs.load("rods"), render_mode="human"),
            "render_mode", "'human'", "value")
    env = icm.envs.as_gymnasium(icm.envs.load("rods"))
    refused(lambda: env.reset(seed=-1), "seed", "-1", "value")
    refused(lambda: env.reset(options={"start": 1}), "options", "'start'", "value")
    env.reset(seed=np.int64(3))  # numpy integers are seeds too


# --- icm.learners ------------------------------------------------------------------------

@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda p: p.update((0, 0, 1, 2, 0), 9.5, (1, 0)), "action", "9.5", "type"),
    (lambda p: p.update((0, 0, 1, 2, 0), "x", (1, 0)), "action", "'x'", "type"),
    (lambda p: p.update((0, 0, 1, 2, 0), -1, (1, 0)), "action", "-1", "value"),
    (lambda p: p.update((0, 0, 1, 2, NAN), 2, (1, 0)), "context", "nan", "value"),
    (lambda p: p.update((0, 0, 1, 2, 0), 2, (1, NAN)), "effect", "nan", "value"),
    (lambda p: p.update((0, 0, 1, 2, 0), 2, (1, INF)), "effect", "inf", "value"),
    (lambda p: p.update("00120", 2, (1, 0)), "context", "'00120'", "type"),
    (lambda p: p.update((0, 0, 1, 2, 0), 2, 1), "effect", "1", "type"),
    (lambda p: p.predict((0, 0, 1, 2, 0), True), "action", "True", "type"),
    (lambda p: p.predict((0, INF, 1, 2, 0), 1), "context", "inf", "value"),
    (lambda p: NearestNeighbourPredictor(action_weight=0), "action_weight", "0", "value"),
    (lambda p: NearestNeighbourPredictor(action_weight="10"), "action_weight", "'10'", "type"),
])
def test_nearest_neighbour_predictor(call, name, shown, kind):
    predictor = NearestNeighbourPredictor()
    predictor.update((0, 0, 1, 2, 0), 2, (1, 0))
    refused(lambda: call(predictor), name, shown, kind)
    assert len(predictor) == 1  # nothing bad was stored


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda p: p.update(3, True, [1, 0]), "action", "True", "type"),
    (lambda p: p.update(3, 4, [1, 0]), "action", "4", "value"),
    (lambda p: p.update(3, 1, [1, NAN]), "observed", "nan", "value"),
    (lambda p: p.update(3, 1, [1, 0, 0]), "observed", "(1, 0, 0)", "value"),
    (lambda p: p.update([3], 1, [1, 0]), "state", "[3]", "type"),
    (lambda p: p.update(NAN, 1, [1, 0]), "state", "nan", "value"),
    (lambda p: p.predict(3, 1.0), "action", "1.0", "type"),
    (lambda p: p.confidence({"cell": 3}), "state", "{'cell': 3}", "type"),
    (lambda p: p.table(3), "states", "3", "type"),
    (lambda p: LinearPredictor(4, 2, lr=NAN), "lr", "nan", "value"),
    (lambda p: LinearPredictor(4, 2, initial_prediction="0"), "initial_prediction", "'0'",
     "type"),
])
def test_linear_predictor(call, name, shown, kind):
    refused(lambda: call(LinearPredictor(4, 2)), name, shown, kind)


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda: least_squares_slope([1.0, NAN, 0.0]), "values", "nan", "value"),
    (lambda: least_squares_slope([1.0, INF]), "values", "inf", "value"),
    (lambda: least_squares_slope([[1.0, 2.0]]), "values", "dimension", "value"),
    (lambda: least_squares_slope([1.0]), "values", "1", "value"),
    (lambda: least_squares_slope("10"), "values", "'10'", "type"),
    (lambda: LearningProgressInterest().record("red", NAN), "error", "nan", "value"),
    (lambda: LearningProgressInterest().record("red", -0.5), "error", "-0.5", "value"),
    (lambda: LearningProgressInterest().record("red", "big"), "error", "'big'", "type"),
    (lambda: LearningProgressInterest().record(["red"], 1.0), "task", "['red']", "type"),
    (lambda: LearningProgressInterest(window=2.0), "window", "2.0", "type"),
    (lambda: LearningProgressInterest(reading=1), "reading", "1", "type"),
])
def test_interest(call, name, shown, kind):
    refused(call, name, shown, kind)


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda a: a.learn(obs(), 9, obs()), "action", "9", "value"),
    (lambda a: a.learn(obs(), "x", obs()), "action", "'x'", "type"),
    (lambda a: a.learn(obs(), 2.0, obs()), "action", "2.0", "type"),
    (lambda a: a.learn(obs(), -1, obs()), "action", "-1", "value"),
    (lambda a: a.learn({"lights": [0, 0, 1, 2, 0]}, 1, {"boxes": [0, 0]}), "observation",
     "'boxes'", "value"),
    (lambda a: a.learn([0, 0, 1, 2, 0], 1, obs()), "observation", "[0, 0, 1, 2, 0]", "type"),
    (lambda a: a.learn(obs(), 1, obs(boxes=(NAN, 0))), "next_observation", "nan", "value"),
    (lambda a: a.select_action(obs(lights=(0, NAN, 1, 2, 0))), "observation", "nan", "value"),
    (lambda a: GoalOrientedAgent(5, context_keys="lights"), "context_keys", "'lights'", "type"),
    (lambda a: GoalOrientedAgent(5, predictor=object()), "predictor", "object", "type"),
    (lambda a: GoalOrientedAgent(5, interest="progress"), "interest", "'progress'", "type"),
    (lambda a: GoalOrientedAgent(5, epsilon=NAN), "epsilon", "nan", "value"),
    (lambda a: GoalOrientedAgent(True), "n_actions", "True", "type"),
])
def test_goal_oriented_agent(call, name, shown, kind):
    agent = GoalOrientedAgent(5, seed=0)
    refused(lambda: call(agent), name, shown, kind)
    assert len(agent.predictor) == 0  # a refused step teaches nothing


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda a: a.learn(obs(), 1, obs(), external_reward=NAN), "external_reward", "nan",
     "value"),
    (lambda a: a.learn(obs(), 1, obs(), external_reward="1"), "external_reward", "'1'",
     "type"),
    (lambda a: a.learn(obs(), 1, obs(), discount=2.0), "discount", "2.0", "value"),
    (lambda a: a.learn(obs(), 5, obs()), "action", "5", "value"),
    (lambda a: a.learn(obs(), True, obs()), "action", "True", "type"),
    (lambda a: a.td_error(INF, (0,), (1,)), "reward", "inf", "value"),
    (lambda a: a.internal_reward((0,) * 7, 1, (1, NAN)), "effect", "nan", "value"),
    (lambda a: a.policy([0, 0, 1]), "state", "[0, 0, 1]", "type"),
    (lambda a: ActorCritic(5, temperature=0), "temperature", "0", "value"),
    (lambda a: ActorCritic(5, variant="sutton"), "variant", "'sutton'", "value"),
    (lambda a: ActorCritic(5, state_keys="lights"), "state_keys", "'lights'", "type"),
    (lambda a: softmax([1.0, NAN], 1.0), "preferences", "nan", "value"),
    (lambda a: softmax([1.0, 2.0], -1.0), "temperature", "-1.0", "value"),
])
def test_actor_critic(call, name, shown, kind):
    agent = ActorCritic(5, seed=0)
    refused(lambda: call(agent), name, shown, kind)
    assert agent.critic == {} and agent.actor == {}  # a refused step changes nothing


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda q: q.update(0, 0, NAN, 1), "reward", "nan", "value"),
    (lambda q: q.update(0, 0, "1", 1), "reward", "'1'", "type"),
    (lambda q: q.update(True, 0, 1.0, 1), "state", "True", "type"),
    (lambda q: q.update(0, -1, 1.0, 1), "action", "-1", "value"),
    (lambda q: q.update(0, 0, 1.0, 1, discount=NAN), "discount", "nan", "value"),
    (lambda q: q.select_action(15), "state", "15", "value"),
    (lambda q: q.select_action(1.0), "state", "1.0", "type"),
    (lambda q: q.learn(0, 9, [1, 0], 1), "action", "9", "value"),
    (lambda q: q.learn(0, 1, [1, NAN], 1), "observed", "nan", "value"),
    (lambda q: QLearner(15, 4, predictor="linear"), "predictor", "'linear'", "type"),
])
def test_q_learner(call, name, shown, kind):
    learner = QLearner(15, 4, LinearPredictor(4, 2), seed=0)
    before = learner.q
    refused(lambda: call(learner), name, shown, kind)
    np.testing.assert_array_equal(learner.q, before)


# --- icm.stats ---------------------------------------------------------------------------

@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda: stats.mean_band([[1.0, NAN], [2.0, 3.0]]), "values", "nan", "value"),
    (lambda: stats.mean_band([[1.0, INF]]), "values", "inf", "value"),
    (lambda: stats.mean_band(np.ones((0, 3))), "values", "(0, 3)", "value"),
    (lambda: stats.mean_band([[1.0]], level=1.0), "level", "1.0", "value"),
    (lambda: stats.mean_band([["a"]]), "values", "'a'", "type"),
    (lambda: stats.first_from_which([1, 0, 1]), "condition", "[1, 0, 1]", "type"),
    (lambda: stats.first_below([1.0, NAN], 0.5), "curve", "nan", "value"),
    (lambda: stats.first_below([1.0, 0.2], 2.0), "fraction", "2.0", "value"),
    (lambda: stats.comes_first(1.5, 2), "first", "1.5", "type"),
])
def test_statistics(call, name, shown, kind):
    refused(call, name, shown, kind)


EVENTS = np.array([3, -1, 5])
"""Event numbers of three seeds (trials from 1; -1: never)."""


# Issue 48: every argument of every public function of icm.stats, each way it can be
# wrong: empty, NaN or infinite where a number is needed, a level or a rate outside
# (0, 1), too few resamples, successes above n, event numbers that are neither >= 1
# nor -1, numbers too large for their sums to stay finite, and the wrong type.
@pytest.mark.parametrize("call, name, shown, kind", [
    # mean_band(values, level)
    (lambda: stats.mean_band(np.ones((3, 0))), "values", "(3, 0)", "value"),
    (lambda: stats.mean_band(7.0), "values", "()", "value"),
    (lambda: stats.mean_band([[1e308], [1e308]]), "values", "1.e+308", "value"),
    (lambda: stats.mean_band([[1.0]], level=NAN), "level", "nan", "value"),
    (lambda: stats.mean_band([[1.0]], level=0.0), "level", "0.0", "value"),
    (lambda: stats.mean_band([[1.0]], level="0.9"), "level", "'0.9'", "type"),
    (lambda: stats.mean_band([[True]]), "values", "True", "type"),
    # first_from_which(condition)
    (lambda: stats.first_from_which(np.array(True)), "condition", "()", "value"),
    (lambda: stats.first_from_which(np.zeros((2, 0), bool)), "condition", "(2, 0)", "value"),
    (lambda: stats.first_from_which("yes"), "condition", "'yes'", "type"),
    # first_below(curve, fraction, after)
    (lambda: stats.first_below([], 0.5), "curve", "none", "value"),
    (lambda: stats.first_below([[1.0, 0.2]], 0.5), "curve", "[[1.0, 0.2]]", "value"),
    (lambda: stats.first_below([1.0, INF], 0.5), "curve", "inf", "value"),
    (lambda: stats.first_below([1.0, 0.2], NAN), "fraction", "nan", "value"),
    (lambda: stats.first_below([1.0, 0.2], -0.1), "fraction", "-0.1", "value"),
    (lambda: stats.first_below([1.0, 0.2], "half"), "fraction", "'half'", "type"),
    (lambda: stats.first_below([1.0, 0.2], 0.5, after=2), "after", "2", "value"),
    (lambda: stats.first_below([1.0, 0.2], 0.5, after=-1), "after", "-1", "value"),
    (lambda: stats.first_below([1.0, 0.2], 0.5, after=1.0), "after", "1.0", "type"),
    (lambda: stats.first_below([1.0, 0.2], 0.5, after=True), "after", "True", "type"),
    # comes_first(first, second): event numbers from 1, -1 for never
    (lambda: stats.comes_first(0, 2), "first", "0", "value"),
    (lambda: stats.comes_first(-2, 2), "first", "-2", "value"),
    (lambda: stats.comes_first(3, 0), "second", "0", "value"),
    (lambda: stats.comes_first(EVENTS, np.array([1, -5, 2])), "second", "-5", "value"),
    (lambda: stats.comes_first(np.array([], int), 2), "first", "none", "value"),
    (lambda: stats.comes_first(np.array([1, 2]), np.array([1, 2, 3])), "first and second",
     "(2,) and (3,)", "value"),
    (lambda: stats.comes_first(True, 2), "first", "True", "type"),
    (lambda: stats.comes_first([True, 2], 2), "first", "[True, 2]", "type"),
    (lambda: stats.comes_first(3, 2.0), "second", "2.0", "type"),
    (lambda: stats.comes_first(3, "4"), "second", "'4'", "type"),
    # paired_gaps(arm, baseline)
    (lambda: stats.paired_gaps(np.array([3, 0, 5]), EVENTS), "arm", "0", "value"),
    (lambda: stats.paired_gaps(EVENTS, np.array([3, -4, 5])), "baseline", "-4", "value"),
    (lambda: stats.paired_gaps(np.array([], int), np.array([], int)), "arm", "none", "value"),
    (lambda: stats.paired_gaps(EVENTS, EVENTS[:2]), "arm and baseline", "3 and 2", "value"),
    (lambda: stats.paired_gaps(EVENTS[None], EVENTS[None]), "arm", "(1, 3)", "value"),
    (lambda: stats.paired_gaps(EVENTS, [3.0, -1.0, 5.0]), "baseline", "3.0", "type"),
    (lambda: stats.paired_gaps(EVENTS, EVENTS > 0), "baseline", "True", "type"),
    # bootstrap_band(values, level, resamples, seed)
    (lambda: stats.bootstrap_band(np.ones((0, 2))), "values", "(0, 2)", "value"),
    (lambda: stats.bootstrap_band(np.ones((4, 0))), "values", "(4, 0)", "value"),
    (lambda: stats.bootstrap_band([1.0, NAN]), "values", "nan", "value"),
    (lambda: stats.bootstrap_band([[1e308], [1e308]]), "values", "1.e+308", "value"),
    (lambda: stats.bootstrap_band(["a"]), "values", "'a'", "type"),
    (lambda: stats.bootstrap_band([1.0], level=1.5), "level", "1.5", "value"),
    (lambda: stats.bootstrap_band([1.0], level=NAN), "level", "nan", "value"),
    (lambda: stats.bootstrap_band([1.0], level=True), "level", "True", "type"),
    (lambda: stats.bootstrap_band([1.0], resamples=0), "resamples", "0", "value"),
    (lambda: stats.bootstrap_band([1.0], resamples=99), "resamples", "99", "value"),
    (lambda: stats.bootstrap_band([1.0], resamples=500.0), "resamples", "500.0", "type"),
    (lambda: stats.bootstrap_band([1.0], seed=-1), "seed", "-1", "value"),
    (lambda: stats.bootstrap_band([1.0], seed=2**63), "seed", str(2**63), "value"),
    (lambda: stats.bootstrap_band([1.0], seed="0"), "seed", "'0'", "type"),
    # every_nth(n, every)
    (lambda: stats.every_nth(0, 2), "n", "0", "value"),
    (lambda: stats.every_nth(5, 0), "every", "0", "value"),
    (lambda: stats.every_nth(5.0, 2), "n", "5.0", "type"),
    (lambda: stats.every_nth(5, None), "every", "None", "type"),
    # paired_p_value(differences, seed, alternative)
    (lambda: stats.paired_p_value([]), "differences", "none", "value"),
    (lambda: stats.paired_p_value([1.0, NAN]), "differences", "nan", "value"),
    (lambda: stats.paired_p_value([1.0, -INF]), "differences", "inf", "value"),
    (lambda: stats.paired_p_value([[1.0, 2.0]]), "differences", "[[1.0, 2.0]]", "value"),
    (lambda: stats.paired_p_value([1e308] * 17), "differences", "1.e+308", "value"),
    (lambda: stats.paired_p_value("1.0"), "differences", "'1.0'", "type"),
    (lambda: stats.paired_p_value([1.0], seed=-1), "seed", "-1", "value"),
    (lambda: stats.paired_p_value([1.0], seed=0.0), "seed", "0.0", "type"),
    (lambda: stats.paired_p_value([1.0], alternative="up"), "alternative", "'up'", "value"),
    (lambda: stats.paired_p_value([1.0], alternative=1), "alternative", "1", "type"),
    # corrected_verdicts(family, rate, seed)
    (lambda: stats.corrected_verdicts({}), "family", "{}", "type"),
    (lambda: stats.corrected_verdicts([0.1]), "family", "[0.1]", "type"),
    (lambda: stats.corrected_verdicts({"a": NAN}), "family['a']", "nan", "value"),
    (lambda: stats.corrected_verdicts({"a": 0.1, "b": 1.5}), "family['b']", "1.5", "value"),
    (lambda: stats.corrected_verdicts({"a": -0.1}), "family['a']", "-0.1", "value"),
    (lambda: stats.corrected_verdicts({"a": []}), "family['a']", "none", "value"),
    (lambda: stats.corrected_verdicts({"a": [1.0, INF]}), "family['a']", "inf", "value"),
    (lambda: stats.corrected_verdicts({"a": [[1.0]]}), "family['a']", "[[1.0]]", "value"),
    (lambda: stats.corrected_verdicts({"a": [1e308, 1e308]}), "family['a']", "1.e+308",
     "value"),
    (lambda: stats.corrected_verdicts({"a": "0.1"}), "family['a']", "'0.1'", "type"),
    (lambda: stats.corrected_verdicts({"a": None}), "family['a']", "None", "type"),
    (lambda: stats.corrected_verdicts({"a": 0.1}, rate=0.0), "rate", "0.0", "value"),
    (lambda: stats.corrected_verdicts({"a": 0.1}, rate=1.0), "rate", "1.0", "value"),
    (lambda: stats.corrected_verdicts({"a": 0.1}, rate=NAN), "rate", "nan", "value"),
    (lambda: stats.corrected_verdicts({"a": 0.1}, rate="5%"), "rate", "'5%'", "type"),
    (lambda: stats.corrected_verdicts({"a": 0.1}, seed=-1), "seed", "-1", "value"),
    (lambda: stats.corrected_verdicts({"a": 0.1}, seed=1.5), "seed", "1.5", "type"),
    # at_bound(values, low, high)
    (lambda: stats.at_bound([]), "values", "none", "value"),
    (lambda: stats.at_bound([0.5, NAN]), "values", "nan", "value"),
    (lambda: stats.at_bound([0.5, 1.5]), "values", "1.5", "value"),
    (lambda: stats.at_bound([0.5, -0.5]), "values", "-0.5", "value"),
    (lambda: stats.at_bound(["a"]), "values", "'a'", "type"),
    (lambda: stats.at_bound([0.5], low=NAN), "low", "nan", "value"),
    (lambda: stats.at_bound([0.5], high=INF), "high", "inf", "value"),
    (lambda: stats.at_bound([0.5], low=1.0), "low must be below high", "1.0", "value"),
    (lambda: stats.at_bound([0.5], low="0"), "low", "'0'", "type"),
    (lambda: stats.at_bound([0.5], high=None), "high", "None", "type"),
    # share_interval(successes, n, level): more in tests/test_robustness.py
    (lambda: stats.share_interval(5, 4), "successes", "5", "value"),
    (lambda: stats.share_interval(np.array([1, 5]), np.array([4, 4])), "successes", "5",
     "value"),
    (lambda: stats.share_interval(1, np.array([4, 0])), "n", "0", "value"),
    (lambda: stats.share_interval(np.array([], int), 4), "successes", "none", "value"),
    (lambda: stats.share_interval(np.array([1, 2]), np.array([4, 4, 4])), "successes and n",
     "(2,) and (3,)", "value"),
    (lambda: stats.share_interval(True, 4), "successes", "True", "type"),
    (lambda: stats.share_interval([True, 3], 4), "successes", "[True, 3]", "type"),
    (lambda: stats.share_interval(1, 4.0), "n", "4.0", "type"),
    (lambda: stats.share_interval(1, 4, level=NAN), "level", "nan", "value"),
    (lambda: stats.share_interval(1, 4, level=0.0), "level", "0.0", "value"),
    (lambda: stats.share_interval(1, 4, level=None), "level", "None", "type"),
    (lambda: stats.share_interval(1, 4, level=1.0), "level", "1.0", "value"),
    (lambda: stats.share_interval(1, 4, level=1.5), "level", "1.5", "value"),
    (lambda: stats.share_interval(-1, 4), "successes", "-1", "value"),
    (lambda: stats.share_interval(1, 0), "n", "0", "value"),
    (lambda: stats.share_interval(0, 0), "n must be an integer (or integers) >= 1", "0",
     "value"),
    (lambda: stats.share_interval(1, np.array([], int)), "n must hold at least one count",
     "none", "value"),
    (lambda: stats.share_interval(1, "4"), "n", "'4'", "type"),
    # verdict(low, high, threshold): more in test_robustness_verdicts_need_shares_...
    (lambda: stats.verdict(0.5, 0.6, NAN), "threshold", "nan", "value"),
    (lambda: stats.verdict(0.5, "0.6", 0.9), "high", "'0.6'", "type"),
    (lambda: stats.verdict(-0.1, 0.6, 0.9), "low", "-0.1", "value"),
    (lambda: stats.verdict(1.5, 1.6, 0.9), "low", "1.5", "value"),
    (lambda: stats.verdict(0.5, 1.5, 0.9), "high", "1.5", "value"),
    (lambda: stats.verdict(0.5, 0.6, 1.5), "threshold", "1.5", "value"),
    (lambda: stats.verdict(0.7, 0.6, 0.5), "low must be at most high", "0.7", "value"),
    # paired_power(differences, n_seeds, alternative, rate, simulations, seed)
    (lambda: stats.paired_power([], 5, "less"), "differences", "none", "value"),
    (lambda: stats.paired_power([1.0, NAN], 5, "less"), "differences", "nan", "value"),
    (lambda: stats.paired_power([1e308], 2, "less"), "differences", "1.e+308", "value"),
    (lambda: stats.paired_power([1.0], 0, "less"), "n_seeds", "0", "value"),
    (lambda: stats.paired_power([1.0], 1.5, "less"), "n_seeds", "1.5", "type"),
    (lambda: stats.paired_power([1.0], 5, "two-sided"), "alternative", "'two-sided'", "value"),
    (lambda: stats.paired_power([1.0], 5, "less", rate=0.0), "rate", "0.0", "value"),
    (lambda: stats.paired_power([1.0], 5, "less", rate=NAN), "rate", "nan", "value"),
    (lambda: stats.paired_power([1.0], 5, "less", simulations=0), "simulations", "0", "value"),
    (lambda: stats.paired_power([1.0], 5, "less", simulations=99), "simulations", "99",
     "value"),
    (lambda: stats.paired_power([1.0], 5, "less", simulations=1e3), "simulations", "1000.0",
     "type"),
    (lambda: stats.paired_power([1.0], 5, "less", seed=-1), "seed", "-1", "value"),
    # seeds_for_power(differences, alternative, power, rate, simulations, seed, most)
    (lambda: stats.seeds_for_power([1.0], "less", power=1.0), "power", "1.0", "value"),
    (lambda: stats.seeds_for_power([1.0], "less", power=NAN), "power", "nan", "value"),
    (lambda: stats.seeds_for_power([1.0], "less", power="0.9"), "power", "'0.9'", "type"),
    (lambda: stats.seeds_for_power([1.0], "less", most=0), "most", "0", "value"),
    (lambda: stats.seeds_for_power([1.0], "less", most=2.0), "most", "2.0", "type"),
    (lambda: stats.seeds_for_power([], "less"), "differences", "none", "value"),
    (lambda: stats.seeds_for_power([1.0], "up"), "alternative", "'up'", "value"),
    (lambda: stats.seeds_for_power([1.0], "less", rate=1.0), "rate", "1.0", "value"),
    (lambda: stats.seeds_for_power([1.0], "less", simulations=0), "simulations", "0",
     "value"),
    (lambda: stats.seeds_for_power([1.0], "less", seed=-1), "seed", "-1", "value"),
])
def test_statistics_refuse_impossible_input(call, name, shown, kind):
    refused(call, name, shown, kind)


# --- icm.experiments ---------------------------------------------------------------------

@pytest.mark.parametrize("run, kwargs, name, shown, kind", [
    ("run_goal_oriented", dict(n_seeds=2.0), "n_seeds", "2.0", "type"),
    ("run_goal_oriented", dict(n_trials=True), "n_trials", "True", "type"),
    ("run_goal_oriented", dict(epsilon=NAN), "epsilon", "nan", "value"),
    ("run_goal_oriented", dict(window=3.5), "window", "3.5", "type"),
    ("run_goal_oriented", dict(physics="no"), "physics", "'no'", "type"),
    ("run_goal_oriented", dict(progress=1), "progress", "1", "type"),
    ("run_actor_critic", dict(temperature=INF), "temperature", "inf", "value"),
    ("run_actor_critic", dict(rewarded_box=None), "rewarded_box", "None", "type"),
    ("run_actor_critic", dict(gamma="0.5"), "gamma", "'0.5'", "type"),
    ("run_rod_toppling", dict(snapshot_episodes=[1.5]), "snapshot_episodes", "1.5", "type"),
    ("run_rod_toppling", dict(snapshot_episodes="10"), "snapshot_episodes", "'10'", "type"),
    ("run_rod_toppling", dict(start_cell=(2, 1)), "start_cell", "(2, 1)", "value"),
    ("run_rod_toppling", dict(first_run=-1), "first_run", "-1", "value"),
    ("run_rod_toppling", dict(initial_q=NAN), "initial_q", "nan", "value"),
    ("run_rod_toppling", dict(max_moves=0), "max_moves", "0", "value"),
    ("run_rod_toppling", dict(max_moves="30"), "max_moves", "'30'", "type"),
    ("run_rod_toppling", dict(max_moves=None, epsilon=0.0), "max_moves=None", "0.0", "value"),
    ("run_rod_toppling", dict(off_grid="wrap"), "off_grid", "'wrap'", "value"),
    ("run_rod_toppling", dict(off_grid=None), "off_grid", "None", "type"),
])
def test_run_arguments(run, kwargs, name, shown, kind):
    function = getattr(icm.experiments, run)
    steps = {"n_episodes": 2} if run == "run_rod_toppling" else {"n_trials": 2}
    refused(lambda: function(**{"n_seeds": 1, **steps, "progress": False, **kwargs}), name,
            shown, kind)


@pytest.fixture(scope="module")
def small_results():
    return {"goal": icm.experiments.run_goal_oriented(n_seeds=2, n_trials=4, progress=False),
            "ac": icm.experiments.run_actor_critic(n_seeds=2, n_trials=4, progress=False),
            "rods": icm.experiments.run_rod_toppling(n_seeds=2, n_episodes=4, progress=False)}


def test_result_methods(small_results):
    goal, rods_result = small_results["goal"], small_results["rods"]
    refused(lambda: goal.peak_trial("blue"), "task", "'blue'", "value")
    refused(lambda: goal.fade_trial("red", fraction=0), "fraction", "0", "value")
    refused(lambda: rods_result.snapshot(2, "first episode"), "seed", "2", "value")
    refused(lambda: rods_result.snapshot(0, "last episode"), "name", "'last episode'", "value")
    refused(lambda: rods_result.first_topple(0), "rod", "0", "type")
    refused(lambda: rods_result.topple_share("red", episodes=3), "episodes", "3", "type")
    refused(lambda: rods_result.rod_errors("some"), "reading", "'some'", "value")
    refused(lambda: rod_toppling.cell_state((1, 7)), "cell", "(1, 7)", "value")


def test_comparison_tables_need_dicts_of_their_results(small_results):
    refused(lambda: icm.chapters.goal_oriented_interest.comparison_table([small_results["goal"]]), "results",
            "GoalOrientedResult", "type")
    refused(lambda: icm.chapters.goal_oriented_interest.comparison_table({"rods": small_results["rods"]}),
            "results['rods']", "RodTopplingResult", "type")
    refused(lambda: icm.chapters.actor_critic.comparison_table({"goal": small_results["goal"]}),
            "results['goal']", "GoalOrientedResult", "type")


def test_sweep_keeps_an_iterator_grid_and_refuses_bad_grids():
    run = icm.experiments.run_goal_oriented
    table = icm.experiments.sweep(run, {"epsilon": iter([0.1, 0.3])}, n_seeds=2,
                                  n_trials=3, progress=False)
    assert len(table) == 4 and sorted(set(table.epsilon)) == [0.1, 0.3]
    refused(lambda: icm.experiments.sweep(run, [("epsilon", [0.1])], progress=False), "grid",
            "[('epsilon', [0.1])]", "type")
    refused(lambda: icm.experiments.sweep(run, {"epsilon": "0.1"}, progress=False),
            "grid['epsilon']", "'0.1'", "type")
    refused(lambda: icm.experiments.sweep(run, {"epsilon": iter([])}, progress=False),
            "grid['epsilon']", "empty", "value")
    refused(lambda: icm.experiments.sweep(run, {"epsilon": [0.1]}, n_jobs=0, progress=False),
            "n_jobs", "0", "value")
    refused(lambda: icm.experiments.sweep(run, {"epsilon": [0.1]}, n_jobs=1.5,
                                          progress=False), "n_jobs", "1.5", "type")
    refused(lambda: icm.experiments.sweep("run_goal_oriented", {"epsilon": [0.1]},
                                          progress=False), "run_fn", "'run_goal_oriented'",
            "type")
    refused(lambda: icm.experiments.sweep(run, {"epsilon": [0.1]}, client=object(),
                                          progress=False), "client", "'joblib'", "value")


# --- icm.figures -------------------------------------------------------------------------

@pytest.mark.parametrize("figure, wrong, name, shown", [
    ("figure5", "rods", "result", "RodTopplingResult"),
    ("mastery_figure", "ac", "result", "ActorCriticResult"),
    ("figure6", "goal", "result", "GoalOrientedResult"),
    ("figure7", "goal", "result", "GoalOrientedResult"),
    ("topple_share_figure", "ac", "result", "ActorCriticResult"),
])
def test_figures_refuse_the_wrong_result_type(small_results, figure, wrong, name, shown):
    refused(lambda: getattr(icm.figures, figure)(small_results[wrong]), name, shown, "type")
    refused(lambda: getattr(icm.figures, figure)({"a": 1}), name, "{'a': 1}", "type")


def test_figure_arguments(small_results):
    goal, ac, rods_result = small_results["goal"], small_results["ac"], small_results["rods"]
    refused(lambda: icm.figures.figure5_grid({"x": ac}), "results['x']", "ActorCriticResult",
            "type")
    refused(lambda: icm.figures.figure6_grid([ac]), "results", "ActorCriticResult", "type")
    refused(lambda: icm.figures.practice_figure({"x": goal}), "results['x']",
            "GoalOrientedResult", "type")
    refused(lambda: icm.figures.physics_comparison_figure({"x": goal}), "runs['x']",
            "GoalOrientedResult", "type")
    refused(lambda: icm.figures.figure5(goal, ax="left"), "ax", "'left'", "type")
    refused(lambda: icm.figures.figure5(goal, title=5), "title", "5", "type")
    refused(lambda: icm.figures.figure7(rods_result, seed=2), "seed", "2", "value")
    refused(lambda: icm.figures.figure7(rods_result, reading="most"), "reading", "'most'",
            "value")
    refused(lambda: icm.figures.figure7(rods_result, episode=99), "episode", "99", "value")
    refused(lambda: icm.figures.figure4(methods="learn"), "methods", "'learn'", "type")
    refused(lambda: icm.figures.figure4(methods=("fly",)), "methods", "'fly'", "value")
    refused(lambda: icm.figures.outcome_table_figure(red_button=6), "red_button", "6", "value")
    refused(lambda: icm.figures.sweep_heatmap({"epsilon": [0.1]}, "epsilon", "window",
                                              "red_first"), "frame", "{'epsilon'", "type")
    refused(lambda: icm.figures.topple_map_figure({"red": 4}), "topple_map", "{'red': 4}",
            "type")
    refused(lambda: icm.figures.animation([]), "frames", "[]", "type")
    refused(lambda: icm.figures.animation([np.zeros((8, 8, 3))], fps=0), "fps", "0", "value")
    refused(lambda: icm.figures.press_trace_figure({"time": []}), "record", "'time'", "type")
    refused(lambda: icm.figures.new_figure(width=-1), "width", "-1", "value")
    _, ax = icm.figures.new_figure()
    band = np.ones((3, 4))
    refused(lambda: icm.figures.plot_mean_band("ax", band, "red", "x"), "ax", "'ax'", "type")
    refused(lambda: icm.figures.plot_mean_band(ax, [[np.nan]], "red", "x"), "values", "nan",
            "value")
    refused(lambda: icm.figures.plot_mean_band(ax, band, "red", "x", x=[1, 2]), "x", "[1, 2]",
            "value")
    refused(lambda: icm.figures.plot_mean_band(ax, band, "red", "x", linestyle="dotted"),
            "linestyle", "'dotted'", "value")


def test_sweep_heatmap_refuses_unknown_columns():
    table = icm.experiments.sweep(icm.experiments.run_goal_oriented, {"epsilon": [0.1]},
                                  n_seeds=1, n_trials=2, progress=False)
    refused(lambda: icm.figures.sweep_heatmap(table, "epsilon", "window", "red_first"), "y",
            "'window'", "value")


def test_rendering_refuses_unknown_cameras_and_sizes(physics_buttons):
    physics = physics_buttons.physics
    refused(lambda: icm.figures.icub.render(physics, "ceiling"), "camera", "'ceiling'",
            "value")
    refused(lambda: icm.figures.icub.render(physics, "side", height=0), "height", "0", "value")
    refused(lambda: icm.figures.icub.render(physics, "side", width=5000), "width", "5000",
            "value")
    refused(lambda: icm.figures.cameras_figure(physics, "side"), "cameras", "'side'", "type")
    refused(lambda: icm.figures.record_press(button=7), "button", "7", "value")
    refused(lambda: icm.figures.record_move(action=4), "action", "4", "value")


# --- icm.widgets -------------------------------------------------------------------------

def test_panels_refuse_bad_sizes_and_arguments_they_cannot_hold():
    refused(lambda: icm.widgets.figure5_panel(n_trials=0), "n_trials", "0", "value")
    refused(lambda: icm.widgets.figure5_panel(epsilon=0.2), "epsilon", "epsilon", "value")
    refused(lambda: icm.widgets.figure5_panel(colour="red"), "colour", "colour", "value")
    refused(lambda: icm.widgets.figure6_panel(n_trials=-3), "n_trials", "-3", "value")
    refused(lambda: icm.widgets.figure7_panel(n_episodes=1.5), "n_episodes", "1.5", "type")
    refused(lambda: icm.widgets.figure7_panel(seed=-1), "seed", "-1", "value")


# --- the last cases: overflow, wrong run functions, comparisons, panels, figures -------

def test_a_linear_predictor_refuses_outcomes_whose_errors_overflow():
    predictor = LinearPredictor(4, 2)
    refused(lambda: predictor.update((0, 0), 1, [1e308, 1e308]), "observed", "1e+308", "value")
    refused(lambda: predictor.update((0, 0), 1, [1e308, -1e308]), "observed", "1e+308", "value")
    assert predictor.predict((0, 0), 1).tolist() == [0.0, 0.0]  # nothing was changed
    assert predictor.update((0, 0), 1, [1, 0]) == 1.0


def _not_a_run(n_seeds, seed, progress, epsilon=0.1):
    return {"epsilon": epsilon}


def test_sweep_refuses_a_function_that_does_not_return_a_run_result():
    refused(lambda: icm.experiments.sweep(_not_a_run, {"epsilon": [0.1]}, progress=False),
            "run_fn", "{'epsilon': 0.1}", "type")


def test_robustness_verdicts_need_shares_and_thresholds_in_0_1():
    refused(lambda: stats.verdict(NAN, 1.0, 0.9), "low", "nan", "value")
    refused(lambda: stats.verdict(0.5, 1.2, 0.9), "high", "1.2", "value")
    refused(lambda: stats.verdict(0.5, 0.6, 1.5), "threshold", "1.5", "value")
    refused(lambda: stats.verdict(0.7, 0.6, 0.5), "low", "0.7", "value")
    assert stats.verdict(0.95, 1.0, 0.9) == "holds"


@pytest.fixture(scope="module")
def signal_comparison():
    return icm.experiments.run_signal_comparison(n_seeds=2, n_trials=3, noisy=(False,),
                                                 signals=("novelty",), progress=False)


def test_a_signal_comparison_refuses_a_world_or_key_it_did_not_run(signal_comparison):
    refused(lambda: icm.chapters.curiosity.signal_table(signal_comparison, noisy_button=True), "noisy_button", "True",
            "value")
    refused(lambda: signal_comparison.numbers(["novelty"]), "signal", "['novelty']", "type")
    refused(lambda: signal_comparison.numbers("novelty", "task", True), "noisy_button",
            "('novelty', 'task', True)", "value")


def test_panels_refuse_bad_settings_when_called_not_when_iterated():
    from icm.experiments import panel_data

    refused(lambda: panel_data.panel_curves_for("figure5", fixed={"n_seeds": 0}),
            "fixed['n_seeds']", "0", "value")
    refused(lambda: panel_data.panel_runs("figure5", [1, 2]), "settings", "1", "type")
    refused(lambda: panel_data.panel_runs("figure5", [{"bogus": 1}]), "'bogus'", "epsilon",
            "value")


def test_physics_environments_name_the_seed_they_refuse():
    for name in ("buttons", "rods"):
        refused(lambda: icm.envs.load(name, physics=True, seed=-5), "seed", "-5", "value")
        refused(lambda: icm.envs.load_continuous(name, seed=-5), "seed", "-5", "value")


def test_figures_refuse_bad_sizes_labels_and_kinds():
    from icm.experiments import coin_rewards
    from icm.figures.curiosity import coin_flip_figure as _coin_flip

    curves = {"x": np.arange(1, 4), "xlabel": "trial",
              "groups": [{"title": "t", "ylabel": "y",
                          "series": {"red": (np.ones(3), np.zeros(3), np.ones(3))}}]}
    refused(lambda: icm.figures.draw_curves(curves, height=0), "height", "0", "value")
    refused(lambda: icm.figures.draw_curves({**curves, "groups": [{**curves["groups"][0],
                                                                   "title": 5}]}),
            "title", "5", "type")
    paid = coin_rewards.outcome_rewards(rewards=("novelty",), n_tries=3, n_seeds=2)
    refused(lambda: _coin_flip({("novelty", "sideways"): paid[("novelty", "coin")]}),
            "curves", "sideways", "value")
    goal = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=3, progress=False)
    refused(lambda: icm.figures.figure5_grid({1: goal}), "results", "label 1", "type")
    refused(lambda: icm.chapters.goal_oriented_interest.comparison_table({("a",): goal}), "results", "('a',)",
            "type")


def test_a_static_panel_keeps_markup_in_its_data_out_of_the_page():
    from icm.figures.static_panels import StaticPanel

    panel = StaticPanel({"$schema": "x", "title": "a <!--<script> b </script> & c"}, "t")
    page = panel.html()
    script = page.split('-spec">', 1)[1].split("</script>", 1)[0]
    assert "<" not in script and ">" not in script and "&" not in script
    import json
    assert json.loads(script)["title"] == "a <!--<script> b </script> & c"


# --- icm.viewer --------------------------------------------------------------------------

def test_live_views_refuse_unknown_scenes_sizes_and_flags(tmp_path):
    from icm import viewer

    refused(lambda: viewer.scene_xml("kitchen"), "scene", "'kitchen'", "value")
    refused(lambda: viewer.scene_export(2), "scene", "2", "type")
    refused(lambda: viewer.learner_replay(n_trials=0), "n_trials", "0", "value")
    refused(lambda: viewer.learner_replay(seed=-1), "seed", "-1", "value")
    refused(lambda: viewer.rod_replay(n_episodes=1.5), "n_episodes", "1.5", "type")
    refused(lambda: viewer.formed_presses("babbling"), "babbling", "'babbling'", "type")
    refused(lambda: viewer.live_scene("kitchen"), "scene", "'kitchen'", "value")
    refused(lambda: viewer.live_scene("rods", live="yes"), "live", "'yes'", "type")
    refused(lambda: viewer.live_scene("rods", static_path=3), "static_path", "3", "type")
    refused(lambda: viewer.live_learner(n_trials=-2), "n_trials", "-2", "value")
    refused(lambda: viewer.live_rod_learner(n_episodes=0), "n_episodes", "0", "value")
    refused(lambda: viewer.live_formed_presses(None), "babbling", "None", "type")
    data = {"scene": "rods", "mode": "scene"}
    refused(lambda: viewer.LiveView([], b"", "a still"), "data", "[]", "type")
    refused(lambda: viewer.LiveView({"scene": "sea"}, b"", "a still"), "data", "'sea'", "value")
    refused(lambda: viewer.LiveView(data, "jpeg", "a still"), "poster", "'jpeg'", "type")
    refused(lambda: viewer.LiveView(data, b"", None), "alt", "None", "type")
    still = viewer.LiveView(data, b"", "a still", live=False)
    refused(lambda: viewer.write_page(3, [still], tmp_path), "folder", "3", "type")
    refused(lambda: viewer.write_page(tmp_path, [], tmp_path), "views", "[]", "type")
    refused(lambda: viewer.write_page(tmp_path, ["view"], tmp_path), "views[0]", "'view'",
            "type")
    refused(lambda: viewer.write_page(tmp_path, [still], tmp_path), "views[0]", "still",
            "value")
    live = viewer.LiveView(data, b"", "a still", live=True)
    refused(lambda: viewer.write_page(tmp_path, [live], tmp_path), "static_dir",
            str(tmp_path), "value")


def test_formed_presses_refuse_a_run_the_result_does_not_have():
    from icm import viewer
    from icm.experiments import run_goal_babbling

    babbling = run_goal_babbling(n_seeds=2, n_rollouts=3, seed=0, progress=False)
    refused(lambda: viewer.formed_presses(babbling, run=2), "run", "2", "value")
    refused(lambda: viewer.formed_presses(babbling, run="0"), "run", "'0'", "type")
