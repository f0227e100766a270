"""The Gymnasium view of the environments passes Gymnasium's own checker."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import icm

ALL = [("buttons", False), ("buttons", True), ("rods", False), ("rods", True)]


@pytest.mark.filterwarnings("error::UserWarning")  # the checker's complaints are warnings
@pytest.mark.parametrize("name, physics", ALL)
def test_gymnasium_env_checker_passes(name, physics):
    env = icm.envs.as_gymnasium(icm.envs.load(name, physics=physics, seed=0))
    assert isinstance(env, gymnasium.Env)
    check_env(env, skip_render_check=True)


@pytest.mark.parametrize("name, physics", ALL)
def test_observations_are_in_the_space_and_match_the_dm_env(name, physics):
    env = icm.envs.as_gymnasium(icm.envs.load(name, physics=physics, seed=1))
    twin = icm.envs.load(name, physics=physics, seed=1)
    observation, info = env.reset(seed=None)
    expected = twin.reset().observation
    for key in expected:
        np.testing.assert_array_equal(observation[key], expected[key])
    rng = np.random.RandomState(0)
    for _ in range(10):
        action = int(rng.randint(env.action_space.n))
        observation, reward, terminated, truncated, _ = env.step(action)
        step = twin.step(action)
        assert env.observation_space.contains(observation)
        for key in step.observation:
            np.testing.assert_array_equal(observation[key], step.observation[key])
        assert reward == step.reward
        assert terminated or truncated or not step.last()
        if terminated or truncated:
            env.reset(), twin.reset()


def test_time_limit_is_truncation_and_topple_is_termination():
    buttons = icm.envs.as_gymnasium(icm.envs.load("buttons", presses_per_trial=2))
    buttons.reset(seed=0)
    assert buttons.step(0)[2:4] == (False, False)
    assert buttons.step(0)[2:4] == (False, True)  # the trial's time limit
    rods = icm.envs.as_gymnasium(icm.envs.load("rods", start_cell=(2, 0)))
    rods.reset(seed=0)
    observation, reward, terminated, truncated, _ = rods.step(0)  # into the red rod
    assert (terminated, truncated) == (True, False)
    assert observation["rods"].tolist() == [1, 0]
    with pytest.raises(RuntimeError, match="reset"):
        rods.step(0)


def test_reset_with_a_seed_repeats_the_episode():
    env = icm.envs.as_gymnasium(icm.envs.load("buttons"))
    first = [env.reset(seed=5)[0]["lights"].tolist() for _ in range(3)]
    assert first[0] == first[1] == first[2]
    layouts = {tuple(env.reset()[0]["lights"]) for _ in range(30)}
    assert len(layouts) > 1  # without a seed, trials go on drawing


def test_physics_env_renders_and_bad_render_modes_are_refused():
    env = icm.envs.as_gymnasium(icm.envs.load("rods", physics=True), render_mode="rgb_array")
    env.reset(seed=0)
    assert env.render().shape == (480, 640, 3)
    with pytest.raises(ValueError, match="physics"):
        icm.envs.as_gymnasium(icm.envs.load("rods"), render_mode="rgb_array")
    with pytest.raises(ValueError, match="render_mode"):
        icm.envs.as_gymnasium(icm.envs.load("rods"), render_mode="human")
