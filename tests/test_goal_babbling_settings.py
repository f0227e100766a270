"""Goal babbling's settings, written once: `GoalBabblingSettings` (its `Setting`s
declared where they are used), the registry of goal-choice strategies, and what reads
them (the run's checks, the command line)."""

import numpy as np
import pytest

from icm import cli
from icm.experiments import babbling_space, goal_babbling
from icm.learners import goal_choice
from icm.learners.goal_babbling import GoalBabblingSettings
from icm.learners.maturation import JointRangeMaturation, MaturationSettings


def _grid():
    return goal_choice.RegionGrid(babbling_space.GOAL_LOW, babbling_space.GOAL_HIGH,
                                  babbling_space.REGION_GRID)


def test_the_settings_hold_the_defaults_the_run_used_to_type():
    settings = GoalBabblingSettings()
    assert settings.as_dict() == {
        "strategy": "learning_progress", "exploration_noise": 0.05, "epsilon": 0.3,
        "window": 10, "inverse_model": "nearest_neighbour", "measure": "learning_progress",
        "regions": "fixed", "maturation": "none", "maturation_start": 0.5,
        "maturation_window": 40, "maturation_plateau": 0.01, "maturation_step": 0.01}
    assert goal_babbling.STRATEGIES == ("random_motor", "random_goal", "learning_progress")
    assert goal_choice.DEFAULT_EPSILON == 0.3 and goal_choice.DEFAULT_WINDOW == 10
    assert MaturationSettings().as_dict() == {"start": 0.5, "window": 40, "plateau": 0.01,
                                              "step": 0.01}


@pytest.mark.parametrize("name, value, message", [
    ("epsilon", 1.5, "epsilon must be a number in [0, 1], got 1.5"),
    ("window", 1, "window must be an integer >= 2"),
    ("exploration_noise", 0, "exploration_noise must be a number in (0, 1]"),
    ("strategy", "curious", "strategy must be one of"),
    ("regions", "tree", "regions must be one of 'fixed', 'splitting'"),
])
def test_each_setting_is_checked_once_by_its_declaration(name, value, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")
                       .replace("[", r"\[").replace("]", r"\]")):
        GoalBabblingSettings(**{name: value})
    with pytest.raises(ValueError, match=name):  # the run refuses it with the same check
        goal_babbling.run_goal_babbling(n_seeds=1, n_rollouts=5, progress=False,
                                        **{name: value})
    with pytest.raises(ValueError, match=name):  # and the learner's part too
        if name in ("epsilon", "window"):
            goal_choice.RegionProgress(_grid(), 1, **{name: value})
        else:
            raise ValueError(name)


def test_the_maturation_clock_reads_its_settings():
    low, high, home = np.zeros(2), np.ones(2), np.full(2, 0.5)
    clock = JointRangeMaturation.from_settings(3, home, low, high, MaturationSettings(
        start=0.25, window=4))
    assert clock.start == 0.25 and clock.window == 4 and clock.psi.tolist() == [0.25] * 3
    with pytest.raises(ValueError, match=r"start must be a number in \(0, 1\]"):
        MaturationSettings(start=0.0)
    with pytest.raises(ValueError, match="plateau"):
        JointRangeMaturation(1, home, low, high, plateau=-1.0)


def test_the_maturation_clock_is_set_from_a_run_the_command_line_and_a_study(monkeypatch):
    # The clock's settings are the learner's (maturation_start, ...): a run takes them
    # as keywords (or in `settings`), and its clock starts where they say.
    assert {f"maturation_{n}" for n in MaturationSettings.names()} <= set(
        GoalBabblingSettings.names())
    run = goal_babbling.run_goal_babbling("random_goal", n_seeds=1, n_rollouts=20,
                                          maturation="joint_range", maturation_start=0.3,
                                          progress=False)
    assert run.settings["maturation_start"] == 0.3 and run.maturity[0, 0] == 0.3
    assert GoalBabblingSettings(maturation_window=8).maturation_settings() == \
        MaturationSettings(window=8)
    with pytest.raises(ValueError, match=r"maturation_start must be a number in \(0, 1\]"):
        goal_babbling.run_goal_babbling(n_seeds=1, n_rollouts=5, maturation_start=0.0,
                                        progress=False)
    # The command line offers them, from the same Setting.
    args = cli.build_parser().parse_args(["goal-babbling", "--maturation", "joint_range",
                                          "--maturation-start", "0.25"])
    assert cli._settings_of(args)["maturation_start"] == 0.25
    # A study's arm is `run_goal_babbling`'s arguments: an arm that grows up from 0.3.
    from icm.studies.forming_actions import arms
    monkeypatch.setitem(arms.ARMS, "growing up from 0.3",
                        {"maturation": "joint_range", "maturation_start": 0.3})
    entry = arms.run_arm("growing up from 0.3", 100, ("maturity",), n_seeds=1,
                         n_rollouts=100)
    # From 0.3, not the default 0.5 (the clock only grows: 0.34 after 100 rollouts).
    assert 0.3 <= entry["maturity"][0][0] < MaturationSettings.spec("start").default


