"""The actor-critic (learner, experiment, figures, panel): hand-computed TD updates, a
stable softmax, and the paper's claims of section 4.1 on many seeds."""

import collections
import warnings

import matplotlib.figure
import numpy as np
import pytest

import icm
from icm import figures, stats
from icm.envs import buttons
from icm.experiments import run_actor_critic
from icm.experiments.actor_critic import probe_queries
from icm.learners import ActorCritic, softmax
from icm.learners import actor_critic

LIGHTS = (0, 0, 1, 2, 0)  # red at 2, green at 3
STATE = LIGHTS + (0, 0)  # boxes shut before the press
AFTER_RED = LIGHTS + (1, 0)


def observation(lights, boxes=(0, 0)):
    return collections.OrderedDict(lights=np.array(lights), boxes=np.array(boxes))


@pytest.fixture(scope="module")
def default_run():
    return run_actor_critic(n_seeds=120, n_trials=100, seed=0)


@pytest.fixture(scope="module")
def extrinsic_runs():
    return {box: run_actor_critic(n_seeds=120, n_trials=100, seed=0, reward="extrinsic",
                                  rewarded_box=box)
            for box in buttons.BOX_NAMES}


# --- softmax --------------------------------------------------------------------------

def test_softmax_sums_to_one_and_follows_the_temperature():
    rng = np.random.default_rng(0)
    for _ in range(50):
        p = softmax(rng.normal(scale=3, size=5), temperature=rng.uniform(0.01, 5))
        assert p.sum() == pytest.approx(1.0) and np.all(p >= 0)
    assert softmax([1.0, 0.0], 1.0) == pytest.approx([np.e / (1 + np.e), 1 / (1 + np.e)])
    assert softmax([1.0, 0.0], 0.5) == pytest.approx([np.e ** 2 / (1 + np.e ** 2),
                                                      1 / (1 + np.e ** 2)])
    assert softmax([3.0, 3.0, 3.0, 3.0], 0.1) == pytest.approx([0.25] * 4)


@pytest.mark.parametrize("preferences", [[1e6, 0.0, -1e6], [1e300, 1e300, -1e300],
                                         [-1e308, 1e308], [710.0, 0.0]])
@pytest.mark.parametrize("temperature", [1e-3, 1.0, 1e3])
def test_softmax_survives_huge_preferences_without_overflow(preferences, temperature):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an overflow warning would fail the test
        p = softmax(preferences, temperature)
    assert np.all(np.isfinite(p)) and p.sum() == pytest.approx(1.0)
    assert np.argmax(p) == np.argmax(preferences)


@pytest.mark.parametrize("preferences", [[], [0.0, np.nan], [np.inf, 0.0]])
def test_softmax_refuses_empty_or_non_finite_preferences(preferences):
    with pytest.raises(ValueError, match="preferences"):
        softmax(preferences, 1.0)


# --- one TD update by hand, for each variant ------------------------------------------

@pytest.mark.parametrize("variant, predicted_right, reward, td_error", [
    # V(s) = 0.4, V(s') = 0.2, gamma = 0.5.
    ("standard", False, 1.0, 1.0 + 0.5 * 0.2 - 0.4),          # 0.7
    ("standard", True, 0.0, 0.0 + 0.5 * 0.2 - 0.4),           # -0.3
    ("printed_td", False, 1.0, 1.0 + 0.5 * (0.4 - 0.2)),      # 1.1
    ("printed_td", True, 0.0, 0.0 + 0.5 * (0.4 - 0.2)),       # 0.1
    ("printed_reward", False, 0.0, 0.0 + 0.5 * 0.2 - 0.4),    # -0.3
    ("printed_reward", True, 1.0, 1.0 + 0.5 * 0.2 - 0.4),     # 0.7
    ("printed", False, 0.0, 0.0 + 0.5 * (0.4 - 0.2)),         # 0.1
    ("printed", True, 1.0, 1.0 + 0.5 * (0.4 - 0.2)),          # 1.1
])
def test_one_td_update_by_hand(variant, predicted_right, reward, td_error):
    agent = ActorCritic(5, lr_actor=0.5, lr_critic=0.25, gamma=0.5, variant=variant, seed=0)
    if predicted_right:
        agent.predictor.update(STATE, 2, (1, 0))  # it has seen red open the red box
    agent.critic[STATE], agent.critic[AFTER_RED] = 0.4, 0.2
    got_reward, got_td = agent.learn(observation(LIGHTS), 2, observation(LIGHTS, (1, 0)))
    assert got_reward == reward
    assert got_td == pytest.approx(td_error)
    assert agent.value(STATE) == pytest.approx(0.4 + 0.25 * td_error)
    assert agent.value(AFTER_RED) == 0.2  # only the state acted in is updated
    assert agent.preferences(STATE) == pytest.approx([0, 0, 0.5 * td_error, 0, 0])
    assert agent.predict(STATE, 2) == (1, 0)  # and the predictor has learned the press


