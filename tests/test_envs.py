"""The button console, tabular version: spec conformance and the paper's rules."""

import collections
import unittest

import dm_env
import numpy as np
import pytest
from dm_env import test_utils

import icm
from icm.envs import buttons


class ButtonConsoleDmEnvTest(test_utils.EnvironmentTestMixin, unittest.TestCase):
    """dm_env's own conformance tests (reset, step, specs, a long action sequence)."""

    def make_object_under_test(self):
        return icm.envs.load("buttons", seed=0)

    def make_action_sequence(self):
        rng = np.random.RandomState(1)
        for _ in range(50):  # several trials, each ending with a LAST step
            yield np.int64(rng.randint(buttons.N_BUTTONS))


def play(env, actions):
    steps = [env.reset()]
    for a in actions:
        steps.append(env.step(a))
    return steps


def test_load_knows_buttons_and_rejects_unknown_names():
    assert isinstance(icm.envs.load("buttons"), dm_env.Environment)
    with pytest.raises(ValueError, match="known: .*buttons"):
        icm.envs.load("levers")


def test_observations_match_the_spec_with_fixed_dtypes():
    env = icm.envs.load("buttons", seed=3)
    spec = env.observation_spec()
    assert list(spec) == ["lights", "boxes"]
    for step in play(env, [0, 1, 2, 3, 4, 2]):
        assert isinstance(step.observation, collections.OrderedDict)
        for name, array in step.observation.items():
            spec[name].validate(array)
            assert array.dtype == np.int64
        assert step.reward is None or step.reward == 0.0


def test_red_never_moves_and_green_is_never_on_red():
    env = icm.envs.load("buttons", seed=0, red_button=1)
    greens = []
    for _ in range(400):
        lights = env.reset().observation["lights"]
        assert lights[1] == buttons.RED
        assert np.sum(lights == buttons.RED) == 1 and np.sum(lights == buttons.GREEN) == 1
        greens.append(int(np.flatnonzero(lights == buttons.GREEN)[0]))
    counts = collections.Counter(greens)
    assert set(counts) == {0, 2, 3, 4}  # all four green positions occur, never 1
    assert min(counts.values()) > 60  # roughly uniform: 100 expected each


def test_green_is_drawn_anew_every_trial_not_every_press():
    env = icm.envs.load("buttons", seed=5, presses_per_trial=4)
    for _ in range(20):
        first = env.reset().observation["lights"]
        for _ in range(4):
            assert np.array_equal(env.step(0).observation["lights"], first)


@pytest.mark.parametrize("seed", range(5))
def test_a_press_opens_the_box_of_its_colour_and_unlit_buttons_open_nothing(seed):
    env = icm.envs.load("buttons", seed=seed, presses_per_trial=5)
    lights = env.reset().observation["lights"]
    for button in range(5):
        boxes = env.step(button).observation["boxes"]
        expected = {buttons.RED: [1, 0], buttons.GREEN: [0, 1], buttons.OFF: [0, 0]}
        assert boxes.tolist() == expected[int(lights[button])]


def test_boxes_close_before_the_next_press():
    env = icm.envs.load("buttons", seed=0, presses_per_trial=5, red_button=0)
    env.reset()
    assert env.step(0).observation["boxes"].tolist() == [1, 0]
    # The red box was open; an unlit press shows both boxes closed again.
    unlit = [b for b in range(5) if env.lights[b] == buttons.OFF][0]
    assert env.step(unlit).observation["boxes"].tolist() == [0, 0]


def test_a_trial_lasts_its_presses_and_ends_on_a_time_limit():
    env = icm.envs.load("buttons", seed=0, presses_per_trial=4)
    steps = play(env, [0, 1, 2, 3])
    assert [s.step_type for s in steps] == [dm_env.StepType.FIRST] + \
        [dm_env.StepType.MID] * 3 + [dm_env.StepType.LAST]
    assert steps[-1].discount == 1.0  # truncation, not termination
    assert env.step(0).first()  # the next step starts a new trial


def test_same_seed_same_trials_and_different_seeds_differ():
    def layouts(seed):
        env = icm.envs.load("buttons", seed=seed)
        return [tuple(env.reset().observation["lights"]) for _ in range(30)]
    assert layouts(7) == layouts(7)
    assert layouts(7) != layouts(8)


@pytest.mark.parametrize("action", [5, -1, 2.0, 1.5, "1", None, True, np.array([1, 2])])
def test_invalid_actions_raise_value_error_naming_the_allowed_range(action):
    env = icm.envs.load("buttons", seed=0)
    env.reset()
    with pytest.raises(ValueError, match=r"action must be an integer in 0\.\.4"):
        env.step(action)


