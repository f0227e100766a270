"""The exercises' checks: each passes the book's solution, fails typical wrong answers
(a sign error, a window off by one, a forgotten edge case) naming the case and, where a
check judges several quantities, the first one wrong; refuses an answer that calls the
library's implementation or a reference; reports a placeholder as not implemented
yet, refuses a wrong argument, and never shows the reference's code; the references
agree with the library."""

import inspect
import math

import numpy as np
import pytest

from icm import _validate
from icm.exercises import (_core, actor_critic, buttons, curiosity_signal, goal_choice,
                           interest, motion, quiz, robustness, rods)
from icm.learners.interest import LearningProgressInterest, least_squares_slope


def _slope(values):
    x = np.arange(len(values), dtype=float)
    return float(np.polyfit(x, np.asarray(values, dtype=float), 1)[0])


# --- typical wrong answers, one function each ------------------------------------------

def slope_sign_error(values):
    return -_slope(values)


def slope_endpoints(values):  # the first and the last value only
    return (values[-1] - values[0]) / (len(values) - 1)


def slope_divided_by_n(values):  # a covariance, not a slope: grows with the window
    x = np.arange(len(values)) - (len(values) - 1) / 2
    return float(x @ (np.asarray(values) - np.mean(values)) / len(values))


def interest_sign_error(history, others, window, new_task_factor):
    if len(history) == 0:
        return 0.0
    if len(history) == 1:
        return new_task_factor * sum(others) / len(others) if others else 0.0
    return max(0.0, _slope(history[-window:]))  # the literal reading: errors going up


def interest_window_off_by_one(history, others, window, new_task_factor):
    if len(history) == 0:
        return 0.0
    if len(history) == 1:
        return new_task_factor * sum(others) / len(others) if others else 0.0
    return max(0.0, -_slope(history[-(window + 1):]))


def interest_forgets_new_task(history, others, window, new_task_factor):
    if len(history) < 2:  # "0 or one element: zero", the new-task rule forgotten
        return 0.0
    return max(0.0, -_slope(history[-window:]))


def interest_divides_by_zero(history, others, window, new_task_factor):
    if len(history) == 0:
        return 0.0
    if len(history) == 1:
        return new_task_factor * sum(others) / len(others)  # no known task: 0 / 0
    return max(0.0, -_slope(history[-window:]))


def outcome_swapped(lights, button):
    return (int(lights[button] == 2), int(lights[button] == 1))


def outcome_any_lit_opens_red(lights, button):
    return (int(lights[button] != 0), 0)


def outcome_off_opens_red(lights, button):  # right on every lit button
    return (int(lights[button] != 2), int(lights[button] == 2))


def _distance(c1, a1, c2, a2, weight):
    return sum(x != y for x, y in zip(c1, c2)) + (weight if a1 != a2 else 0.0)


def predict_first_of_ties(memory, context, action, action_weight, default):
    best, effect = math.inf, default
    for c, a, e in memory:
        d = _distance(c, a, context, action, action_weight)
        if d < best:  # the earliest wins a tie
            best, effect = d, e
    return effect


def predict_ignores_weight(memory, context, action, action_weight, default):
    best, effect = math.inf, default
    for c, a, e in memory:
        d = _distance(c, a, context, action, 1.0)
        if d <= best:
            best, effect = d, e
    return effect


def predict_empty_memory_crashes(memory, context, action, action_weight, default):
    distances = [_distance(c, a, context, action, action_weight) for c, a, _ in memory]
    best = max(i for i, d in enumerate(distances) if d == min(distances))
    return memory[best][2]


def jerk_smoothstep(fraction):
    return 3 * fraction ** 2 - 2 * fraction ** 3


def jerk_sign_error(fraction):
    return 10 * fraction ** 3 + 15 * fraction ** 4 + 6 * fraction ** 5


def softmax_overflows(preferences, temperature):
    weights = np.exp(np.asarray(preferences, dtype=float) / temperature)
    return (weights / weights.sum()).tolist()


def softmax_times_temperature(preferences, temperature):
    p = np.asarray(preferences, dtype=float) * temperature
    weights = np.exp(p - p.max())
    return (weights / weights.sum()).tolist()


def td_sign_error(critic, actor, state, action, reward, next_state, td_form, lr_actor,
                  lr_critic, gamma):
    v, v_next = critic.get(state, 0.0), critic.get(next_state, 0.0)
    td = reward + gamma * v - v_next if td_form == "standard" else \
        reward + gamma * (v - v_next)
    critic[state] = v + lr_critic * td
    actor[state][action] += lr_actor * td
    return td


def td_one_reading(critic, actor, state, action, reward, next_state, td_form, lr_actor,
                   lr_critic, gamma):
    v, v_next = critic.get(state, 0.0), critic.get(next_state, 0.0)
    td = reward + gamma * v_next - v  # td_form ignored
    critic[state] = v + lr_critic * td
    actor[state][action] += lr_actor * td
    return td


