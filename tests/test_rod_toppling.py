"""The rod-toppling chapter: the linear predictor and the Q-learner by hand, the
experiment's arrays and determinism, the paper's claims on many seeds (section 4.2,
Figure 7), the figures and the panel."""

import matplotlib.figure
import numpy as np
import pytest

from icm import chapters, figures
from icm.envs import rods
from icm.experiments import rod_toppling
from icm.experiments.rod_toppling import RODS, run_rod_toppling
from icm.learners import LinearPredictor, QLearner


TEST_ROOT = 11
"""The tests' root seed: not the book's (0), so that the claims are checked on other
seeds than the ones the chapter shows."""


@pytest.fixture(scope="module")
def default_run():
    return run_rod_toppling(n_seeds=120, n_episodes=300, seed=TEST_ROOT, progress=False)


# --- The linear predictor -------------------------------------------------------------


def test_linear_predictor_update_by_hand():
    p = LinearPredictor(n_actions=4, n_outputs=2, lr=0.2)
    assert p.predict((2, 0), 0).tolist() == [0.0, 0.0]
    # First topple of red: error |1 - 0| + |0 - 0| = 1; prediction 0 + 0.2 * (1 - 0).
    assert p.update((2, 0), 0, [1, 0]) == pytest.approx(1.0)
    assert p.predict((2, 0), 0) == pytest.approx([0.2, 0.0])
    # Second: error 0.8; prediction 0.2 + 0.2 * 0.8 = 0.36.
    assert p.update_per_output((2, 0), 0, [1, 0]) == pytest.approx([0.8, 0.0])
    assert p.predict((2, 0), 0) == pytest.approx([0.36, 0.0])
    # The error of the n-th observation is 0.8^(n-1): below 0.1 from the 12th on.
    errors = [p.update((2, 0), 0, [1, 0]) for _ in range(10)]
    assert errors == pytest.approx([0.8 ** n for n in range(2, 12)])
    assert errors[-2] > 0.1 > errors[-1]
    # Other pairs and states are untouched.
    assert p.predict((2, 0), 1).tolist() == [0.0, 0.0]
    assert p.predict((0, 0), 0).tolist() == [0.0, 0.0]


def test_state_confidence_is_one_minus_the_mean_latest_error_untried_counting_one():
    p = LinearPredictor(n_actions=4, n_outputs=2, lr=0.2)
    assert p.confidence("cell") == 0.0  # never visited
    p.update("cell", 0, [1, 0])  # a surprise: error 1
    assert p.confidence("cell") == pytest.approx(0.0)
    p.update("cell", 1, [0, 0])  # predicted right: error 0
    assert p.confidence("cell") == pytest.approx(1 - (1 + 0 + 1 + 1) / 4)
    p.update("cell", 2, [0, 0])
    p.update("cell", 3, [0, 0])
    assert p.confidence("cell") == pytest.approx(1 - 1 / 4)
    p.update("cell", 0, [1, 0])  # the latest error there is now 0.8
    assert p.last_error("cell", 0) == pytest.approx(0.8)
    assert p.confidence("cell") == pytest.approx(1 - 0.8 / 4)


def test_linear_predictor_table_holds_every_prediction():
    p = LinearPredictor(n_actions=4, n_outputs=2, lr=0.5)
    p.update(3, 2, [0, 1])
    table = p.table([0, 3])
    assert table.shape == (2, 4, 2)
    assert table[1, 2].tolist() == [0.0, 0.5]
    assert table.sum() == 0.5


# --- The Q-learner --------------------------------------------------------------------


def test_q_update_by_hand():
    q = QLearner(n_states=3, n_actions=2, alpha=0.5, gamma=0.9, initial_q=0.1, seed=0)
    # Equation 3: Q <- Q + alpha [r + gamma max_a Q(s', a) - Q]
    #           = 0.1 + 0.5 * (1 + 0.9 * 0.1 - 0.1) = 0.595.
    td = q.update(0, 1, 1.0, next_state=1)
    assert td == pytest.approx(0.99)
    assert q.q[0, 1] == pytest.approx(0.595)
    # From state 2 into state 0, where the best value is now 0.595:
    #   0.1 + 0.5 * (0 + 0.9 * 0.595 - 0.1) = 0.31775.
    q.update(2, 0, 0.0, next_state=0)
    assert q.q[2, 0] == pytest.approx(0.31775)
    # A topple ends the episode (discount 0): nothing follows, the target is r alone.
    q.update(1, 0, 0.8, next_state=0, discount=0.0)
    assert q.q[1, 0] == pytest.approx(0.1 + 0.5 * (0.8 - 0.1))
    # Everything else keeps its initial value.
    assert q.q[1, 1] == q.q[2, 1] == pytest.approx(0.1)