def test_extrinsic_reward_comes_from_the_environment_and_ignores_the_predictor():
    agent = ActorCritic(5, lr_actor=0.5, lr_critic=0.25, gamma=0.5, reward="extrinsic")
    reward, td = agent.learn(observation(LIGHTS), 3, observation(LIGHTS, (0, 1)),
                             external_reward=1.0)
    assert reward == 1.0 and td == pytest.approx(1.0)
    reward, td = agent.learn(observation(LIGHTS), 0, observation(LIGHTS), external_reward=0.0)
    # V(s) is now 0.25 and s' = s: td = 0 + 0.5 * 0.25 - 0.25
    assert reward == 0.0 and td == pytest.approx(-0.125)


def test_discount_zero_ends_the_episode_in_both_td_forms():
    for variant in ("standard", "printed_td"):
        agent = ActorCritic(5, gamma=0.9, variant=variant)
        agent.critic[STATE], agent.critic[AFTER_RED] = 0.4, 0.2
        assert agent.td_error(1.0, STATE, AFTER_RED, discount=0.0) == pytest.approx(
            1.0 - 0.4 if variant == "standard" else 1.0)


def test_a_diverged_critic_raises_instead_of_returning_nan():
    agent = ActorCritic(5, gamma=1.0, variant="printed_td")
    agent.critic[STATE], agent.critic[AFTER_RED] = 1e308, -1e308
    with pytest.raises(FloatingPointError, match="diverged"):
        agent.td_error(0.0, STATE, AFTER_RED)


# --- the learner --------------------------------------------------------------------

def test_the_state_is_the_observation_lights_then_boxes():
    agent = ActorCritic(5)
    assert agent.state(observation(LIGHTS, (0, 1))) == LIGHTS + (0, 1)
    assert agent.policy(STATE) == pytest.approx([0.2] * 5)  # nothing learned: uniform


def test_a_surprise_makes_the_learner_repeat_the_surprising_press():
    agent = ActorCritic(5, seed=0)  # default variant: reward 1 on a wrong prediction
    reward, _ = agent.learn(observation(LIGHTS), 2, observation(LIGHTS, (1, 0)))
    assert reward == 1.0  # nothing stored: it predicted "no box", the red box opened
    p = agent.policy(STATE)
    expected = np.exp(actor_critic.DEFAULT_LR_ACTOR / actor_critic.DEFAULT_TEMPERATURE)
    assert p[2] / p[0] == pytest.approx(expected)
    picks = collections.Counter(agent.select_action(observation(LIGHTS)) for _ in range(2000))
    assert picks[2] / 2000 == pytest.approx(p[2], abs=0.03)
    reward, td = agent.learn(observation(LIGHTS), 2, observation(LIGHTS, (1, 0)))
    assert reward == 0.0 and td < 0  # no longer surprising: the press loses preference