def td_unseen_state_crashes(critic, actor, state, action, reward, next_state, td_form,
                            lr_actor, lr_critic, gamma):
    td = reward + gamma * critic[next_state] - critic[state] if td_form == "standard" \
        else reward + gamma * (critic[state] - critic[next_state])
    critic[state] += lr_critic * td
    actor[state][action] += lr_actor * td
    return td


def q_step_error_after_update(q, predictions, state, action, observed, next_state, done,
                              alpha, gamma, lr):
    old = predictions.get((state, action), [0.0] * len(observed))
    new = [p + lr * (o - p) for o, p in zip(observed, old)]
    predictions[(state, action)] = new
    reward = sum(abs(o - p) for o, p in zip(observed, new))  # the error after learning
    target = reward if done else reward + gamma * max(q[next_state])
    q[state][action] += alpha * (target - q[state][action])
    return reward


def q_step_max_after_update(q, predictions, state, action, observed, next_state, done,
                            alpha, gamma, lr):
    old = predictions.get((state, action), [0.0] * len(observed))
    predictions[(state, action)] = [p + lr * (o - p) for o, p in zip(observed, old)]
    reward = sum(abs(o - p) for o, p in zip(observed, old))
    q[state][action] += alpha * (reward - q[state][action])  # Q(s, a) changed first,
    if not done:  # then max Q(s', .) read: with s' = s it may read the new Q(s, a)
        q[state][action] += alpha * gamma * max(q[next_state])
    return reward


def q_step_never_updates_q(q, predictions, state, action, observed, next_state, done,
                           alpha, gamma, lr):
    old = predictions.get((state, action), [0.0] * len(observed))
    predictions[(state, action)] = [p + lr * (o - p) for o, p in zip(observed, old)]
    return sum(abs(o - p) for o, p in zip(observed, old))


def q_step_bootstraps_at_the_end(q, predictions, state, action, observed, next_state, done,
                                 alpha, gamma, lr):
    old = predictions.get((state, action), [0.0] * len(observed))
    predictions[(state, action)] = [p + lr * (o - p) for o, p in zip(observed, old)]
    reward = sum(abs(o - p) for o, p in zip(observed, old))
    target = reward + gamma * max(q[next_state])  # done forgotten
    q[state][action] += alpha * (target - q[state][action])
    return reward


def confidence_untried_as_right(last_errors):
    return 1 - sum(0.0 if e is None else min(e, 1.0) for e in last_errors) / len(last_errors)


def confidence_uncapped(last_errors):
    return 1 - sum(1.0 if e is None else e for e in last_errors) / len(last_errors)


def red_first_ties_count(red, green):
    return red >= 1 and (green == -1 or red <= green)


def red_first_forgets_never(red, green):
    return red < green


def choose_greedy(interests, epsilon, rng):
    return int(np.argmax(interests))


def choose_without_epsilon(interests, epsilon, rng):
    values = np.asarray(interests, dtype=float)
    if values.sum() <= 0:
        return int(rng.integers(len(values)))
    return int(rng.choice(len(values), p=values / values.sum()))


def choose_divides_by_zero(interests, epsilon, rng):
    values = np.asarray(interests, dtype=float)
    if rng.random() < epsilon:
        return int(rng.integers(len(values)))
    return int(rng.choice(len(values), p=values / values.sum()))


def choose_returns_a_goal(interests, epsilon, rng):
    return rng.random(3)


def choose_half_epsilon(interests, epsilon, rng):  # explores half as often as it should
    return reference_goal_choice(interests, epsilon / 2, rng)


def choose_global_generator(interests, epsilon, rng):  # numpy's global state, not rng
    return reference_goal_choice(interests, epsilon, np.random.default_rng())


def signal_raw_slope(history):
    return -_slope(history) if len(history) >= 2 else 0.0  # negative when errors go up


def signal_last_error(history):
    return history[-1]  # an empty history: IndexError


def signal_sorts_in_place(history):
    history.sort()
    return float(sum(history[:2]))


def signal_random(history, _rng=np.random.default_rng(0)):
    return float(_rng.random())


def signal_recent_error(history):
    return float(np.mean(history[-5:])) if history else 1.0


def signal_constant(history):
    return 0.0


def signal_loves_noise(history):
    return history[-1] if history else 1.0  # the last error: a coin's stays high


def signal_mean_error(history):
    recent = history[-5:]
    return sum(recent) / len(recent) if recent else 1.0  # prediction error, written out


# --- the checks, their references and their wrong answers ------------------------------