def test_learn_pays_the_predictors_surprise_then_teaches_it():
    predictor = LinearPredictor(4, 2, lr=0.2)
    q = QLearner(15, 4, predictor, alpha=1.0, gamma=0.9, initial_q=0.0, seed=0)
    reward = q.learn(2, 0, [1, 0], next_state=7, discount=0.0)
    assert reward == pytest.approx(1.0)
    assert q.q[2, 0] == pytest.approx(1.0)  # alpha 1, terminal: Q = r
    reward = q.learn(2, 0, [1, 0], next_state=7, discount=0.0)
    assert reward == pytest.approx(0.8)
    assert q.q[2, 0] == pytest.approx(0.8)
    assert q.learn(1, 3, [0, 0], next_state=2) == 0.0  # predicted right: no reward
    assert q.q[1, 3] == pytest.approx(0.9 * 0.8)  # but the way to the surprise is worth


def test_epsilon_greedy_picks_the_best_and_breaks_ties_at_random():
    q = QLearner(2, 4, epsilon=0.0, initial_q=0.0, seed=1)
    q.update(0, 2, 1.0, next_state=1, discount=0.0)
    assert {q.select_action(0) for _ in range(50)} == {2}
    counts = np.bincount([q.select_action(1) for _ in range(4000)], minlength=4)
    assert np.all(np.abs(counts / 4000 - 0.25) < 0.03)  # a four-way tie
    explorer = QLearner(2, 4, epsilon=1.0, initial_q=0.0, seed=1)
    explorer.update(0, 2, 1.0, next_state=1, discount=0.0)
    counts = np.bincount([explorer.select_action(0) for _ in range(4000)], minlength=4)
    assert np.all(np.abs(counts / 4000 - 0.25) < 0.03)


def test_q_learner_accepts_a_generator_and_is_deterministic_per_seed():
    a = QLearner(5, 4, seed=np.random.default_rng(3))
    b = QLearner(5, 4, seed=np.random.default_rng(3))
    moves = [(a.select_action(i % 5), b.select_action(i % 5)) for i in range(30)]
    assert all(x == y for x, y in moves)


@pytest.mark.parametrize("kwargs, message", [
    (dict(n_states=0), "n_states"),
    (dict(n_actions=0), "n_actions"),
    (dict(alpha=0.0), "alpha"),
    (dict(alpha=1.5), "alpha"),
    (dict(gamma=1.1), "gamma"),
    (dict(epsilon=-0.1), "epsilon"),
    (dict(initial_q=-1.0), "initial_q"),
    (dict(initial_q=float("nan")), "initial_q"),
    (dict(seed=-3), "seed"),
])
def test_bad_q_learner_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        QLearner(**{"n_states": 4, "n_actions": 2, **kwargs})


@pytest.mark.parametrize("call, message", [
    (lambda q: q.update(9, 0, 1.0, 0), "state"),
    (lambda q: q.update(0, 5, 1.0, 0), "action"),
    (lambda q: q.update(0, 0, float("nan"), 0), "reward"),
    (lambda q: q.update(0, 0, 1.0, 0, discount=2.0), "discount"),
    (lambda q: q.update(0, 0, 1.0, -1), "next_state"),
    (lambda q: q.select_action(4), "state"),
    (lambda q: q.learn(0, 0, [1, 0, 0], 1), "observed"),
])
def test_bad_q_learner_calls_raise_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call(QLearner(4, 2, LinearPredictor(2, 2)))


@pytest.mark.parametrize("kwargs, message", [
    (dict(n_actions=0), "n_actions"),
    (dict(n_outputs=0), "n_outputs"),
    (dict(lr=0.0), "lr"),
    (dict(lr=2.0), "lr"),
    (dict(initial_prediction=1.5), "initial_prediction"),
])
def test_bad_linear_predictor_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        LinearPredictor(**{"n_actions": 4, "n_outputs": 2, **kwargs})


# --- The experiment -------------------------------------------------------------------