def test_the_predictor_generalises_to_the_test_contexts_never_seen_in_training():
    # Section 4.1 tests with one button lit; training always lights two. The nearest
    # stored context with the same button differs by one light.
    queries = probe_queries()
    training = {tuple(l.tolist()) for l in buttons.layouts()}
    assert [q[0] for q in queries] == ["red"] + ["green"] * 4
    assert [q[2] for q in queries] == [2] + buttons.green_candidates(2)
    assert not {q[1][:5] for q in queries} & training
    agent = ActorCritic(5, seed=0)
    for lights in buttons.layouts():
        green = int(np.flatnonzero(lights == buttons.GREEN)[0])
        for button in (2, green, (green + 1) % 5 if (green + 1) % 5 != 2 else 0):
            agent.learn(observation(lights), button,
                        observation(lights, buttons.press_outcome(lights, button)))
    for _, state, button, truth in queries:
        assert agent.predict(state, button) == truth


def test_agent_is_deterministic_per_seed():
    def choices(seed):
        agent = ActorCritic(5, temperature=1.0, seed=seed)
        return [agent.select_action(observation(LIGHTS)) for _ in range(50)]
    assert choices(3) == choices(3)
    assert choices(3) != choices(4)


@pytest.mark.parametrize("kwargs, message", [
    (dict(n_actions=0), "n_actions"),
    (dict(temperature=0), "temperature"),
    (dict(temperature=float("inf")), "temperature"),
    (dict(lr_actor=0), "lr_actor"),
    (dict(lr_critic=1.5), "lr_critic"),
    (dict(gamma=-0.1), "gamma"),
    (dict(gamma=1.01), "gamma"),
    (dict(reward="both"), "reward"),
    (dict(variant="textbook"), "variant"),
    (dict(seed=-1), "seed"),
])
def test_bad_learner_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        ActorCritic(**{"n_actions": 5, **kwargs})


# --- the experiment -------------------------------------------------------------------

def test_result_arrays_have_the_documented_shapes(default_run):
    r = default_run
    assert r.prediction_error.shape == (120, 100, 2)
    assert r.zero_trial.shape == (120, 2)
    assert r.practice.shape == r.press_probability.shape == (120, 100, 2)
    assert r.reward.shape == r.max_abs_value.shape == (120, 100)
    assert np.all((0 <= r.prediction_error) & (r.prediction_error <= np.sqrt(2) + 1e-12))
    assert r.practice.sum(axis=2).max() <= r.settings["presses_per_trial"]


def test_zero_trial_is_where_the_error_reaches_zero_for_good(default_run):
    r = default_run
    for s in range(r.n_seeds):
        for task in range(2):
            z, errors = r.zero_trial[s, task], r.prediction_error[s, :, task]
            if z == -1:
                assert errors[-1] > 0
            else:
                assert np.all(errors[z - 1:] == 0) and (z == 1 or errors[z - 2] > 0)


def test_same_seed_gives_identical_arrays_and_other_seeds_differ():
    a = run_actor_critic(n_seeds=4, n_trials=20, seed=7)
    b = run_actor_critic(n_seeds=4, n_trials=20, seed=7)
    c = run_actor_critic(n_seeds=4, n_trials=20, seed=8)
    for name in ("prediction_error", "zero_trial", "practice", "press_probability",
                 "reward", "max_abs_value"):
        assert np.array_equal(getattr(a, name), getattr(b, name))
    assert not np.array_equal(a.practice, c.practice)
    few = run_actor_critic(n_seeds=2, n_trials=20, seed=7)
    assert np.array_equal(few.practice, a.practice[:2])


def test_paper_claim_red_error_reaches_zero_before_green(default_run):
    # Section 4.1 and Figure 6: red's prediction error vanishes first.
    assert default_run.n_seeds >= 100
    assert default_run.red_first_fraction() >= 0.9
    s = default_run.summary()
    assert s["red_zero_share"] == s["green_zero_share"] == 1.0  # both are learned
    assert s["red_zero_mean"] + 10 < s["green_zero_mean"]


def test_paper_claim_green_familiarity_is_sometimes_temporarily_above_red(default_run):
    # Discussion: "familiarity with the more complex task would temporarily increase
    # above the simple task", when green is met before red is ever pressed.
    r = default_run
    assert 0.2 < r.green_below_red_fraction() < 0.8
    below = r.green_below_red()
    for s in np.flatnonzero(below.any(axis=1)):
        assert np.flatnonzero(below[s]).max() + 1 < r.zero_trial[s, 0]  # only before red
    assert r.summary()["green_below_red_last_max"] <= 20  # and only early


