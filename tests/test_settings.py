"""Settings written once: each learner's settings object checks every value once, the
batched learners take it and refuse bad values too, everything else is derived from it,
adding a setting or an interest signal is one edit, and the compiled rod loop reads its
rules from their homes."""

import dataclasses
import inspect

import numpy as np
import pytest

import icm
from icm import _settings, cli, widgets
from icm.envs import buttons
from icm.envs.rods import rules as rod_rules
from icm.experiments import panel_data
from icm.studies import robustness
from icm.learners import action_selection, actor_critic, goal_oriented, interest, q_learning
from icm.learners.goal_oriented import GoalOrientedBatch, GoalOrientedSettings

LEARNERS = [(goal_oriented.GoalOrientedSettings, icm.experiments.run_goal_oriented),
            (actor_critic.ActorCriticSettings, icm.experiments.run_actor_critic),
            (q_learning.QLearnerSettings, icm.experiments.run_rod_toppling)]


@pytest.mark.parametrize("settings_cls, run_fn", LEARNERS, ids=lambda x: getattr(x, "__name__", ""))
def test_every_setting_says_where_it_comes_from(settings_cls, run_fn):
    for name, spec in settings_cls.specs().items():
        assert spec.name == name and spec.label and spec.source, name
        assert spec.check(spec.default) == spec.default
        if spec.published:
            assert spec.default == spec.paper, name  # the library follows the paper
        if spec.slider is not None:
            low, high, step = spec.slider.live
            grid = np.array(spec.slider.grid, dtype=float)
            assert low <= grid.min() and grid.max() <= high and spec.default in spec.slider.grid
            steps = (grid - low) / step
            assert np.allclose(steps, np.round(steps)), name  # every grid value on the slider
            for value in spec.slider.grid:
                spec.check(value)
        if spec.swept is not None:
            assert spec.default in spec.swept and not spec.published


def test_the_papers_values_are_the_papers():
    specs = GoalOrientedSettings.specs()
    assert specs["window"].paper == 5 and specs["new_task_factor"].paper == 0.5
    assert q_learning.QLearnerSettings.spec("predictor_lr").paper == 0.2
    unpublished = {"epsilon", "action_weight", "reading", "new_task_mean", "short_history",
                   "tie"}
    assert {n for n, s in specs.items() if not s.published} == unpublished