def test_result_arrays_have_the_documented_shapes(default_run):
    r = default_run
    n, e, k = 120, 300, len(r.snapshot_names)
    assert r.toppled.shape == r.episode_length.shape == (n, e)
    assert r.prediction_error.shape == r.rod_error.shape == r.rod_error_toppled.shape == (n, e, 2)
    assert r.predicted_well.shape == r.predicted_well_toppled.shape == (n, 2)
    assert r.snapshot_episode.shape == (n, k) and r.snapshot_names == rod_toppling.MOMENTS
    assert r.q_table.shape == (n, k, 5, 3, 4)
    assert r.predictions.shape == (n, k, 5, 3, 4, 2)
    assert r.confidence.shape == (n, k, 5, 3)
    assert set(np.unique(r.toppled)) <= {-1, 0, 1}
    assert np.all((1 <= r.episode_length) & (r.episode_length <= rods.DEFAULT_MAX_MOVES))
    # Time limits only: an episode without a topple lasts max_moves.
    assert np.all(r.episode_length[r.toppled == -1] == rods.DEFAULT_MAX_MOVES)
    # The hand never rests where the rods stand: NaN there, numbers elsewhere.
    unstandable = {(c, rr) for c in range(5) for rr in range(3)} - rods.load_topple_map()["standable"]
    assert len(unstandable) == 3
    for cell in unstandable:
        assert np.all(np.isnan(r.q_table[:, :, cell[0], cell[1]]))
    assert not np.any(np.isnan(r.q_table[:, 0, 0, 0]))
    assert np.all((0 <= r.prediction_error) & (r.prediction_error <= 1))


def test_errors_paid_are_the_surprise_of_the_topple(default_run):
    r = default_run
    # On the tabular rods a move that topples nothing is predicted right from the start
    # (prediction 0, outcome 0): all the error of an episode is its last move's.
    red = r.prediction_error[..., 0]
    blue = r.prediction_error[..., 1]
    assert np.all(red[r.toppled != 0] == 0) and np.all(blue[r.toppled != 1] == 0)
    assert np.all(red[r.toppled == 0] > 0)
    # The first topple of the run is always a full surprise.
    for s in range(r.n_seeds):
        first = np.flatnonzero(r.toppled[s] >= 0)[0]
        assert r.prediction_error[s, first].sum() == pytest.approx(1.0)


def test_predicted_well_is_where_the_rod_error_falls_below_a_tenth_for_good(default_run):
    r = default_run
    for s in range(r.n_seeds):
        for rod in range(2):
            well, errors = r.predicted_well[s, rod], r.rod_error[s, :, rod]
            if well == -1:
                assert errors[-1] >= 0.1
            else:
                assert np.all(errors[well - 1:] < 0.1)
                assert well == 1 or errors[well - 2] >= 0.1
            first = r.predicted_well_toppled[s, rod]
            known = r.rod_error_toppled[s, :, rod]
            if first != -1:
                assert known[first - 1] < 0.1
                assert not np.any(known[:first - 1] < 0.1)


def test_moments_are_found_from_the_data(default_run):
    r = default_run
    names = list(r.snapshot_names)
    assert np.all(r.snapshot_episode[:, names.index("first episode")] == 1)
    assert np.array_equal(r.snapshot_episode[:, names.index("red predicted well")],
                          r.predicted_well[:, 0])
    assert np.array_equal(r.snapshot_episode[:, names.index("red predicted well (toppled)")],
                          r.predicted_well_toppled[:, 0])
    assert np.array_equal(r.snapshot_episode[:, names.index("blue begins")],
                          r.first_topple("blue"))
    # After the first episode exactly one pair has been learned from (if it toppled).
    snap = r.snapshot(0, "first episode")
    changed = np.nansum(snap["predictions"] > 0)
    assert changed == (1 if r.toppled[0, 0] >= 0 else 0)


def test_snapshots_match_a_shorter_run_of_the_same_seed():
    long = run_rod_toppling(n_seeds=2, n_episodes=40, snapshot_episodes=(12,), seed=5,
                            progress=False)
    short = run_rod_toppling(n_seeds=2, n_episodes=12, snapshot_episodes=(12,), seed=5,
                             progress=False)
    k = long.snapshot_names.index("episode 12")
    for name in ("q_table", "predictions", "confidence"):
        assert np.array_equal(getattr(long, name)[:, k], getattr(short, name)[:, k],
                              equal_nan=True)
    assert np.array_equal(long.toppled[:, :12], short.toppled)


