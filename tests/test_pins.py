"""Pins on the newest code (issue 30, section 3): each behaviour written from what the
code must do, small and through public names, so that a wrong change fails here
whichever module the code lives in.

- a region's competence progress reads its last `window` competences (the oldest
  dropped, not the newest), and so does the maturational clock;
- splitting regions cut along x, then y, then z, down the tree;
- the LWLR inverse model steps towards its goal;
- `presses_formed` uses the rollouts within its budget, and none beyond;
- "the others pressed early" counts a first press at the early bound itself;
- a shown button pressed no sooner than with learning progress alone (a tie) is
  "not sooner";
- the Figure 5 panel runs the chapter's 60 trials;
- a live panel's band runs from the lower bound to the upper one.

(The executor's runaway limit and the settings' two refusals are pinned in
tests/test_build.py and tests/test_settings_pins.py.)
"""

import copy

import numpy as np
import pytest

from icm import chapters, figures
from icm.envs import buttons
from icm.experiments import formed_actions, goal_babbling, panel_data
from icm.studies.forming_actions import arms
from icm.studies.forming_actions import remedies as remedies_study
from icm.learners import goal_choice, maturation, sensorimotor


def _competence_progress(distances, window):
    """SAGG-RIAC's competence progress, written from its definition: of the last
    `window` competences (minus the distances), the absolute difference between the
    mean of the newer half and that of the older half (the older half the first
    n // 2)."""
    recent = -np.asarray(distances[-window:], dtype=float)
    half = len(recent) // 2
    return abs(recent[half:].mean() - recent[:half].mean())


DISTANCES = [0.9, 0.05, 0.5, 0.3, 0.7, 0.2, 0.6, 0.1]
"""Distances whose progress over the last 4 differs from that of any other 4."""


def test_a_regions_competence_progress_reads_its_last_window_goals():
    grid = goal_choice.RegionGrid([0.0, 0.0], [1.0, 1.0], (2, 1))
    choice = goal_choice.RegionProgress(grid, 1, measure="competence_progress", window=4)
    for i, distance in enumerate(DISTANCES):
        choice.update(np.array([1]), np.array([distance]))
        expected = _competence_progress(DISTANCES[:i + 1], 4) if i >= 1 else 0.0
        np.testing.assert_allclose(choice.values()[0], [0.0, expected], rtol=0, atol=1e-12,
                                   err_msg=f"after {i + 1} distances")


def test_the_maturational_clock_reads_the_last_window_goals_too():
    clock = maturation.JointRangeMaturation(1, [0.0], [-1.0], [1.0], window=4,
                                            plateau=0.0, step=0.1)
    for i, distance in enumerate(DISTANCES):
        clock.update(np.array([distance]))
        expected = _competence_progress(DISTANCES[:i + 1], 4) if i >= 1 else 0.0
        np.testing.assert_allclose(clock.progress(), [expected], rtol=0, atol=1e-12,
                                   err_msg=f"after {i + 1} distances")


def test_splitting_regions_cut_along_x_then_y_then_z():
    # SAGG-RIAC's tree: the box is cut along x, each half along y, each quarter along
    # z, then x again. A region cut along z has so been cut along x and y before.
    grid = goal_choice.RegionGrid([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], (1, 1, 1))
    choice = goal_choice.SplittingRegionProgress(grid, 2, window=4, max_goals=8)
    generators = [np.random.default_rng(seed) for seed in (0, 1)]
    noise = np.random.default_rng(2)
    for _ in range(600):
        goals, regions = choice.sample(generators)
        # Distances that fall with the goal's x and rise with y: progress differs
        # across the box, so cuts are made where they separate it.
        distances = np.abs(0.5 + goals[:, 1] - goals[:, 0] + noise.normal(0, 0.05, 2))
        choice.update(regions, distances)
    for row in range(2):
        cut = np.array([[(box[0, d] > 0) or (box[1, d] < 1) for d in range(3)]
                        for box in choice.bounds[row]])  # [region, dimension]
        assert len(cut) >= 16, len(cut)
        # Cut along y only after x, along z only after y.
        assert not np.any(cut[:, 1] & ~cut[:, 0]), cut
        assert not np.any(cut[:, 2] & ~cut[:, 1]), cut
        assert cut[:, 1].any() and cut[:, 2].any(), cut
        # And x again after z: a region cut along x twice is cut on both sides.
        boxes = np.array(choice.bounds[row])
        assert np.any((boxes[:, 0, 0] > 0) & (boxes[:, 1, 0] < 1)), boxes[:, :, 0]