def test_strategy_comes_by_position_or_by_name_not_both():
    with pytest.raises(TypeError, match="strategy both by position and by name"):
        goal_babbling.run_goal_babbling("random_goal", strategy="random_motor", n_seeds=1,
                                        n_rollouts=5, progress=False)


def test_a_settings_object_gives_the_run_of_its_keywords():
    by_keywords = goal_babbling.run_goal_babbling("random_goal", n_seeds=1, n_rollouts=30,
                                                  epsilon=0.2, window=5, progress=False)
    by_object = goal_babbling.run_goal_babbling(
        n_seeds=1, n_rollouts=30, progress=False,
        settings=GoalBabblingSettings(strategy="random_goal", epsilon=0.2, window=5))
    assert by_object.settings == by_keywords.settings
    np.testing.assert_array_equal(by_object.movements, by_keywords.movements)
    np.testing.assert_array_equal(by_object.test_error, by_keywords.test_error)


def test_the_command_line_options_are_the_settings():
    parser = cli.build_parser()
    args = parser.parse_args(["goal-babbling", "--epsilon", "0.2", "--regions", "splitting"])
    settings = cli._settings_of(args)
    assert set(settings) == set(GoalBabblingSettings.names()) - {"strategy"}
    assert settings["epsilon"] == 0.2 and settings["regions"] == "splitting"
    assert settings["window"] == GoalBabblingSettings.spec("window").default


@pytest.fixture
def made_up_strategy(monkeypatch):
    """A strategy registered through the public path (`goal_strategy`), for one test:
    every goal in the first region, drawn as random goal babbling draws them."""
    monkeypatch.setattr(goal_choice, "STRATEGIES", dict(goal_choice.STRATEGIES))

    class FirstRegion(goal_choice.RandomGoals):
        def sample(self, generators):
            low, high = self.grid.bounds()[0]
            goals = np.array([rng.uniform(low, high) for rng in generators])
            return goals, self.grid.region_of(goals)

    @goal_choice.goal_strategy("first_region", "every goal in the first region")
    def first_region(grid, n_rows, measure, epsilon, window, regions):
        return FirstRegion(grid, n_rows)

    return "first_region"


def test_a_strategy_is_one_registration_where_it_is_defined(made_up_strategy):
    assert made_up_strategy in GoalBabblingSettings.spec("strategy").choices
    result = goal_babbling.run_goal_babbling(made_up_strategy, n_seeds=1, n_rollouts=30,
                                             progress=False)
    assert result.strategy == made_up_strategy
    chosen = result.regions[0][result.regions[0] >= 0]
    assert chosen.size and set(chosen.tolist()) == {0}
    with pytest.raises(ValueError, match="name must be new"):
        goal_choice.goal_strategy(made_up_strategy, "again")


def test_a_strategy_not_registered_is_refused():
    with pytest.raises(ValueError, match="strategy must be one of 'random_motor', "
                                         "'random_goal', 'learning_progress'"):
        goal_choice.make_goal_choice("first_region", _grid(), 1)


def test_the_public_loop_is_the_runs_loop_and_observes_each_rollout():
    from icm.envs.buttons.movements import MovementLab
    from icm.experiments.seeding import run_seeds

    run = goal_babbling.run_goal_babbling("learning_progress", n_seeds=2, n_rollouts=30,
                                          seed=4, progress=False)
    lab = MovementLab(1)
    seen = []
    seeds = [s[0] for s in run_seeds(4, 2, 2)]
    played = goal_babbling.babble(goal_babbling.make_agent(lab, seeds, 30), lab, 30,
                                  observe=lambda step: seen.append(int(step.episode[0])))
    assert seen == list(range(30))
    for name in ("movements", "outcomes", "regions", "interest"):
        np.testing.assert_array_equal(played[name], getattr(run, name))
    with pytest.raises(ValueError, match="observe must be a function"):
        goal_babbling.babble(goal_babbling.make_agent(lab, seeds, 3), lab, 3, observe=5)