def test_same_seed_gives_identical_arrays_and_other_seeds_differ():
    a = run_rod_toppling(n_seeds=4, n_episodes=80, seed=11, progress=False)
    b = run_rod_toppling(n_seeds=4, n_episodes=80, seed=11, progress=False)
    c = run_rod_toppling(n_seeds=4, n_episodes=80, seed=12, progress=False)
    for name in ("toppled", "episode_length", "prediction_error", "rod_error",
                 "predicted_well", "snapshot_episode", "q_table", "predictions", "confidence"):
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name
    assert not np.array_equal(a.episode_length, c.episode_length)


def test_fewer_seeds_are_the_first_runs_of_more_seeds():
    few = run_rod_toppling(n_seeds=2, n_episodes=50, seed=4, progress=False)
    many = run_rod_toppling(n_seeds=5, n_episodes=50, seed=4, progress=False)
    assert np.array_equal(few.toppled, many.toppled[:2])


def test_the_physics_run_makes_the_same_episodes_as_the_tabular_twin():
    # The stored topple map was measured in physics; the same seeds make the same
    # choices, so the episodes agree move for move.
    physics = run_rod_toppling(n_seeds=1, n_episodes=6, physics=True, seed=2, progress=False)
    tabular = run_rod_toppling(n_seeds=1, n_episodes=6, physics=False, seed=2, progress=False)
    assert np.array_equal(physics.toppled, tabular.toppled)
    assert np.array_equal(physics.episode_length, tabular.episode_length)
    assert np.allclose(physics.q_table, tabular.q_table, equal_nan=True)


# --- The paper's claims ---------------------------------------------------------------


def test_paper_claim_red_is_predicted_well_before_blue(default_run):
    # Section 4.2 and Figure 7: the robot learns the easy red rod first, then the blue
    # one. Reading "toppled" (the pairs the robot has toppled each rod from): red first
    # in at least 90% of seeds.
    assert default_run.n_seeds >= 100
    assert default_run.red_first_fraction("toppled") >= 0.9


def test_issue_claim_red_is_predicted_well_on_every_pair_before_blue(default_run):
    # The issue's reading: the predictor's error on *every* pair that topples the rod
    # (in the measured map) stays below 0.1. Red first in at least 90% of seeds.
    assert default_run.red_first_fraction("all") >= 0.9