CHECKS = {
    "least_squares_slope": (interest.check_least_squares_slope, least_squares_slope, [
        (slope_sign_error, "two values"),
        (slope_endpoints, "not on a line"),
        (slope_divided_by_n, "two values"),
    ]),
    "task_interest": (lambda f: interest.check_task_interest(f, experiment=False),
                      interest.reference_task_interest, [
        (interest_sign_error, "two elements, the error went down"),
        (interest_window_off_by_one, "more than k errors: only the last k count"),
        (interest_forgets_new_task, "one element: a new task gets half the mean"),
        (interest_divides_by_zero, "one element, no other known task"),
    ]),
    "press_outcome": (buttons.check_press_outcome, buttons.reference_press_outcome, [
        (outcome_swapped, "button 2 (lit red)"),
        (outcome_any_lit_opens_red, "(lit green)"),
        (outcome_off_opens_red, "(off)"),
    ]),
    "nearest_neighbour": (buttons.check_nearest_neighbour, buttons.reference_predict, [
        (predict_first_of_ties, "ties: two experiences at the same distance"),
        (predict_ignores_weight, "the same button under other lights, action weight 10"),
        (predict_empty_memory_crashes, "empty memory"),
    ]),
    "minimum_jerk": (motion.check_minimum_jerk, motion.reference_minimum_jerk, [
        (jerk_smoothstep, "a quarter of the time"),
        (jerk_sign_error, "the end: fraction 1"),
    ]),
    "softmax": (actor_critic.check_softmax, actor_critic.reference_softmax, [
        (softmax_overflows, "large preferences"),
        (softmax_times_temperature, "one preferred action"),
    ]),
    "td_update": (actor_critic.check_td_update, actor_critic.reference_td_update, [
        (td_sign_error, "standard form, both states valued"),
        (td_one_reading, "printed form, both states valued"),
        (td_unseen_state_crashes, "a state the critic has never valued"),
    ]),
    "q_learning_step": (rods.check_q_learning_step, rods.reference_q_learning_step, [
        (q_step_error_after_update, "an untried move topples the red rod"),
        (q_step_bootstraps_at_the_end, "the episode ended: no next value"),
        (q_step_max_after_update, "the next state is the state itself"),
        (q_step_never_updates_q, "an untried move topples the red rod"),
    ]),
    "state_confidence": (rods.check_state_confidence, rods.reference_state_confidence, [
        (confidence_untried_as_right, "a cell never visited"),
        (confidence_uncapped, "an error above 1"),
    ]),
    "red_first": (robustness.check_red_first, robustness.reference_red_first, [
        (red_first_ties_count, "ties: both at the same trial"),
        (red_first_forgets_never, "green never mastered"),
    ]),
    "goal_choice": (goal_choice.check_goal_choice, None, [
        (choose_greedy, "every interest 0"),
        (choose_without_epsilon, "epsilon 1: uniform"),
        (choose_divides_by_zero, "every interest 0"),
        (choose_returns_a_goal, "every interest 0"),
        (choose_half_epsilon, "epsilon 1: uniform"),
        (choose_global_generator, "the generator it is given"),
    ]),
    "curiosity_signal": (lambda f: curiosity_signal.check_curiosity_signal(f, experiment=False),
                         signal_recent_error, [
        (signal_raw_slope, "errors going up"),
        (signal_last_error, "empty history"),
        (signal_sorts_in_place, "two elements"),  # the first history it changes
        (signal_random, "empty history"),
        (signal_constant, "the same interest for every history"),
        (signal_loves_noise, "the noisy button, interest per button"),
        (signal_mean_error, "the noisy button, interest per button"),
    ]),
}


def reference_goal_choice(interests, epsilon, rng):
    """The rule as `run_goal_babbling` documents it."""
    values = np.asarray(interests, dtype=float)
    if rng.random() < epsilon or not values.sum() > 0:
        return int(rng.integers(len(values)))
    return int(rng.choice(len(values), p=values / values.sum()))


def _book_solutions():
    """The book's solutions of the implement exercises (the code under each one in the
    chapters' notebooks), as functions: the student's own code, which the checks take."""
    from icm.course.assign import chapter_exercises, chapters

    namespace = {"np": np}
    for _, path in chapters():
        for exercise in chapter_exercises(path):
            if exercise.kind == "implement":
                exec(exercise.solution, namespace)
    return namespace


SOLUTIONS = _book_solutions()
SOLUTION_OF = {"least_squares_slope": "least_squares_slope", "task_interest": "task_interest",
               "press_outcome": "press_outcome", "nearest_neighbour": "predict",
               "minimum_jerk": "minimum_jerk", "softmax": "softmax", "td_update": "td_update",
               "q_learning_step": "q_learning_step", "state_confidence": "state_confidence",
               "red_first": "red_first", "goal_choice": "choose_region",
               "curiosity_signal": "my_interest"}