def test_a_random_presser_learns_both_tasks_clearly_sooner():
    # The chapter's verdict, on seeds of its own: seed by seed, the trial from which each
    # error is zero for good, random presser minus curious learner, red and green
    # corrected together (Holm).
    curious = run_actor_critic(n_seeds=200, n_trials=100, seed=1)
    random_presser = run_actor_critic(n_seeds=200, n_trials=100, seed=1, temperature=1e9)
    gaps = {}
    for i, task in enumerate(("red", "green")):
        a, b = random_presser.zero_trial[:, i], curious.zero_trial[:, i]
        both = (a >= 1) & (b >= 1)
        assert both.sum() >= 190
        gaps[task] = (a[both] - b[both]).astype(float)
    verdicts = stats.corrected_verdicts(gaps)
    assert all(v["clear"] and v["mean"] < 0 for v in verdicts.values()), verdicts


def test_extrinsic_learner_prefers_its_rewarded_button(extrinsic_runs):
    for box, result in extrinsic_runs.items():
        task = ("red", "green").index(box)
        final = result.press_probability[:, -1, :]
        assert np.mean(final[:, task] > 0.5) >= 0.9
        assert np.mean(final[:, task] > final[:, 1 - task]) >= 0.95
        s = result.summary()
        assert s[f"{box}_late_practice_share"] > 0.8
        assert s[f"{'green' if box == 'red' else 'red'}_late_practice_share"] < 0.05


def test_extrinsic_learner_paid_for_red_does_not_learn_green(extrinsic_runs, default_run):
    # It learns only its rewarded box; the intrinsic learner learns both.
    assert extrinsic_runs["red"].summary()["green_zero_share"] < 0.6
    assert default_run.summary()["green_zero_share"] == 1.0


def test_printed_td_form_makes_the_critic_diverge(default_run):
    gamma = default_run.settings["gamma"]
    assert default_run.summary()["max_abs_value"] <= 1 / (1 - gamma)  # rewards in [0, 1]
    printed = run_actor_critic(n_seeds=120, n_trials=100, seed=0, variant="printed_td")
    assert printed.summary()["max_abs_value"] > 100 * (1 / (1 - gamma))


def test_printed_reward_avoids_the_green_task(default_run):
    # Paid for correct predictions, the learner presses what it can already predict.
    printed = run_actor_critic(n_seeds=120, n_trials=100, seed=0, variant="printed_reward")
    s = printed.summary()
    assert s["green_zero_share"] < 0.1 and s["late_reward_per_press"] > 0.95
    assert s["green_late_practice_share"] < 0.5 * default_run.summary()[
        "green_late_practice_share"]


@pytest.mark.parametrize("kwargs, message", [
    (dict(n_seeds=0), "n_seeds"),
    (dict(n_trials=0), "n_trials"),
    (dict(temperature=-1), "temperature"),
    (dict(lr_actor=2), "lr_actor"),
    (dict(lr_critic=0), "lr_critic"),
    (dict(gamma=1.5), "gamma"),
    (dict(reward="social"), "reward"),
    (dict(variant="sutton"), "variant"),
    (dict(rewarded_box="blue"), "rewarded_box"),
    (dict(action_weight=0), "action_weight"),
    (dict(presses_per_trial=0), "presses_per_trial"),
    (dict(red_button=5), "red_button"),
    (dict(seed=-1), "seed"),
    (dict(seed="zero"), "seed"),
    (dict(seed=2**63), "seed"),
])
def test_bad_run_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        run_actor_critic(**{"n_seeds": 2, "n_trials": 2, **kwargs})


def test_comparison_table_has_one_column_per_run(default_run):
    table = icm.chapters.actor_critic.comparison_table({"a": default_run, "b": default_run})
    lines = table.splitlines()
    assert lines[0] == "| measure | a | b |" and lines[1] == "|---|---|---|"
    assert lines[2] == "| seeds | 120 | 120 |"
    s = default_run.summary()
    assert f"| red first | {s['red_first']:.0%} | {s['red_first']:.0%} |" in lines
    assert all(line.count("|") == 4 for line in lines[:-2])
    assert lines[-2] == "" and lines[-1].startswith("†")  # the footnote