def test_the_lwlr_inverse_model_steps_towards_its_goal():
    # On a linear arm (outcome = B m + c), the local linear fit is exact, and one
    # Gauss-Newton step from the movement whose outcome lies nearest the goal reaches
    # a goal within its step: much nearer the goal than that nearest outcome.
    rng = np.random.default_rng(0)
    lower, upper = -np.ones(3), np.ones(3)
    arm = rng.normal(size=(2, 3))
    model = sensorimotor.LocallyWeightedInverse(1, 60, lower, upper, 2, neighbours=12,
                                                kernel_width=0.5, max_step=0.2)
    for movement in rng.uniform(-0.8, 0.8, (60, 3)):
        model.update(movement[None], (arm @ movement + 0.3)[None])
    for goal in rng.uniform(-0.5, 0.5, (10, 2)):
        index, nearest = model.nearest(goal[None])
        movement = model.infer(goal[None])[0]
        reached = np.linalg.norm(arm @ movement + 0.3 - goal)
        assert reached < 0.5 * nearest[0], (goal, reached, nearest[0])


@pytest.fixture(scope="module")
def shown_five():
    """A run whose first five rollouts are the teacher's presses of buttons 0 to 4."""
    return goal_babbling.run_goal_babbling("learning_progress", n_seeds=1, n_rollouts=6,
                                           demonstrations=(0, 1, 2, 3, 4), seed=0,
                                           progress=False)


def test_presses_formed_uses_the_rollouts_within_its_budget_and_none_beyond(shown_five):
    # Rollout n is the teacher's press of button n - 1, so within a budget of n
    # rollouts exactly the buttons 0 .. n-1 have a press formed.
    assert shown_five.pressed[0, :5].tolist() == [0, 1, 2, 3, 4]
    formed = formed_actions.presses_formed(shown_five, [1, 2, 3, 4, 5])[:, 0]
    expected = np.tril(np.ones((5, 5), dtype=bool))
    assert formed.tolist() == expected.tolist()


def _study(first_presses, n_rollouts=1000):
    """A study of one root seed and as many seeds as `first_presses` has rows per
    condition: {label: [seed][button] first presses (-1 never)}; every press formed."""
    budgets = list(arms.BUDGETS)
    runs = {}
    for label in remedies_study.CONDITIONS:
        first = first_presses.get(label, [[-1] * buttons.N_BUTTONS])
        n = len(first)
        runs[label] = {"0": {
            "pressed": [[[1] * buttons.N_BUTTONS] * len(budgets)] * n, "first_press": first,
            "test_error": [0.01] * n, "red_first": [1] * n, "as_scripted": [1.0] * n,
            "maturity": [[1.0] * len(budgets)] * n,
            "coverage": {"early": [[0]], "all": [[0]]}}}
    return {"budgets": budgets, "n_seeds": 1, "n_rollouts": n_rollouts, "runs": runs}


def test_the_others_pressed_early_count_a_first_press_at_the_bound_itself():
    early = arms.EARLY
    label = "shown button 2"  # the others: 0, 1, 3, 4
    study = _study({label: [[early, early + 1, 5, -1, 1]]})
    counted = remedies_study.seed_values(study, label, "others_pressed_early")
    assert counted.tolist() == [2.0]  # rollouts EARLY and 1; not EARLY + 1, not never


def test_a_shown_button_pressed_as_soon_as_without_a_teacher_is_not_sooner():
    baseline = [[300, 300, 300, 300, 300]]
    sooner = {label: [[100] * buttons.N_BUTTONS] for label in remedies_study.TEACHING}
    sentence = chapters.forming_actions.remedies.shown_sooner_sentence(
        _study({"learning progress": baseline, **sooner}))
    assert sentence.startswith("sooner than learning progress alone in all")
    tied = copy.deepcopy(sooner)
    tied["shown button 2"] = [[100, 100, 300, 100, 100]]  # button 2, the one shown: a tie
    sentence = chapters.forming_actions.remedies.shown_sooner_sentence(
        _study({"learning progress": baseline, **tied}))
    assert sentence.startswith("not sooner in shown button 2, button 2"), sentence


def test_the_figure_5_panel_runs_the_chapters_60_trials():
    spec = panel_data.spec("figure5")
    assert spec.fixed["n_trials"] == 60
    curves = panel_data.panel_curves_for("figure5", {"n_seeds": 4}, **spec.defaults)
    assert np.asarray(curves["x"]).tolist() == list(range(1, 61))


def test_a_live_panels_band_runs_from_the_lower_bound_to_the_upper():
    x = np.arange(1, 11)
    mean = np.linspace(0.2, 0.6, 10)
    low, high = mean - 0.1, mean + np.linspace(0.05, 0.3, 10)
    curves = {"x": x, "xlabel": "trial", "groups": [{
        "title": "interest", "ylabel": "interest",
        "series": {"red": (mean, low, high), "green": (mean / 2, low / 2, high / 2)}}]}
    fig = figures.draw_curves(curves)
    ax = fig.axes[0]
    bands = ax.collections
    assert len(bands) == 2
    for band, (m, lo, hi) in zip(bands, [(mean, low, high), (mean / 2, low / 2, high / 2)]):
        vertices = band.get_paths()[0].vertices
        for i, xi in enumerate(x):
            at = vertices[np.isclose(vertices[:, 0], xi), 1]
            np.testing.assert_allclose([at.min(), at.max()], [lo[i], hi[i]], atol=1e-12)