def _reference(name):
    return SOLUTIONS[SOLUTION_OF[name]]


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_the_books_solution_passes(name):
    check = CHECKS[name][0]
    result = check(_reference(name))
    assert result.passed, repr(result)
    assert bool(result) is True
    assert "passed" in repr(result) and "passed" in result._repr_html_()


WRONG = [(name, wrong, case) for name, (_, _, wrongs) in CHECKS.items()
         for wrong, case in wrongs]


@pytest.mark.parametrize("name, wrong, case", WRONG,
                         ids=[f"{n}-{w.__name__}" for n, w, _ in WRONG])
def test_a_typical_wrong_answer_fails_naming_the_case(name, wrong, case):
    result = CHECKS[name][0](wrong)
    assert not result.passed and not bool(result)
    assert result.status == _core.FAILED
    assert case in result.case.name, (case, repr(result))
    report = repr(result)
    assert result.case.name in report
    for label in ("input:", "expected:", "given:", "hint:"):
        assert label in report, (label, report)
    assert result.hint and result.arguments
    html = result._repr_html_()
    assert "failed" in html and "<dt>hint</dt>" in html


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_each_check_has_at_least_two_wrong_answers(name):
    assert len(CHECKS[name][2]) >= 2


@pytest.mark.parametrize("name, wrong, case", WRONG,
                         ids=[f"{n}-{w.__name__}" for n, w, _ in WRONG])
def test_a_report_never_shows_the_reference_code(name, wrong, case):
    sources = [reference_goal_choice if name == "goal_choice" else CHECKS[name][1]]
    report = repr(CHECKS[name][0](wrong))
    for function in sources:
        for line in inspect.getsource(function).splitlines():
            line = line.strip()
            if len(line) > 20 and not line.startswith(("\"", "#", "Args", "Returns")):
                assert line not in report, line


def not_implemented(*args):
    raise NotImplementedError("write this function")


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_a_placeholder_is_not_implemented_yet_not_a_traceback(name):
    parameters = {"least_squares_slope": 1, "task_interest": 4, "press_outcome": 2,
                  "nearest_neighbour": 5, "minimum_jerk": 1, "softmax": 2, "td_update": 10,
                  "q_learning_step": 10, "state_confidence": 1, "red_first": 2,
                  "goal_choice": 3, "curiosity_signal": 1}[name]
    placeholder = eval("lambda " + ", ".join(f"a{i}" for i in range(parameters))
                       + ": not_implemented()")
    result = CHECKS[name][0](placeholder)
    assert result.status == _core.NOT_IMPLEMENTED and not result
    assert "not implemented yet" in repr(result)
    assert "Traceback" not in repr(result)


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_a_check_refuses_what_is_not_a_function(name):
    with pytest.raises(_validate.ArgumentTypeError) as raised:
        CHECKS[name][0](3.0)
    assert "must be a function" in str(raised.value)
    assert isinstance(raised.value, TypeError) and isinstance(raised.value, ValueError)


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_a_check_refuses_a_function_of_the_wrong_signature(name):
    with pytest.raises(TypeError) as raised:
        CHECKS[name][0](lambda a, b, c, d, e, f, g, h, i, j, k, extra: 0)
    assert "must take the arguments" in str(raised.value)
    assert "yours takes (a, b, c" in str(raised.value)


def test_a_failure_inside_the_student_code_is_reported_with_the_error():
    result = buttons.check_nearest_neighbour(predict_empty_memory_crashes)
    assert "ValueError" in repr(result) or "IndexError" in repr(result)
    assert "raised" in result.hint


def test_a_function_that_forgets_return_is_told_so():
    def forgets(values):
        _slope(values)
    result = interest.check_least_squares_slope(forgets)
    assert "did you forget `return`" in result.hint


def test_inputs_are_copied_so_a_function_that_changes_them_changes_nothing_else():
    def mutates(history, others, window, new_task_factor):
        answer = SOLUTIONS["task_interest"](list(history), list(others), window,
                                            new_task_factor)
        history.clear()
        others.clear()
        return answer
    assert interest.check_task_interest(mutates, experiment=False).passed


# --- the first quantity wrong, the generator, a constant -------------------------------

