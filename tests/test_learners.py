"""Predictor, interest module and goal-oriented agent: hand-computed cases."""

import collections
import inspect

import numpy as np
import pytest

import icm
from icm.envs import buttons
from icm.learners import (GoalOrientedAgent, LearningProgressInterest, LinearPredictor,
                          NearestNeighbourPredictor, QLearner, least_squares_slope)
from icm.learners import interest, predictors
from icm.learners.goal_oriented import GoalOrientedBatch, GoalOrientedSettings
from icm.learners.interest import (DEFAULT_NEW_TASK_FACTOR, DEFAULT_WINDOW, InterestTable,
                                   make_interest)
from icm.learners.predictors import DEFAULT_LINEAR_LR

RED_TASK = ((0, 0), (1, 0))
GREEN_TASK = ((0, 0), (0, 1))
NOTHING_TASK = ((0, 0), (0, 0))


# --- least-squares slope and learning progress -------------------------------------

@pytest.mark.parametrize("window", [2, 3, 5, 8, 13, 20])
def test_slope_of_a_line_is_its_slope_whatever_the_window(window):
    line = [0.5 + 0.1 * x for x in range(window)]
    assert least_squares_slope(line) == pytest.approx(0.1)
    # The interest module, fed the same line as errors, sees the same slope.
    literal = LearningProgressInterest(window=window, reading="literal")
    progress = LearningProgressInterest(window=window)
    for e in line:
        literal.record("t", e)
    for e in reversed(line):
        progress.record("t", e)
    assert literal.interest("t") == pytest.approx(0.1)
    assert progress.interest("t") == pytest.approx(0.1)


def test_slope_needs_two_values():
    with pytest.raises(ValueError, match="at least 2"):
        least_squares_slope([1.0])


def test_progress_after_one_surprise_then_correct_predictions():
    # Errors 1, 0, 0, 0, 0: slopes over x centred on 0 are -1, -1/2, -3/10, -2/10,
    # so the progress reading gives 1, 0.5, 0.3, 0.2; then the window holds only zeros.
    interest = LearningProgressInterest(window=5)
    seen = []
    for e in [1, 0, 0, 0, 0, 0]:
        interest.record("red", e)
        seen.append(interest.interest("red"))
    assert seen[1:] == pytest.approx([1.0, 0.5, 0.3, 0.2, 0.0])


def test_errors_going_up_are_interesting_only_in_the_literal_reading():
    progress, literal = LearningProgressInterest(), LearningProgressInterest(reading="literal")
    for e in [0, 0, 1]:
        progress.record("t", e)
        literal.record("t", e)
    assert progress.interest("t") == 0.0  # clipped at 0
    assert literal.interest("t") == pytest.approx(0.5)


def test_new_task_gets_a_share_of_the_mean_interest_of_the_known_tasks():
    interest = LearningProgressInterest(window=5, new_task_factor=0.5)
    assert interest.interest("anything") == 0.0  # never witnessed
    for e in [1, 0, 0, 0, 0]:
        interest.record("a", e)  # known, interest 0.2
    for e in [1, 0, 0]:
        interest.record("b", e)  # known, interest 0.5
    interest.record("c", 1.0)  # witnessed once
    assert interest.interest("c") == pytest.approx(0.5 * (0.2 + 0.5) / 2)
    interest.record("d", 0.0)  # another new task: new tasks do not count as "other"
    assert interest.interest("d") == pytest.approx(0.175)
    assert interest.tasks == ["a", "b", "c", "d"]
    assert interest.history("b") == [1.0, 0.0, 0.0]


def test_a_new_task_alone_has_no_interest():
    interest = LearningProgressInterest(new_task_factor=1.0)
    interest.record("only", 1.0)
    assert interest.interest("only") == 0.0


def test_window_keeps_only_the_last_k_errors():
    interest = LearningProgressInterest(window=3)
    for e in [5, 0, 0, 1, 1, 1]:
        interest.record("t", e)
    assert interest.interest("t") == 0.0  # the 5 and the drop from it are forgotten


# --- nearest-neighbour predictor ----------------------------------------------------

def test_empty_predictor_predicts_the_default():
    predictor = NearestNeighbourPredictor()
    assert predictor.predict((0, 1, 2), 0, default=(0, 0)) == (0, 0)
    assert len(predictor) == 0


def test_exact_experience_is_recalled():
    predictor = NearestNeighbourPredictor()
    predictor.update((0, 1, 2), 1, (1, 0))
    predictor.update((0, 2, 1), 2, (1, 0))
    assert predictor.predict((0, 1, 2), 1) == (1, 0)


def test_ties_go_to_the_most_recent_experience():
    predictor = NearestNeighbourPredictor(action_weight=10)
    context = (1, 0, 2, 0, 0)
    # Two experiences at the same distance (one light differs) from the query.
    predictor.update((1, 0, 2, 0, 1), 3, (0, 1))
    predictor.update((1, 0, 2, 1, 0), 3, (0, 0))
    assert predictor.predict(context, 3) == (0, 0)
    predictor.update((1, 1, 2, 0, 0), 3, (1, 1))  # a newer tie
    assert predictor.predict(context, 3) == (1, 1)


