"""Registration where things are defined: a made-up interest signal is one class, a
made-up scenario one environment plus its registration, each added through the public
path only (`icm.learners.interest.interest_signal`, `icm.envs.SUITE.add`), and every
part of the library that lists signals or scenarios then knows it."""

import dm_env
import numpy as np
import pytest
from dm_env import specs

import icm.envs
from icm import cli
from icm.experiments import rod_toppling, run_goal_oriented
from icm.figures import curiosity as curiosity_figures
from icm.learners import interest, q_learning
from icm.learners.goal_oriented import GoalOrientedSettings


@pytest.fixture
def surprise_squared(monkeypatch):
    """The signal CONTRIBUTING shows, added as a user adds one: one class, registered
    by its decorator (the registry is restored after the test)."""
    monkeypatch.setattr(interest, "SIGNAL_CLASSES", dict(interest.SIGNAL_CLASSES))

    @interest.interest_signal
    class SurpriseSquared(interest.InterestSignal):
        NAME = "surprise_squared"
        COLOUR, LINESTYLE, MARKER = "#e7298a", "-", "v"

        def record(self, task, error):
            self._append(task, error)

        def interest(self, task):
            history = self._history.get(task, ())
            return history[-1] ** 2 if history else 0.0

        @staticmethod
        def table_values(table, rows):
            last = table.errors[rows][..., -1]
            return np.where(table.count[rows] > 0, last * last, 0.0)

    return SurpriseSquared


def test_a_signal_is_one_class(surprise_squared):
    name = surprise_squared.NAME
    assert name in interest.SIGNALS and name in GoalOrientedSettings.spec("interest").choices
    assert name in q_learning.REWARDS
    # The learners run it: the batched learner as the one-agent class, seed by seed.
    result = run_goal_oriented(n_seeds=2, n_trials=4, interest=name, progress=False)
    assert result.settings["interest"] == name and np.isfinite(result.interest).all()
    # The figures draw it in its own colour and style.
    assert curiosity_figures.SIGNAL_COLOURS[name] == "#e7298a"
    assert curiosity_figures.SIGNAL_STYLES[name] == {"linestyle": "-", "marker": "v"}
    # The command line offers it.
    args = cli.build_parser().parse_args(["figure5", "--interest", name])
    assert cli._settings_of(args)["interest"] == name
    # The rods' compiled loop does not compute it (no KERNEL_FORMULA), and says so by name.
    with pytest.raises(ValueError, match="'surprise_squared' is an interest signal the "
                                         "compiled rod loop does not compute"):
        rod_toppling.run_rod_toppling(n_seeds=1, n_episodes=2, reward=name, progress=False)


def test_the_library_signals_carry_their_colour_and_kernel_code():
    from icm.experiments import _rods_kernel

    assert _rods_kernel.signal_codes() == {
        "learning_progress": _rods_kernel.SLOPE, "prediction_error": _rods_kernel.ERROR,
        "novelty": _rods_kernel.NOVELTY, "random": _rods_kernel.NONE}
    assert [_rods_kernel.FORMULAS[c] for c in (_rods_kernel.ERROR, _rods_kernel.SLOPE,
                                               _rods_kernel.NOVELTY, _rods_kernel.NONE)] \
        == ["error", "slope", "novelty", "none"]
    colours = dict(curiosity_figures.SIGNAL_COLOURS)
    assert set(colours) == set(interest.SIGNALS) and len(set(colours.values())) == 4


class CoinFlips(dm_env.Environment):
    """A made-up scenario's rules: guess a coin, 3 flips an episode, reward 1 when
    right."""

    def __init__(self, seed=None):
        self._random = np.random.default_rng(seed)
        self._flips = 0

    def reseed(self, seed):
        self._random = np.random.default_rng(seed)

    def reset(self):
        self._flips = 0
        return dm_env.restart({"coin": np.zeros(1, dtype=np.int64)})

    def step(self, action):
        coin = int(self._random.integers(2))
        self._flips += 1
        observation = {"coin": np.array([coin])}
        reward = float(coin == action)
        if self._flips >= 3:
            return dm_env.truncation(reward, observation, discount=1.0)
        return dm_env.transition(reward, observation)

    def observation_spec(self):
        return {"coin": specs.BoundedArray((1,), np.int64, 0, 1, name="coin")}

    def action_spec(self):
        return specs.DiscreteArray(2, name="guess")


@pytest.fixture
def coin_scenario():
    """A scenario added as a user adds one: its environment and its registration."""

    @icm.envs.SUITE.add("coin", episodes=CoinFlips)
    class CoinTable(CoinFlips):
        """The coin scenario's tabular version."""

    yield CoinTable
    icm.envs.SUITE.remove("coin")


def test_a_scenario_is_its_package_and_its_registration(coin_scenario):
    assert "coin" in icm.envs.NAMES
    env = icm.envs.load("coin", seed=3)
    assert isinstance(env, coin_scenario)
    steps = [env.reset()] + [env.step(1) for _ in range(3)]
    assert steps[-1].last() and all(s.observation["coin"].shape == (1,) for s in steps)
    gym_env = icm.envs.as_gymnasium(icm.envs.load("coin", seed=3))
    observation, _ = gym_env.reset(seed=5)
    assert observation["coin"].shape == (1,)
    with pytest.raises(ValueError, match="scenario 'coin' has no physics version"):
        icm.envs.load("coin", physics=True)
    with pytest.raises(ValueError, match="unknown argument"):
        icm.envs.load("coin", start_cell=(0, 0))


def test_the_suite_refuses_what_it_cannot_register(coin_scenario):
    with pytest.raises(ValueError, match="registered already"):
        icm.envs.SUITE.add("coin", episodes=CoinFlips)
    with pytest.raises(TypeError, match="must subclass episodes"):
        icm.envs.SUITE.add("other", episodes=CoinFlips)(int)
    with pytest.raises(TypeError, match="physics must be 'module:name'"):
        icm.envs.SUITE.add("other", episodes=CoinFlips, physics="no_colon")
    assert "other" not in icm.envs.SUITE
    with pytest.raises(ValueError, match="unknown environment 'other'; known: buttons, "
                                         "rods, coin"):
        icm.envs.load("other")