def test_the_hint_names_the_first_quantity_that_is_wrong():
    # A step that never updates Q has the right reward: the hint is about Q.
    never = rods.check_q_learning_step(q_step_never_updates_q)
    assert never.hint.startswith("Q is wrong (the reward and the prediction right).")
    assert "Equation 3" in never.hint and "predictor's error" not in never.hint
    # One whose reward is the error after learning: the hint is about the reward, even
    # on a case whose own hint is about Q.
    late = rods.check_q_learning_step(q_step_error_after_update)
    assert late.hint.startswith("The reward is wrong.") and "before it learns" in late.hint
    ended = rods.check_q_learning_step(q_step_bootstraps_at_the_end)
    assert ended.hint.startswith("Q is wrong") and "done" in ended.hint

    def q_step_prediction_not_learned(q, predictions, state, action, observed, next_state,
                                      done, alpha, gamma, lr):
        reward = SOLUTIONS["q_learning_step"](q, dict(predictions), state, action, observed,
                                              next_state, done, alpha, gamma, lr)
        return reward  # the prediction is left as it was
    unlearned = rods.check_q_learning_step(q_step_prediction_not_learned)
    assert unlearned.hint.startswith("The prediction is wrong (the reward right).")
    # The TD update: the TD error, then the critic, then the actor.
    td = actor_critic.check_td_update(td_sign_error)
    assert td.hint.startswith("The TD error is wrong.")

    def td_forgets_the_actor(critic, actor, state, action, reward, next_state, td_form,
                             lr_actor, lr_critic, gamma):
        return SOLUTIONS["td_update"](critic, {k: list(v) for k, v in actor.items()}, state,
                                      action, reward, next_state, td_form, lr_actor, lr_critic,
                                      gamma)
    actor_left = actor_critic.check_td_update(td_forgets_the_actor)
    assert actor_left.hint.startswith("The actor is wrong (the TD error and the critic right).")


def test_a_goal_choice_rule_must_draw_from_the_generator_it_is_given():
    result = goal_choice.check_goal_choice(choose_global_generator)
    assert result.case.name == goal_choice.GENERATOR
    assert "from `rng`" in result.hint and "global" in result.hint
    # A rule whose choices repeat whatever generator it is given.
    calls = []

    def ignores_rng(interests, epsilon, rng):
        calls.append(1)
        return reference_goal_choice(interests, epsilon,
                                     np.random.default_rng(len(calls) % goal_choice.SEQUENCE))
    cases = goal_choice.public_cases()
    names = [case.name for case in cases] + [goal_choice.GENERATOR]
    result = goal_choice._generator_verdict(ignores_rng, cases, names, 5)
    assert not result.passed and "whatever generator" in result.hint
    assert goal_choice._generator_verdict(reference_goal_choice, cases, names, 5).passed


def test_the_curiosity_check_refuses_a_constant_and_takes_a_signal_that_varies():
    for constant in (0.0, 1.0, 0.25):
        result = curiosity_signal.check_curiosity_signal(lambda history: constant, experiment=False)
        assert result.case.name == curiosity_signal.CONSTANT and "constant" in result.hint
    novelty = curiosity_signal.check_curiosity_signal(lambda history: 1.0 / (1 + len(history)),
                                              experiment=False)
    assert novelty.passed


# --- answers that are not the student's own ---------------------------------------------

def _calls(module, name):
    def call(*args):
        import importlib

        return getattr(importlib.import_module(module), name)(*args)
    return call


CHEATS = {
    "least_squares_slope": [_calls("icm.learners.interest", "least_squares_slope")],
    "task_interest": [_calls("icm.exercises.interest", "reference_task_interest"),
                      lambda h, o, w, f: 0.0 if not h else (f * sum(o) / len(o) if o else 0.0)
                      if len(h) == 1 else max(0.0, -_calls("icm.learners.interest",
                                                           "least_squares_slope")(h[-w:]))],
    "press_outcome": [_calls("icm.envs.buttons", "press_outcome"),
                      _calls("icm.exercises.buttons", "reference_press_outcome")],
    "nearest_neighbour": [_calls("icm.exercises.buttons", "reference_predict")],
    "minimum_jerk": [_calls("icm.envs.icub", "minimum_jerk")],
    "softmax": [_calls("icm.learners", "softmax")],
    "td_update": [_calls("icm.exercises.actor_critic", "reference_td_update")],
    "q_learning_step": [_calls("icm.exercises.rods", "reference_q_learning_step")],
    "state_confidence": [_calls("icm.exercises.rods", "reference_state_confidence")],
    "red_first": [_calls("icm.stats", "comes_first")],
    "goal_choice": [lambda i, e, r: _calls("icm.learners.goal_choice", "choose_region")(
        np.asarray(i, dtype=float), e, r)],
    "curiosity_signal": [lambda h: _calls("icm.learners.interest", "least_squares_slope")(h)
                         if len(h) > 1 else 0.0],
}


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_an_answer_that_calls_the_library_or_a_reference_is_not_the_students(name):
    assert CHEATS[name]
    for cheat in CHEATS[name]:
        result = CHECKS[name][0](cheat)
        assert not result.passed and result.borrowed is not None, repr(result)
        assert f"`{result.borrowed.name}`" in result.hint and "gets 0" in result.hint
        assert result.borrowed.name.startswith(("icm.learners", "icm.exercises", "icm.envs",
                                                "icm.stats"))