def test_paper_claim_interest_shifts_from_red_to_blue(default_run):
    # Figure 7: (a) the red rod is more interesting, (b) it gets boring, (c) the robot
    # turns to blue. The share of episodes ending with blue toppled is larger in the
    # second half of training than in the first ten episodes.
    r = default_run
    early = r.topple_share("blue", slice(0, 10))
    late = r.topple_share("blue", slice(r.n_episodes // 2, None))
    assert late > early
    assert late > 0.1 > early
    # ...and the first topple is nearly always red, the first blue one comes much later.
    s = r.summary()
    assert s["red_toppled_first"] >= 0.9
    assert s["first_blue_median"] >= 20 * s["first_red_median"]


def test_red_gets_boring_the_robot_turns_to_blue_after_it_learned_red(default_run):
    # Figure 7's order: red predicted well (toppled reading) before blue is first
    # toppled, in most seeds.
    assert default_run.red_before_blue_begins("toppled") >= 0.5


def test_the_value_of_untried_moves_decides_the_story():
    # initial_q = 0: every untried move is worth 0, less than any leftover error, so the
    # robot keeps toppling the red pairs it knows and seldom finds blue. initial_q = 1:
    # everything new beats any rod, the robot meets blue early and red loses its lead.
    runs = {q0: run_rod_toppling(n_seeds=100, n_episodes=100, initial_q=q0, seed=0,
                                 progress=False) for q0 in (0.0, 0.1, 1.0)}
    found_blue = {q0: np.mean(r.first_topple("blue") >= 1) for q0, r in runs.items()}
    assert found_blue[0.0] < 0.5 < 0.95 <= found_blue[0.1]
    assert runs[1.0].summary()["first_blue_median"] < 20 < runs[0.1].summary()["first_blue_median"]
    red_first = {q0: r.red_first_fraction("toppled") for q0, r in runs.items()}
    assert red_first[1.0] < 0.8 < 0.9 <= red_first[0.1]


def test_the_chapters_claims_hold_on_the_tests_seeds(default_run):
    claims = chapters.rod_toppling.claims(default_run)
    assert set(claims) == set(chapters.rod_toppling.CLAIMS)
    assert all(claims.values()), claims
    runs = [run_rod_toppling(n_seeds=60, n_episodes=300, initial_q=q0, seed=TEST_ROOT,
                             progress=False) for q0 in (0.0, 1.0)]
    claims = chapters.rod_toppling.initial_q_claims(default_run, *runs)
    assert set(claims) == set(chapters.rod_toppling.INITIAL_Q_CLAIMS)
    assert all(claims.values()), claims


def test_the_chapters_claims_fail_on_runs_that_contradict_them(default_run):
    import dataclasses

    # The rods swapped: blue is toppled, and learned, first.
    red, blue = RODS.index("red"), RODS.index("blue")
    toppled = default_run.toppled.copy()
    toppled[default_run.toppled == red], toppled[default_run.toppled == blue] = blue, red
    swapped = dataclasses.replace(
        default_run, toppled=toppled,
        predicted_well=default_run.predicted_well[:, ::-1].copy(),
        predicted_well_toppled=default_run.predicted_well_toppled[:, ::-1].copy())
    claims = chapters.rod_toppling.claims(swapped)
    assert not any(claims.values()), claims
    # The initial Q runs given in the wrong roles: refused; the same run thrice: no claim.
    low = dataclasses.replace(default_run, settings={**default_run.settings, "initial_q": 0.0})
    high = dataclasses.replace(default_run, settings={**default_run.settings, "initial_q": 1.0})
    with pytest.raises(ValueError, match="initial_q must rise"):
        chapters.rod_toppling.initial_q_claims(default_run, high, low)
    with pytest.raises(TypeError, match="untried_worth_nothing"):
        chapters.rod_toppling.initial_q_claims(default_run, "run", high)
    assert not any(chapters.rod_toppling.initial_q_claims(default_run, low, high).values())
    # Red never learned on every pair, but blue met as early: the robot did not stay.
    never = default_run.predicted_well.copy()
    never[:, red] = -1
    unlearned = dataclasses.replace(low, predicted_well=never)
    assert not chapters.rod_toppling.initial_q_claims(
        default_run, unlearned, high)["low_stays_with_red"]


def test_summary_holds_the_numbers_the_book_quotes(default_run):
    s = default_run.summary()
    for key in ("red_well_median", "blue_well_median", "first_blue_median", "red_first",
                "red_first_toppled", "red_well_median_toppled", "blue_well_median_toppled",
                "blue_share_first_10", "blue_share_second_half"):
        assert np.isfinite(s[key]), key
    assert s["red_well_median_toppled"] < s["first_blue_median"] < s["blue_well_median_toppled"]
    assert 0 <= s["red_first"] <= 1


@pytest.mark.parametrize("kwargs, message", [
    (dict(n_seeds=0), "n_seeds"),
    (dict(n_episodes=0), "n_episodes"),
    (dict(epsilon=2), "epsilon"),
    (dict(alpha=0), "alpha"),
    (dict(gamma=-0.5), "gamma"),
    (dict(predictor_lr=1.5), "predictor_lr"),
    (dict(initial_q=-1), "initial_q"),
    (dict(physics="yes"), "physics"),
    (dict(start_cell=(2, 1)), "start_cell"),
    (dict(start_cell=(7, 0)), "start_cell"),
    (dict(max_moves=0), "max_moves"),
    (dict(snapshot_episodes=(0,)), "snapshot_episodes"),
    (dict(snapshot_episodes=(3,)), "snapshot_episodes"),  # beyond n_episodes=2
    (dict(snapshot_episodes=5), "snapshot_episodes"),
    (dict(seed=-5), "seed"),
    (dict(seed="zero"), "seed"),
    (dict(seed=2**63), "seed"),
    (dict(progress="yes"), "progress"),
])
def test_bad_run_arguments_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        run_rod_toppling(**{"n_seeds": 2, "n_episodes": 2, **kwargs})


def test_bad_result_queries_raise_value_error(default_run):
    with pytest.raises(ValueError, match="reading"):
        default_run.red_first_fraction("some")
    with pytest.raises(ValueError, match="rod"):
        default_run.first_topple("green")
    with pytest.raises(ValueError, match="seed"):
        default_run.snapshot(500, "first episode")
    with pytest.raises(ValueError, match="name"):
        default_run.snapshot(0, "episode 7")


# --- Figures and the panel ------------------------------------------------------------


def test_figure7_draws_the_three_moments(default_run):
    fig = figures.figure7(default_run, seed=0)
    assert isinstance(fig, matplotlib.figure.Figure)
    grid_axes = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert len(grid_axes) == 12  # 4 rows x 3 moments
    titles = [ax.get_title() for ax in grid_axes[:3]]
    assert [t[:3] for t in titles] == ["(a)", "(b)", "(c)"]
    episodes = default_run.snapshot_episode[0]
    assert f"episode {episodes[1]}" in titles[1] and f"episode {episodes[3]}" in titles[2]
    assert fig.png()[:8] == b"\x89PNG\r\n\x1a\n"


def test_figure7_q_table_arrows_point_along_the_greedy_moves(default_run):
    fig, ax = figures.new_figure()
    snap = default_run.snapshot(0, "red predicted well (toppled)")
    from icm.figures.rod_toppling import draw_q_table
    draw_q_table(ax, snap["q_table"])
    arrows = [child for child in ax.texts if child.arrow_patch is not None]
    q = snap["q_table"]
    expected = 0
    for column in range(5):
        for row in range(3):
            values = q[column, row]
            if not np.any(np.isnan(values)) and np.ptp(values) > 0:
                expected += 1
    assert len(arrows) == expected
    for arrow in arrows:
        (x0, y0), (x1, y1) = arrow.xyann, arrow.xy
        best = int(np.argmax(q[int(round(x0)), int(round(y0))]))
        dx, dy = np.sign(x1 - x0), np.sign(y1 - y0)
        assert (dx, dy) == {0: (0, 1), 1: (0, -1), 2: (-1, 0), 3: (1, 0)}[best]


def test_figure7_with_an_extra_episode_and_bad_arguments():
    r = run_rod_toppling(n_seeds=2, n_episodes=30, snapshot_episodes=(20,), progress=False)
    fig = figures.figure7(r, seed=1, reading="toppled", episode=20)
    grid_axes = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert len(grid_axes) == 16
    with pytest.raises(ValueError, match="episode"):
        figures.figure7(r, episode=21)
    with pytest.raises(ValueError, match="seed"):
        figures.figure7(r, seed=2)
    with pytest.raises(ValueError, match="reading"):
        figures.figure7(r, reading="most")


def test_topple_share_figure_draws_the_mean_share_of_each_rod(default_run):
    fig = figures.topple_share_figure(default_run)
    left = fig.axes[0]
    lines = {line.get_label(): line for line in left.get_lines()}
    for i, rod in enumerate(RODS):
        line = lines[f"{rod} rod toppled"]
        assert np.allclose(line.get_ydata(), (default_run.toppled == i).mean(axis=0))
    assert len(left.collections) == 3  # a 95% band per curve


def test_physics_comparison_figure_has_a_row_per_run(default_run):
    fig = figures.physics_comparison_figure({"a": default_run, "b": default_run})
    assert len(fig.axes) == 2
    assert len(fig.axes[0].patches) == default_run.n_episodes


def test_first_run_gives_run_k_of_a_larger_batch_alone():
    batch = run_rod_toppling(n_seeds=4, n_episodes=30, seed=6, progress=False)
    alone = run_rod_toppling(n_seeds=1, n_episodes=30, seed=6, first_run=3, progress=False)
    for name in ("toppled", "episode_length", "prediction_error", "q_table"):
        np.testing.assert_array_equal(getattr(alone, name)[0], getattr(batch, name)[3])


def test_the_run_figure7_shows_is_chosen_by_a_rule_and_described_in_its_order(default_run):
    story = default_run.tells_the_papers_story("toppled")
    order = default_run.in_paper_order("toppled")
    assert order.mean() == default_run.red_before_blue_begins("toppled")
    assert 0 < story.mean() < 1  # not every run tells it: the chapter says how many do
    shown = default_run.first_telling_the_story("toppled")
    assert story[shown] and not story[:shown].any()
    assert default_run.toppled[shown, 0] == 0  # (a): the first episode toppled red
    for run in range(default_run.n_seeds):
        text = chapters.rod_toppling.describe_order(default_run, run, "toppled")
        red = default_run.predicted_well_toppled[run, 0]
        blue = default_run.first_topple("blue")[run]
        assert (f"episode {red}" in text) == (red >= 1)
        assert (f"episode {blue}" in text) == (blue >= 1)
        if red >= 1 and blue >= 1 and red != blue:
            first = "red" if red < blue else "blue"
            assert text.startswith(first), text
            assert order[run] == (first == "red")