# --- figures and panel ----------------------------------------------------------------

def test_figure6_draws_each_seed_and_the_mean_with_a_band():
    small = run_actor_critic(n_seeds=6, n_trials=15, seed=1)
    fig = figures.figure6(small)
    assert isinstance(fig, matplotlib.figure.Figure)
    ax = fig.axes[0]
    means = [l for l in ax.get_lines() if l.get_label().startswith("only")]
    assert [l.get_label() for l in means] == ["only red lit, press it (mean)",
                                              "only green lit, press it (mean)"]
    for i, line in enumerate(means):
        assert np.allclose(line.get_ydata(), small.prediction_error[:, :, i].mean(axis=0))
    assert len(ax.get_lines()) == 2 * 6 + 2  # a thin line per seed and task, two means
    assert len(ax.collections) == 2  # one band per task
    assert fig.png()[:8] == b"\x89PNG\r\n\x1a\n"
    grid = figures.figure6_grid({"a": small, "b": small, "c": small})
    assert len([ax for ax in grid.axes if ax.get_lines()]) == 3
    assert len(figures.practice_figure({"a": small, "b": small}).axes) == 2


def test_figure3_draws_and_figure4_is_the_library_source_as_text():
    assert len(figures.figure3().axes) == 2
    listing = figures.figure4(name="fig-4")
    for line in ("def learn(self, observation, action, next_observation",
                 "self.critic[state] = self.value(state) + self.lr_critic * td_error",
                 "def td_error(self, reward, state, next_state, discount=1.0):"):
        assert line in listing.code
    assert '"""' not in listing.code  # docstrings are left out
    markdown = listing._repr_markdown_()
    assert markdown.startswith("````{code-block} python\n:caption: ActorCritic in")
    assert ":name: fig-4" in markdown and listing.code in markdown
    assert markdown.endswith("\n````")
    with pytest.raises(ValueError, match="methods"):
        figures.figure4(("fly",))




def test_the_paid_learner_settles_on_its_box_with_either_selection_rule():
    # Chapter 4: chosen epsilon-greedily (the paper's section 3.2) or by softmax (its
    # Figure 4), the learner paid for green settles on green; epsilon-greedy wanders more.
    runs = {rule: run_actor_critic(n_seeds=120, n_trials=100, seed=21, reward="extrinsic",
                                   rewarded_box="green", action_selection=rule,
                                   progress=False).summary()
            for rule in ("softmax", "epsilon_greedy")}
    for summary in runs.values():
        assert summary["green_late_practice_share"] > 0.6
        assert summary["green_late_practice_share"] > 3 * summary["red_late_practice_share"]
    assert runs["epsilon_greedy"]["green_late_practice_share"] < \
        runs["softmax"]["green_late_practice_share"] - 0.05


def test_the_paid_learner_learns_red_from_its_first_red_press_on_seeds_of_its_own():
    # Issue 44: "only because red is easy: a single chance press teaches the predictor
    # everything" was a causal claim with no check. The chapter now says what it
    # measures (icm.chapters.actor_critic.PAID_CLAIMS); here on seeds of their own.
    import dataclasses

    from icm import chapters
    paid = run_actor_critic(n_seeds=200, n_trials=100, seed=7, reward="extrinsic",
                            rewarded_box="green", progress=False)
    assert all(chapters.actor_critic.paid_claims(paid).values())
    found = chapters.actor_critic.red_from_first_press(paid)
    assert found["low"] >= 0.9 and found["first_median"] <= 10
    assert found["single"] <= found["from_first"] <= found["learned"] <= 200
    # A run whose red error fell to zero only a trial after its first red press fails.
    later = paid.zero_trial.copy()
    later[:, 0] = np.where(later[:, 0] >= 1, np.minimum(later[:, 0] + 1, 100), -1)
    late = dataclasses.replace(paid, zero_trial=later)
    assert not chapters.actor_critic.paid_claims(late)["red_from_first_red_press"]
    with pytest.raises(TypeError, match="result"):
        chapters.actor_critic.red_from_first_press("run")