def test_an_answer_that_reads_the_checkers_frames_is_not_the_students():
    import inspect
    import sys

    def peeks(values):
        return sys._getframe(1).f_locals.get("expected")

    def stacks(values):
        return inspect.stack()[1].frame.f_locals.get("expected")

    def unwatches(values):
        sys.setprofile(None)
        return SOLUTIONS["least_squares_slope"](values)
    for cheat in (peeks, stacks, unwatches):
        result = interest.check_least_squares_slope(cheat)
        assert result.borrowed is not None and result.borrowed.why == "prying", repr(result)
    # The standard library's own use of frames (here, namedtuple) is not a student's.
    def uses_namedtuple(values):
        import collections

        collections.namedtuple("Point", "x y")
        return SOLUTIONS["least_squares_slope"](values)
    assert interest.check_least_squares_slope(uses_namedtuple).passed


def test_the_own_answer_watch_is_off_once_the_check_returns():
    import sys

    before = sys.getprofile()
    interest.check_least_squares_slope(CHEATS["least_squares_slope"][0])
    interest.check_least_squares_slope(SOLUTIONS["least_squares_slope"])
    assert sys.getprofile() is before


# --- the references are the library's --------------------------------------------------

def test_reference_task_interest_is_learning_progress_interest():
    rng = np.random.default_rng(0)
    for _ in range(50):
        window, factor = int(rng.integers(2, 7)), float(rng.choice([0.0, 0.5, 1.0]))
        module = LearningProgressInterest(window, factor)
        histories = {}
        for _ in range(int(rng.integers(1, 30))):
            task = int(rng.integers(4))
            error = float(rng.random())
            module.record(task, error)
            histories.setdefault(task, []).append(error)
        known = {t: interest.reference_task_interest(h, [], window, factor)
                 for t, h in histories.items() if len(h) >= 2}
        for task in range(5):
            history = histories.get(task, [])
            others = [known[t] for t in sorted(known) if t != task]
            assert interest.reference_task_interest(history, others, window, factor) == \
                pytest.approx(module.interest(task), abs=1e-12)


def test_function_interest_with_the_reference_gives_the_library_run():
    from icm.exercises._runs import run_goal_oriented_with
    from icm.experiments import run_goal_oriented

    mine = run_goal_oriented_with(
        lambda: interest.FunctionInterest(interest.reference_task_interest), 4, 20)
    library = run_goal_oriented(n_seeds=4, n_trials=20, seed=0, progress=False)
    np.testing.assert_allclose(mine.interest, library.interest, atol=1e-12)
    np.testing.assert_array_equal(mine.mastery_trial, library.mastery_trial)
    np.testing.assert_allclose(mine.button_share, library.button_share)
    np.testing.assert_allclose(mine.action_interest, library.action_interest, atol=1e-12)
    np.testing.assert_allclose(mine.prediction_error, library.prediction_error)


def test_reference_q_learning_step_is_the_q_learner():
    from icm.learners import LinearPredictor, QLearner

    rng = np.random.default_rng(1)
    learner = QLearner(6, 4, LinearPredictor(4, 2, lr=0.2), alpha=0.5, gamma=0.9,
                       initial_q=0.1, seed=0)
    q, predictions = [[0.1] * 4 for _ in range(6)], {}
    for _ in range(300):
        state, action, next_state = (int(v) for v in rng.integers(0, [6, 4, 6]))
        observed = [float(rng.integers(2)), 0.0]
        done = bool(rng.random() < 0.3)
        paid = learner.learn(state, action, observed, next_state, discount=0.0 if done else 1.0)
        mine = rods.reference_q_learning_step(q, predictions, state, action, observed,
                                              next_state, done, 0.5, 0.9, 0.2)
        assert mine == pytest.approx(paid, abs=1e-12)
    np.testing.assert_allclose(np.array(q), learner.q, atol=1e-12)


def test_reference_state_confidence_is_the_linear_predictors():
    from icm.learners import LinearPredictor

    rng = np.random.default_rng(2)
    predictor = LinearPredictor(4, 2, lr=0.2)
    last = {}
    for _ in range(200):
        state, action = int(rng.integers(5)), int(rng.integers(4))
        error = predictor.update(state, action, [float(rng.integers(2)), float(rng.integers(2))])
        last.setdefault(state, [None] * 4)[action] = error
    for state in range(6):
        errors = last.get(state, [None] * 4)
        assert rods.reference_state_confidence(errors) == pytest.approx(
            predictor.confidence(state), abs=1e-12)


def test_region_probabilities_are_the_goal_choice_of_goal_babbling():
    # The behaviour run_goal_babbling documents, measured on the function that makes
    # the choice there (it draws two numbers per choice).
    from icm.learners.goal_choice import choose_region as choose

    for values, epsilon in (([0.0, 0.0, 0.0], 0.3), ([0.1, 0.3, 0.6, 0.0], 0.3),
                            ([0.0, 1.0], 0.0), ([0.2, 0.2, 0.1], 1.0)):
        rng = np.random.default_rng(3)
        counts = np.bincount([choose(np.array(values), epsilon, rng) for _ in range(20000)],
                             minlength=len(values)) / 20000
        np.testing.assert_allclose(counts, goal_choice.region_probabilities(values, epsilon),
                                   atol=0.015)