def test_cache_agrees_with_a_fresh_search():
    rng = np.random.default_rng(0)
    cached = NearestNeighbourPredictor(action_weight=1.0)
    queries = [(tuple(rng.integers(0, 3, 5).tolist()), int(rng.integers(5))) for _ in range(30)]
    for _ in range(60):
        c, a = queries[rng.integers(len(queries))]
        for q in queries[:10]:
            cached.predict(*q)  # fill the cache as the agent does
        cached.update(c, a, tuple(rng.integers(0, 2, 2).tolist()))
    fresh = NearestNeighbourPredictor(action_weight=1.0)
    for experience in cached._experiences:
        fresh.update(*experience)
    for q in queries:
        assert cached.predict(*q) == fresh.predict(*q)


def test_action_weight_decides_whether_red_generalises_across_layouts():
    first, second = [tuple(l.tolist()) for l in buttons.layouts(red_button=2)[:2]]
    experiences = [(first, 2, (1, 0)), (second, 0, (0, 0))]  # red pressed only in `first`
    action_first = NearestNeighbourPredictor()  # default: the action decides first
    plain = NearestNeighbourPredictor(action_weight=1.0)  # every entry counts the same
    for e in experiences:
        action_first.update(*e)
        plain.update(*e)
    assert action_first.predict(second, 2) == (1, 0)
    assert plain.predict(second, 2) == (0, 0)  # same layout, other button, is nearer


def test_contexts_of_different_lengths_are_refused():
    predictor = NearestNeighbourPredictor()
    predictor.update((0, 1), 0, (0, 0))
    with pytest.raises(ValueError, match="context must have 2 entries"):
        predictor.update((0, 1, 2), 0, (0, 0))


# --- the goal-oriented agent ----------------------------------------------------------

def observation(lights, boxes=(0, 0)):
    return collections.OrderedDict(lights=np.array(lights), boxes=np.array(boxes))


def test_agent_turns_predictions_into_tasks_and_scores_errors():
    agent = GoalOrientedAgent(5, seed=0)
    before = observation([0, 0, 1, 2, 0])
    task, error = agent.learn(before, 2, observation([0, 0, 1, 2, 0], (1, 0)))
    assert task == RED_TASK and error == 1.0  # nothing stored: predicted no change
    task, error = agent.learn(before, 3, observation([0, 0, 1, 2, 0], (0, 1)))
    assert task == GREEN_TASK
    assert error == pytest.approx(np.sqrt(2))  # predicted red (the only experience)
    assert agent.predicted_effects(before)[2] == (1, 0)


def test_greedy_agent_presses_the_button_whose_predicted_task_is_most_interesting():
    agent = GoalOrientedAgent(5, epsilon=0.0, seed=0)
    lights = [0, 0, 1, 2, 0]
    for button in (0, 1, 4):  # these do nothing, and the agent learns that
        agent.learn(observation(lights), button, observation(lights))
    agent.learn(observation(lights), 3, observation(lights, (0, 1)))  # green, seen once
    for boxes in [(1, 0), (1, 0)]:  # red surprises, then is predicted: progress 1
        agent.learn(observation(lights), 2, observation(lights, boxes))
    # Red was first predicted green (the newest experience nearby): error sqrt(2), then
    # 0, so progress sqrt(2). Green, seen once: half the mean of red and nothing (0).
    root2 = np.sqrt(2)
    assert agent.action_interests(observation(lights)) == pytest.approx(
        [0, 0, root2, 0.5 * root2 / 2, 0])
    assert {agent.select_action(observation(lights)) for _ in range(20)} == {2}


def test_ties_are_broken_at_random_and_epsilon_one_is_uniform():
    agent = GoalOrientedAgent(5, epsilon=0.0, seed=1)
    picks = np.bincount([agent.select_action(observation([0, 0, 1, 2, 0]))
                         for _ in range(500)], minlength=5)
    assert picks.min() > 60  # every button, about 100 times each
    explorer = GoalOrientedAgent(5, epsilon=1.0, seed=2)
    lights = [0, 0, 1, 2, 0]
    for button in (0, 1, 4):  # these do nothing, and the agent learns that
        explorer.learn(observation(lights), button, observation(lights))
    explorer.learn(observation(lights), 3, observation(lights, (0, 1)))  # green, once
    for boxes in [(1, 0), (1, 0)]:
        explorer.learn(observation(lights), 2, observation(lights, boxes))
    assert explorer.action_interests(observation(lights))[2] > max(
        np.delete(explorer.action_interests(observation(lights)), 2))  # red is the best
    # Counted over every button, pressed or not: red alone is the most interesting, yet
    # each of the five is pressed about 100 times in 500.
    picks = np.bincount([explorer.select_action(observation(lights)) for _ in range(500)],
                        minlength=5)
    assert picks.min() > 60


def test_agent_is_deterministic_per_seed():
    def choices(seed):
        agent = GoalOrientedAgent(5, epsilon=0.3, seed=seed)
        return [agent.select_action(observation([0, 0, 1, 2, 0])) for _ in range(50)]
    assert choices(4) == choices(4)
    assert choices(4) != choices(5)