def test_numpy_integer_actions_are_accepted():
    env = icm.envs.load("buttons", seed=0)
    env.reset()
    env.step(np.int64(3))
    env.step(np.array(2))


@pytest.mark.parametrize("kwargs, message", [
    (dict(red_button=5), "red_button"),
    (dict(red_button=-1), "red_button"),
    (dict(presses_per_trial=0), "presses_per_trial"),
    (dict(seed=-3), "seed"),
    (dict(seed=1.5), "seed"),
    (dict(physics="yes"), "physics"),
])
def test_bad_environment_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        icm.envs.load("buttons", **kwargs)


@pytest.mark.parametrize("rewarded_box, index", [("red", 0), ("green", 1)])
def test_rewarded_box_pays_one_for_each_press_that_opens_it(rewarded_box, index):
    env = icm.envs.load("buttons", seed=2, presses_per_trial=5, rewarded_box=rewarded_box)
    env.reset()
    for button in range(5):
        step = env.step(button)
        assert step.reward == float(step.observation["boxes"][index] == 1)
    with pytest.raises(ValueError, match="rewarded_box"):
        icm.envs.load("buttons", rewarded_box="blue")


def test_layouts_and_press_outcome_describe_the_rules():
    all_layouts = buttons.layouts(red_button=2)
    assert len(all_layouts) == 4
    for lights in all_layouts:
        green = int(np.flatnonzero(lights == buttons.GREEN)[0])
        assert buttons.press_outcome(lights, 2).tolist() == [1, 0]
        assert buttons.press_outcome(lights, green).tolist() == [0, 1]


# --- the noisy button: the outcome of each draw, not only their frequencies ------------

# The rules (icm.envs.buttons.rules): one uniform number u per press of the noisy button
# opens the red box if u < 1/3, the green box if u < 2/3, and nothing otherwise.
NOISY_DRAWS = [(0.0, (1, 0)), (0.2, (1, 0)), (0.3333, (1, 0)),
               (0.3334, (0, 1)), (0.5, (0, 1)), (0.6666, (0, 1)),
               (0.6667, (0, 0)), (0.9, (0, 0)), (0.9999, (0, 0))]


def _noisy_boxes(u):
    """The boxes a press of the noisy button opens for the uniform draw `u`, written out
    from the rules (not through `noisy_outcome`).

    Args:
      u: a uniform number in [0, 1).

    Returns:
      (red, green), 1 for the box that opens.
    """
    return (1, 0) if u < 1 / 3 else (0, 1) if u < 2 / 3 else (0, 0)


def test_the_noisy_buttons_outcome_for_given_draws():
    for u, boxes in NOISY_DRAWS:
        assert _noisy_boxes(u) == boxes
        assert tuple(buttons.noisy_outcome(u).tolist()) == boxes, u
        assert buttons.EFFECTS[buttons.noisy_effect(u)] == boxes, u
    # The same, element-wise, as the batched consoles use it.
    draws = np.array([u for u, _ in NOISY_DRAWS])
    assert [buttons.EFFECTS[e] for e in buttons.noisy_effect(draws)] == \
        [boxes for _, boxes in NOISY_DRAWS]


def test_each_press_of_the_noisy_button_opens_what_its_own_draw_says():
    # The draws of a seed are known in advance: one per trial (its layout), then one
    # per press of the noisy button, in that order. Press it 3 times a trial, 4 trials.
    seed, presses = 17, 3
    draws = np.random.default_rng(seed).random(4 * (1 + presses))
    expected = [_noisy_boxes(u) for trial in draws.reshape(4, 1 + presses)
                for u in trial[1:]]
    assert {(1, 0), (0, 1), (0, 0)} <= set(expected)  # the seed shows every outcome
    env = buttons.ButtonConsole(seed=seed, presses_per_trial=presses, noisy_button=True)
    env.reset()
    seen = []
    while len(seen) < len(expected):
        step = env.step(buttons.NOISY_BUTTON)
        if not step.first():
            seen.append(tuple(step.observation["boxes"].tolist()))
    assert seen == expected
    # The batched consoles: row k draws what a console seeded like it draws.
    batch = buttons.ButtonConsoleBatch([seed, seed], noisy_button=True)
    effects = []
    for _ in range(4):
        batch.new_trials()
        for _ in range(presses):
            effects.append(batch.press([buttons.NOISY_BUTTON, 0])[0])
    assert [buttons.EFFECTS[e] for e in effects] == expected