def test_reference_td_update_is_the_actor_critics_learn_step():
    # ActorCritic.learn on a console observation, against the reference on the same
    # states and values.
    from icm.learners import ActorCritic

    for td_form, variant in (("standard", "standard"), ("printed", "printed_td")):
        learner = ActorCritic(3, variant=variant, reward="extrinsic", state_keys=("x",),
                              effect_key="y", seed=0)
        critic, actor = {}, {}
        rng = np.random.default_rng(4)
        for _ in range(50):
            s, s2, a = int(rng.integers(3)), int(rng.integers(3)), int(rng.integers(3))
            reward = float(rng.integers(2))
            _, td = learner.learn({"x": np.array([s]), "y": np.array([0])}, a,
                                  {"x": np.array([s2]), "y": np.array([0])}, reward)
            actor.setdefault((s,), [0.0] * 3)
            mine = actor_critic.reference_td_update(critic, actor, (s,), a, reward, (s2,),
                                                    td_form, 0.5, 0.5, 0.5)
            assert mine == pytest.approx(td, abs=1e-12)
        for state, value in learner.critic.items():
            assert critic[state] == pytest.approx(value, abs=1e-12)
            assert actor[state] == pytest.approx(learner.actor[state], abs=1e-12)


# --- the experiments the checks run ----------------------------------------------------

def test_check_task_interest_runs_your_figure5_beside_the_librarys():
    result = interest.check_task_interest(SOLUTIONS["task_interest"], n_seeds=3,
                                          n_trials=15)
    assert result.passed and result.figure is not None
    assert "Your Figure 5" in result.notes[0]
    assert '<img src="data:image/png;base64,' in result._repr_html_()
    assert interest.check_task_interest(interest_window_off_by_one).figure is None


def test_check_curiosity_signal_runs_the_learner_with_the_noisy_button():
    # (Was signal_recent_error, the mean of the last errors: a noise-loving signal,
    # which the check now refuses; issue 43.)
    result = curiosity_signal.check_curiosity_signal(SOLUTIONS["my_interest"], n_seeds=6,
                                             n_trials=30)
    assert result.passed and result.figure is not None
    assert "noisy button" in result.notes[0] and "interest per button" in result.notes[0]
    assert result.cases[-1] == curiosity_signal.NOISE_TRAP
    assert '<img src="data:image/png;base64,' in result._repr_html_()


def test_the_noise_case_refuses_a_noise_loving_signal_and_says_why():
    result = curiosity_signal.check_curiosity_signal(signal_loves_noise, experiment=False)
    assert not result.passed and result.case.name == curiosity_signal.NOISE_TRAP
    assert "drawn to the noise" in result.hint and "going down" in result.hint
    assert "learning progress" in result.expected and "per seed" in result.given
    trap = curiosity_signal.noise_trap(signal_loves_noise)
    mean, low, high = trap["difference"]
    assert trap["drawn"] and low > curiosity_signal.DRAWN_MARGIN and low <= mean <= high
    # The paper's own signal, written by a student, is not refused: it differs from
    # the library's learning progress only by chance.
    assert curiosity_signal.noise_trap(SOLUTIONS["my_interest"])["drawn"] is False
    assert curiosity_signal.check_curiosity_signal(SOLUTIONS["my_interest"], experiment=False)


def test_the_noise_case_runs_where_noise_can_trap():
    # Per task (the old check) the noise-loving signal passes: the noisy button has no
    # history of its own there. Per button it does not.
    from icm.exercises._runs import run_goal_oriented_with

    share = lambda run: run.button_share[:, :, 5].mean()
    per_task = run_goal_oriented_with(lambda: curiosity_signal.SignalInterest(signal_loves_noise),
                                      noisy_button=True)
    per_button = curiosity_signal.noise_trap(signal_loves_noise)["yours"]
    assert per_task.settings["interest_per"] == "task"
    assert per_button.settings["interest_per"] == "region"
    assert share(per_task) < 0.25 < share(per_button)


def test_the_signal_is_asked_once_per_history_and_the_run_is_the_same():
    from icm.exercises._runs import run_goal_oriented_with

    class AskedEveryTime(curiosity_signal.SignalInterest):
        def interest(self, task):
            return float(self.function(list(self.histories.get(task, []))))

    asked = []

    def counted(history):
        asked.append(tuple(history))
        return signal_loves_noise(history)

    settings = dict(n_seeds=3, n_trials=8, noisy_button=True, interest_per="region")
    kept = run_goal_oriented_with(lambda: curiosity_signal.SignalInterest(counted), **settings)
    calls, distinct = len(asked), len(set(asked))
    asked.clear()
    every = run_goal_oriented_with(lambda: AskedEveryTime(counted), **settings)
    assert distinct <= calls < len(asked)  # asked once per history of each run
    np.testing.assert_array_equal(kept.button_share, every.button_share)
    np.testing.assert_array_equal(kept.prediction_error, every.prediction_error)