@pytest.mark.parametrize("make, message", [
    (lambda: LearningProgressInterest(window=1), "window"),
    (lambda: LearningProgressInterest(window=2.5), "window"),
    (lambda: LearningProgressInterest(new_task_factor=1.5), "new_task_factor"),
    (lambda: LearningProgressInterest(new_task_factor=-0.1), "new_task_factor"),
    (lambda: LearningProgressInterest(reading="backwards"), "reading"),
    (lambda: NearestNeighbourPredictor(action_weight=0), "action_weight"),
    (lambda: NearestNeighbourPredictor(action_weight=float("nan")), "action_weight"),
    (lambda: GoalOrientedAgent(5, epsilon=1.1), "epsilon"),
    (lambda: GoalOrientedAgent(5, epsilon=-0.01), "epsilon"),
    (lambda: GoalOrientedAgent(5, epsilon="0.1"), "epsilon"),
    (lambda: GoalOrientedAgent(0), "n_actions"),
    (lambda: GoalOrientedAgent(5, seed=-1), "seed"),
    (lambda: LearningProgressInterest().record("t", -1.0), "error"),
])
def test_bad_arguments_raise_value_error_naming_the_argument(make, message):
    with pytest.raises(ValueError, match=message):
        make()


# --- the paper's published constants, each asserted as the paper prints it -----------------

def _batch():
    """A goal-oriented batch of one row with the library's settings."""
    return GoalOrientedBatch([0], np.zeros((1, 5)), buttons.EFFECTS, 5)


def _defaults(function, *names):
    """The default values of parameters `names` of `function`, in order.

    Args:
      function: a function or class.
      *names: parameter names.

    Returns:
      A list of the defaults.
    """
    parameters = inspect.signature(function).parameters
    return [parameters[name].default for name in names]


def test_the_window_is_the_papers_k_of_5():
    # Section 3.1: "d_t is the first derivative of the last k elements of H_t. In our
    # implementation, k was fixed at 5."
    assert DEFAULT_WINDOW == 5
    assert LearningProgressInterest().window == 5
    assert make_interest().window == 5
    # By behaviour: after errors 0, 1, 0, 0, 0, 0 the interest is the progress over the
    # last five (1, 0, 0, 0, 0), 0.2; a window of 4 would give 0, one of 6 gives 3/35.
    one, table = LearningProgressInterest(), InterestTable(1, 1)
    for error in [0, 1, 0, 0, 0, 0]:
        one.record("t", error)
        table.record(None, np.array([0]), np.array([float(error)]))
    assert one.interest("t") == pytest.approx(0.2)
    assert table.values()[0, 0] == pytest.approx(0.2)
    assert GoalOrientedSettings().window == 5 and interest.WINDOW.paper == 5
    assert _batch().interest.window.tolist() == [5]
    assert _defaults(icm.experiments.run_goal_oriented, "window") == [5]


def test_the_linear_predictors_rate_is_the_papers_0_2():
    # Section 4.2: "A linear predictor with a learning rate = 0.2 is used."
    assert DEFAULT_LINEAR_LR == 0.2
    predictor = LinearPredictor(4, 1)
    assert predictor.lr == 0.2
    # By behaviour: each topple moves the prediction a fifth of the way to 1.
    errors = [predictor.update(0, 0, [1.0]) for _ in range(3)]
    assert errors == pytest.approx([1.0, 0.8, 0.64])
    assert predictor.predict(0, 0)[0] == pytest.approx(1 - 0.8 ** 3)
    assert QLearner(15, 4).predictor.lr == 0.2
    assert QLearner.from_settings(15, 4, 2).predictor.lr == 0.2
    assert _defaults(icm.experiments.run_rod_toppling, "predictor_lr") == [0.2]
    assert predictors.LINEAR_LR.paper == 0.2


def test_a_new_task_gets_the_papers_50_percent_of_the_mean_interest():
    # Section 3.1: "The interest for new tasks (witnessed only one time) is fixed at 50%
    # of the average interest for other tasks."
    assert DEFAULT_NEW_TASK_FACTOR == 0.5
    assert LearningProgressInterest().new_task_factor == 0.5
    # By behaviour: known tasks of interest 0.2 and 1, a task seen once gets 0.3.
    one, table = LearningProgressInterest(), InterestTable(1, 3)
    for task, errors in ((0, [1, 0, 0, 0, 0]), (1, [1, 0]), (2, [1])):
        for error in errors:
            one.record(task, error)
            table.record(None, np.array([task]), np.array([float(error)]))
    assert [one.interest(task) for task in range(3)] == pytest.approx([0.2, 1.0, 0.3])
    assert table.values()[0] == pytest.approx([0.2, 1.0, 0.3])
    assert GoalOrientedSettings().new_task_factor == 0.5
    assert interest.NEW_TASK_FACTOR.paper == 0.5
    assert _batch().interest.factor.tolist() == [0.5]
    assert _defaults(icm.experiments.run_goal_oriented, "new_task_factor") == [0.5]