def test_a_settings_object_checks_once_and_names_what_it_refuses():
    settings = GoalOrientedSettings(epsilon=0.2, window=7)
    assert (settings.epsilon, settings.window, settings.reading) == (0.2, 7, "progress")
    with pytest.raises(ValueError, match=r"epsilon must be a number in \[0, 1\], got 7.0"):
        GoalOrientedSettings(epsilon=7.0)
    with pytest.raises(ValueError, match="window must be an integer in 2..100, got 1"):
        GoalOrientedSettings(window=1)
    with pytest.raises(TypeError, match="'bogus' is not a setting of GoalOrientedSettings"):
        GoalOrientedSettings(bogus=1)
    with pytest.raises(TypeError, match="takes its settings by name"):
        GoalOrientedSettings(0.1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        settings.epsilon = 0.5
    assert settings.replace(epsilon=0.3).epsilon == 0.3 and settings.epsilon == 0.2
    with pytest.raises(ValueError, match="tie must be one of 'latest', 'earliest'"):
        settings.replace(tie="random")


def test_settings_may_hold_one_value_per_row_each_checked():
    settings = GoalOrientedSettings(epsilon=[0.1, 0.3], window=np.array([3, 5]))
    assert settings.epsilon.tolist() == [0.1, 0.3] and settings.window.dtype == np.int64
    with pytest.raises(ValueError, match=r"epsilon\[1\] must be a number in \[0, 1\]"):
        GoalOrientedSettings(epsilon=[0.1, 7.0])
    with pytest.raises(TypeError, match="interest must be one value for every row"):
        GoalOrientedSettings(interest=["novelty", "random"])


def test_the_batched_learner_refuses_what_its_settings_refuse():
    # The example: GoalOrientedBatch, the class that actually runs, accepted
    # epsilon=7.0, window=1.
    contexts = np.array(buttons.layouts())
    with pytest.raises(ValueError, match="epsilon must be"):
        GoalOrientedBatch([0, 1], contexts, buttons.EFFECTS, 5, epsilon=7.0, window=1)
    with pytest.raises(ValueError, match=r"window\[1\] must be an integer in 2"):
        GoalOrientedBatch([0, 1], contexts, buttons.EFFECTS, 5, window=[5, 1])
    with pytest.raises(ValueError, match="either as settings or one by one"):
        GoalOrientedBatch([0], contexts, buttons.EFFECTS, 5, settings=GoalOrientedSettings(),
                          epsilon=0.2)
    for batch in (actor_critic.ActorCriticBatch,):
        with pytest.raises(ValueError, match="lr_actor must be"):
            batch([0], np.zeros((1, 7)), buttons.EFFECTS, 5, lr_actor=0.0)


@pytest.mark.parametrize("settings_cls, run_fn", LEARNERS, ids=lambda x: getattr(x, "__name__", ""))
def test_run_functions_take_exactly_the_settings_as_keywords(settings_cls, run_fn):
    parameters = inspect.signature(run_fn).parameters
    for name, spec in settings_cls.specs().items():
        assert parameters[name].default == spec.default
        assert parameters[name].kind == inspect.Parameter.KEYWORD_ONLY
        assert f"`{name}`: {spec.label}" in run_fn.__doc__  # the API reference lists it
    assert "settings" in parameters and run_fn.settings_class is settings_cls
    with pytest.raises(ValueError, match="'bogus' is not an argument of"):
        run_fn(n_seeds=1, bogus=3, progress=False)


def test_a_settings_object_and_keywords_give_the_same_run():
    settings = GoalOrientedSettings(epsilon=0.2, window=4)
    by_object = icm.experiments.run_goal_oriented(n_seeds=3, n_trials=8, settings=settings,
                                                  progress=False)
    by_keywords = icm.experiments.run_goal_oriented(n_seeds=3, n_trials=8, epsilon=0.2,
                                                    window=4, progress=False)
    mixed = icm.experiments.run_goal_oriented(n_seeds=3, n_trials=8, window=4,
                                              settings=GoalOrientedSettings(epsilon=0.2),
                                              progress=False)
    for other in (by_keywords, mixed):
        assert np.array_equal(by_object.interest, other.interest)
        assert by_object.settings == other.settings


def test_panels_cli_grids_and_robustness_are_derived_from_the_settings():
    for name, panel in panel_data.PANELS.items():
        settings_cls = panel.run.settings_class
        for control, grid in panel.sliders.items():
            assert grid == settings_cls.spec(control).slider.grid
    for name, spec in widgets.FIGURE5_SLIDERS.items():
        low, high, step = GoalOrientedSettings.spec(name).slider.live
        assert (spec["min"], spec["max"], spec["step"]) == (low, high, step)
    assert icm.experiments.goal_oriented.GRID_ARGUMENTS == tuple(
        n for n, s in GoalOrientedSettings.specs().items() if s.per_row)
    help_text = cli.build_parser()._subparsers._group_actions[0].choices["figure5"].format_help()
    for name, spec in GoalOrientedSettings.specs().items():
        assert "--" + name.replace("_", "-") in help_text
    study = robustness.STUDIES["goal_oriented"]
    assert study.setting("action_weight").values == GoalOrientedSettings.spec(
        "action_weight").swept
    assert study.setting("presses_per_trial").values == buttons.PRESSES_PER_TRIAL.swept


def test_adding_a_setting_is_one_entry_in_its_settings_class(monkeypatch):
    # A new setting declared once appears as a keyword of the run function, a CLI
    # option and a checked value, with nothing else edited.
    @_settings.settings_class
    class Extended(GoalOrientedSettings):
        temperature: float = _settings.setting(
            default=1.0, label="a new setting", kind="real", low=0.0, low_open=True,
            source="an example")

    def run(n_seeds=1, settings=None):
        return settings

    decorated = _settings.with_settings(Extended)(run)
    assert decorated(temperature=2.0).temperature == 2.0
    assert "temperature" in inspect.signature(decorated).parameters
    with pytest.raises(ValueError, match="temperature must be a number > 0"):
        decorated(temperature=0.0)
    parser = cli.argparse.ArgumentParser()
    cli._settings_options(parser, Extended)
    assert parser.parse_args(["--temperature", "3"]).settings_temperature == 3.0


class SurpriseSquared(interest.InterestSignal):
    """An example signal: the square of the last error (what a student might try)."""

    NAME = "surprise_squared"

    def record(self, task, error):
        self._append(task, error)

    def interest(self, task):
        history = self._history.get(task, ())
        return history[-1] ** 2 if history else 0.0

    @staticmethod
    def table_values(table, rows):
        last = table.errors[rows][..., -1]
        return np.where(table.count[rows] > 0, last * last, 0.0)


def test_adding_an_interest_signal_is_one_class_and_one_registry_entry(monkeypatch):
    monkeypatch.setitem(interest.SIGNAL_CLASSES, SurpriseSquared.NAME, SurpriseSquared)
    assert "surprise_squared" in interest.SIGNALS and "surprise_squared" in q_learning.REWARDS
    settings = GoalOrientedSettings(interest="surprise_squared")
    assert isinstance(goal_oriented.GoalOrientedAgent.from_settings(5, settings).interest,
                      SurpriseSquared)
    # The batched learner runs it, and gives the per-agent numbers.
    from test_batched import reference_goal_oriented

    run = icm.experiments.run_goal_oriented(n_seeds=3, n_trials=10, seed=2, progress=False,
                                            interest="surprise_squared")
    reference = reference_goal_oriented(3, 10, seed=2, interest="surprise_squared")
    np.testing.assert_array_equal(run.interest, reference["interest"])
    # The compiled rod loop does not compute it: refused by name, before it runs.
    with pytest.raises(ValueError, match="'surprise_squared' is an interest signal the "
                                         "compiled rod loop does not compute"):
        icm.experiments.run_rod_toppling(n_seeds=1, n_episodes=2, progress=False,
                                         reward="surprise_squared")


def test_a_signal_must_be_an_interest_signal_class():
    with pytest.raises(TypeError, match="subclass of InterestSignal"):
        interest.interest_signal(object)


# The compiled rod loop reads its rules from their homes -------------------------------

def _rods(**kwargs):
    return icm.experiments.run_rod_toppling(n_seeds=6, n_episodes=40, seed=4, progress=False,
                                            **kwargs)


def test_the_rod_loop_reads_the_wobbly_rods_probability_from_the_rules(monkeypatch):
    before = _rods(wobbly_rod=True)
    monkeypatch.setattr(rod_rules, "WOBBLE_TOPPLE_PROBABILITY", 0.9)
    after = _rods(wobbly_rod=True)
    assert not np.array_equal(before.toppled, after.toppled)
    # ... and so does the tabular twin, which the per-agent reference plays.
    from test_batched import reference_rod_toppling

    reference = reference_rod_toppling(6, 40, seed=4, wobbly_rod=True)
    np.testing.assert_array_equal(after.toppled, reference["toppled"])


def test_the_rod_loop_draws_what_action_selection_says_a_choice_draws(monkeypatch):
    before = _rods()
    monkeypatch.setattr(action_selection, "DRAWS_PER_CHOICE", 4)
    after = _rods()
    assert not np.array_equal(before.toppled, after.toppled)
    from test_batched import reference_rod_toppling

    reference = reference_rod_toppling(6, 40, seed=4)
    np.testing.assert_array_equal(after.toppled, reference["toppled"])


def test_the_rod_loop_takes_the_slope_weights_of_the_interest_module(monkeypatch):
    before = _rods(reward="learning_progress")
    real = interest.slope_weights
    monkeypatch.setattr(interest, "slope_weights", lambda n: tuple(2 * w for w in real(n)))
    after = _rods(reward="learning_progress")
    assert not np.array_equal(before.prediction_error, after.prediction_error) or \
        not np.array_equal(before.toppled, after.toppled)