def test_the_noise_case_fails_a_signal_that_breaks_on_a_history_the_learner_makes():
    # Passes the cases (none has 7 errors), then meets a history of 7 in the run.
    def breaks_at_seven(history):
        if len(history) == 7:
            raise IndexError("seven")
        return 1.0 / (1 + len(history))

    def nan_at_seven(history):
        return float("nan") if len(history) == 7 else 1.0 / (1 + len(history))

    for signal, given in ((breaks_at_seven, "seven"), (nan_at_seven, "nan")):
        result = curiosity_signal.check_curiosity_signal(signal, experiment=False)
        assert not result.passed and result.case.name == curiosity_signal.NOISE_TRAP
        assert given in repr(result.given).lower()


def test_a_hidden_test_runs_the_noise_case_on_seeds_of_its_own():
    rng = np.random.default_rng(5)
    hidden = curiosity_signal.hidden_signal_cases(rng)
    assert curiosity_signal._trap_root(None) == 0 != curiosity_signal._trap_root(hidden)
    result = curiosity_signal.check_curiosity_signal(signal_loves_noise, experiment=False,
                                             cases=hidden)
    assert not result.passed and result.case.name == curiosity_signal.NOISE_TRAP


def test_goal_oriented_runs_with_a_students_module_per_region_are_the_librarys():
    from icm.exercises._runs import run_goal_oriented_with
    from icm.experiments import run_goal_oriented
    from icm.learners.interest import make_interest

    for signal in ("prediction_error", "learning_progress"):
        mine = run_goal_oriented_with(lambda: make_interest(signal), 4, 20,
                                      noisy_button=True, interest_per="region")
        library = run_goal_oriented(n_seeds=4, n_trials=20, noisy_button=True,
                                    interest=signal, interest_per="region", seed=0,
                                    progress=False)
        np.testing.assert_array_equal(mine.mastery_trial, library.mastery_trial)
        np.testing.assert_allclose(mine.button_share, library.button_share)
        np.testing.assert_allclose(mine.interest, library.interest, atol=1e-12)
    with pytest.raises(ValueError, match="interest_per"):
        run_goal_oriented_with(lambda: make_interest(), 2, 2, interest_per="button")


def test_check_goal_choice_draws_the_shares_for_given_interests():
    result = goal_choice.check_goal_choice(reference_goal_choice,
                                           interests=[0.0, 0.1, 0.4, 0.0])
    assert result.passed and result.figure is not None
    with pytest.raises(ValueError, match="interests"):
        goal_choice.check_goal_choice(reference_goal_choice, interests=[-1.0, 0.5])
    with pytest.raises(ValueError, match="epsilon"):
        goal_choice.check_goal_choice(reference_goal_choice, epsilon=2.0)


def test_experiment_flag_must_be_a_bool():
    with pytest.raises(_validate.ArgumentTypeError, match="experiment"):
        interest.check_task_interest(SOLUTIONS["task_interest"], experiment="yes")


# --- the "predict, then check" options -------------------------------------------------

def test_option_for_picks_the_bin_of_a_value():
    assert [quiz.option_for(v, [0.5, 0.9]) for v in (0.1, 0.5, 0.89, 0.9, 1.0)] == \
        [0, 1, 1, 2, 2]
    with pytest.raises(ValueError, match="edges must increase"):
        quiz.option_for(0.5, [0.9, 0.5])
    with pytest.raises(ValueError, match="value"):
        quiz.option_for(float("nan"), [0.5])


def test_choices_render_labelled_radio_buttons_with_one_right_option():
    choices = quiz.Choices("epsilon-zero", ["under half", "half to 90%", "90% or more"], 2,
                           ["hint a", "hint b", "unused"])
    html = choices._repr_html_()
    assert html.count('type="radio"') == 3
    assert html.count('data-correct="true"') == 1
    assert '<label for="icm-quiz-epsilon-zero-2">90% or more</label>' in html
    assert "<legend>" in html and 'data-hint="hint a"' in html
    with pytest.raises(ValueError, match="correct"):
        quiz.Choices("x", ["a", "b"], 2, ["", ""])
    with pytest.raises(ValueError, match="hints"):
        quiz.Choices("x", ["a", "b"], 0, [""])
    with pytest.raises(ValueError, match="name"):
        quiz.Choices("Has Space", ["a", "b"], 0, ["", ""])
