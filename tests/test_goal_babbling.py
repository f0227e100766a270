"""Goal babbling on the simulated iCub (icm.experiments.goal_babbling): the API, bad
input, determinism, outcomes that come from the physics, the closing of the loop,
the figures, and the learning-progress claim on the tests' own seeds."""

import dataclasses

import mujoco
import numpy as np
import pytest

import icm
from icm.envs import buttons, icub
from icm.experiments import goal_babbling
from icm.experiments._babbling_physics import MovementLab, first_press, lowest_capsule_point
from icm.figures import forming_actions

from test_bad_input import refused


@pytest.fixture(scope="module")
def lab():
    return MovementLab()


@pytest.fixture(scope="module")
def small():
    return goal_babbling.run_goal_babbling("learning_progress", n_seeds=2, n_rollouts=40,
                                           seed=3, progress=False)


@pytest.fixture(scope="module")
def scripted_downs(lab):
    """The scripted primitive's "down" posture of each button (inverse kinematics)."""
    return np.array(buttons.ButtonsTask().motions(lab.physics).down)


# --- the API -------------------------------------------------------------------------------

def test_result_has_the_documented_arrays(small):
    n_goals = len(goal_babbling.console_geometry()["test_goals"])
    assert small.n_seeds == 2 and small.n_rollouts == 40
    assert small.test_error.shape == (2, len(small.checkpoints))
    assert small.checkpoints[-1] == 40 and np.all(np.diff(small.checkpoints) > 0)
    assert small.test_goals.shape == (n_goals, 3)
    assert small.buttons_pressed.shape == (2, 5) and small.buttons_pressed.dtype == bool
    assert small.press_movements.shape == (2, 5, 7)
    assert small.movements.shape == (2, 40, 7) and small.outcomes.shape == (2, 40, 3)
    assert small.touched.shape == small.pressed.shape == small.regions.shape == (2, 40)
    assert small.goals.shape == (2, 40, 3)
    n_regions = int(np.prod(goal_babbling.REGION_GRID))
    assert small.interest.shape == (2, 40, n_regions)
    # The first N_BOOTSTRAP rollouts are random motor commands: no goal, no region.
    boot = goal_babbling.N_BOOTSTRAP
    assert np.isnan(small.goals[:, :boot]).all() and (small.regions[:, :boot] == -1).all()
    assert np.isfinite(small.goals[:, boot:]).all()
    assert np.array_equal(small.regions[:, boot:], goal_babbling.region_of(small.goals[:, boot:]))
    # Every goal lies in the goal space; every movement within the joint ranges.
    assert (small.goals[:, boot:] >= goal_babbling.GOAL_LOW).all()
    assert (small.goals[:, boot:] <= goal_babbling.GOAL_HIGH).all()
    lab = MovementLab()
    assert (small.movements >= lab.lower).all() and (small.movements <= lab.upper).all()
    summary = small.summary()
    assert summary["test_error_low"] <= summary["test_error"] <= summary["test_error_high"]
    assert 0 <= summary["buttons_pressed"] <= 5
    assert len(small.seed_summaries()) == 2


def test_test_error_is_the_distance_to_the_nearest_outcome_so_far(small):
    goals = small.test_goals
    for k in range(small.n_seeds):
        for c, done in enumerate(small.checkpoints):
            reached = small.outcomes[k, :done]
            nearest = np.linalg.norm(reached[:, None] - goals[None], axis=2).min(axis=0)
            assert small.test_error[k, c] == pytest.approx(nearest.mean(), abs=1e-12)
    # It can only go down as outcomes accumulate.
    assert np.all(np.diff(small.test_error, axis=1) <= 1e-15)


def test_the_press_movements_are_the_inverse_models_answers(small):
    press_goals = goal_babbling.console_geometry()["press_goals"]
    for k in range(small.n_seeds):
        for b in range(5):
            nearest = np.argmin(np.linalg.norm(small.outcomes[k] - press_goals[b], axis=1))
            assert np.array_equal(small.press_movements[k, b], small.movements[k, nearest])
            assert np.array_equal(small.press_outcomes[k, b], small.outcomes[k, nearest])


def test_goal_geometry_follows_the_model():
    geometry = goal_babbling.console_geometry()
    physics = buttons.load_physics()
    physics.forward()
    for b in range(5):
        cap = physics.named.data.geom_xpos[f"button{b}_cap"]
        # The press goal: the cap's top centre pushed all the way in (15 mm).
        assert np.allclose(geometry["press_goals"][b], cap + [0, 0, 0.015 - 0.015])
    top = geometry["console_top"]
    assert top == pytest.approx(0.485)
    grid = geometry["test_goals"][5:]
    assert len(grid) == 16 and np.all(grid[:, 2] == top)
    # No grid goal lies on a cap: each is clear of every cap by at least 1 cm.
    caps = geometry["caps"][:, :2]
    clearance = np.linalg.norm(grid[:, None, :2] - caps[None], axis=2).min(axis=1)
    assert clearance.min() >= geometry["cap_radius"] + 0.01
    # Each button sits in its own column of regions, at its centre.
    columns = [np.unravel_index(goal_babbling.region_of(g), goal_babbling.REGION_GRID)[1]
               for g in geometry["press_goals"]]
    assert columns == [5, 4, 3, 2, 1]
    bounds = goal_babbling.region_bounds()
    assert bounds.shape == (int(np.prod(goal_babbling.REGION_GRID)), 2, 3)
    for region, (low, high) in enumerate(bounds):
        assert goal_babbling.region_of((low + high) / 2) == region


def test_first_press_reads_the_first_update_and_the_lowest_button():
    depth = buttons.PRESS_DEPTH
    depths = np.zeros((3, 4, 5))
    depths[0, 2, 3] = depths[0, 3, 1] = depth + 1e-3  # button 3 first
    depths[1, 1, [4, 2]] = depth + 1e-3  # same update: the lower index
    depths[2, :, 0] = depth  # at the threshold is not past it
    assert first_press(depths).tolist() == [3, 2, -1]


# --- bad input -----------------------------------------------------------------------------

run = goal_babbling.run_goal_babbling


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda: run(strategy="curious"), "strategy", "'curious'", "value"),
    (lambda: run(strategy=3), "strategy", "3", "type"),
    (lambda: run(n_seeds=0), "n_seeds", "0", "value"),
    (lambda: run(n_seeds=1.5), "n_seeds", "1.5", "type"),
    (lambda: run(n_rollouts=0), "n_rollouts", "0", "value"),
    (lambda: run(n_rollouts="many"), "n_rollouts", "'many'", "type"),
    (lambda: run(seed=-1), "seed", "-1", "value"),
    (lambda: run(progress="yes"), "progress", "'yes'", "type"),
    (lambda: run(exploration_noise=0.0), "exploration_noise", "0.0", "value"),
    (lambda: run(exploration_noise=1.5), "exploration_noise", "1.5", "value"),
    (lambda: run(epsilon=-0.1), "epsilon", "-0.1", "value"),
    (lambda: run(window=1), "window", "1", "value"),
    (lambda: run(n_seeds=10 ** 6, n_rollouts=10 ** 6), "run_goal_babbling", "memory", "value"),
    (lambda: goal_babbling.region_of([0.3, 0.1]), "points", "(2,)", "value"),
    (lambda: goal_babbling.run_formed_actions("babbling"), "babbling", "'babbling'", "type"),
    (lambda: buttons.PhysicsButtonConsole(press_motions=[[]] * 5), "press_motions[0]", "[]",
     "value"),
    (lambda: buttons.PhysicsButtonConsole(press_motions=[[(np.zeros(7), 0.4)]] * 4),
     "press_motions", "one motion per button", "value"),
    (lambda: buttons.PhysicsButtonConsole(press_motions=[[(np.zeros(6), 0.4)]] * 5),
     "press_motions[0][0] joint targets", "(6,)", "value"),
    (lambda: buttons.PhysicsButtonConsole(press_motions=[[(np.zeros(7), -1.0)]] * 5),
     "press_motions[0][0] seconds", "-1.0", "value"),
    (lambda: buttons.PhysicsButtonConsole(press_motions=[[np.zeros(7)]] * 5),
     "press_motions[0][0]", "pair", "value"),
    (lambda: buttons.PhysicsButtonConsoleBatch([0, 1], press_motions=[None]),
     "press_motions", "one entry per row", "value"),
])
def test_bad_input_is_refused(call, name, shown, kind):
    refused(call, name, shown, kind)


def test_bad_input_to_the_figures_and_the_loop_is_refused(small):
    random_motor = dataclasses.replace(small, settings={**small.settings,
                                                        "strategy": "random_motor"})
    refused(lambda: forming_actions.goal_choice_figure(random_motor), "result",
            "'random_motor'", "value")
    refused(lambda: forming_actions.goal_choice_figure(small, n_stretches=0), "n_stretches",
            "0", "value")
    refused(lambda: forming_actions.test_error_figure({}), "results", "{}", "type")
    refused(lambda: forming_actions.coverage_figure({"a": small}, early=1.0), "early", "1.0",
            "value")
    refused(lambda: forming_actions.record_learned_press(small, seed=2), "seed", "2", "value")
    refused(lambda: forming_actions.record_learned_press(small, camera="top"), "camera",
            "'top'", "value")
    refused(lambda: goal_babbling.run_formed_actions(small, n_trials=0), "n_trials", "0",
            "value")
    refused(lambda: small.goal_shares([0, 50]), "edges", "50", "value")


# --- determinism ---------------------------------------------------------------------------

def test_the_same_seed_gives_identical_results_and_seed_k_runs_alone(small):
    again = goal_babbling.run_goal_babbling("learning_progress", n_seeds=2, n_rollouts=40,
                                            seed=3, progress=False)
    for field in dataclasses.fields(small):
        a, b = getattr(small, field.name), getattr(again, field.name)
        if isinstance(a, np.ndarray):
            assert np.array_equal(a, b, equal_nan=True), field.name
    alone = goal_babbling.run_goal_babbling("learning_progress", n_seeds=1, n_rollouts=40,
                                            seed=3, progress=False)
    assert np.array_equal(alone.outcomes[0], small.outcomes[0])
    assert np.array_equal(alone.buttons_pressed[0], small.buttons_pressed[0])
    other = goal_babbling.run_goal_babbling("learning_progress", n_seeds=1, n_rollouts=40,
                                            seed=4, progress=False)
    assert not np.array_equal(other.movements[0], small.movements[0])


def test_the_strategies_choose_differently():
    motor = goal_babbling.run_goal_babbling("random_motor", n_seeds=1, n_rollouts=30, seed=3,
                                            progress=False)
    goal = goal_babbling.run_goal_babbling("random_goal", n_seeds=1, n_rollouts=30, seed=3,
                                           progress=False)
    assert np.isnan(motor.goals).all() and (motor.regions == -1).all()
    assert not motor.interest.any() and not goal.interest.any()
    # The same random start, then different choices.
    boot = goal_babbling.N_BOOTSTRAP
    assert np.array_equal(motor.movements[:, :boot], goal.movements[:, :boot])
    assert not np.array_equal(motor.movements[:, boot:], goal.movements[:, boot:])


# --- outcomes come from the physics -----------------------------------------------------

def test_a_movement_that_misses_the_console_presses_nothing(lab):
    home = lab.home
    raised = home.copy()
    raised[0] = lab.lower[0]  # shoulder pitch: the arm up and forward, over the console
    done = lab.perform(np.array([home, raised]), retract=True)
    assert done["pressed"].tolist() == [-1, -1]
    assert not done["touched"].any()
    # Both end in the air, above the caps.
    assert (done["outcome"][:, 2] > goal_babbling.console_geometry()["cap_top"]).all()
    # On the console too: no press, no box.
    console = buttons.PhysicsButtonConsole(seed=0, press_motions=[lab.phases(raised)] * 5)
    console.reset()
    assert console.press(2).tolist() == [0, 0] and console.task.press_log == []


def test_outcomes_are_where_the_physics_stops_the_finger(lab, scripted_downs):
    # The scripted "down" postures put the fingertip 2.5 cm below each cap's top: the
    # button stops the finger, which pushes it in, and the outcome is there, not at
    # the posture's fingertip.
    done = lab.perform(scripted_downs)
    assert done["pressed"].tolist() == [0, 1, 2, 3, 4]
    assert done["touched"].all()
    geometry = goal_babbling.console_geometry()
    arm = icub.Arm(lab.physics)
    scratch = mujoco.MjData(lab.model)
    for target, outcome in zip(scripted_downs, done["outcome"]):
        scratch.qpos[:] = lab.initial_state[lab.qpos_slice]
        scratch.qpos[arm.qpos_index] = target
        mujoco.mj_kinematics(lab.model, scratch)  # where the posture alone puts the finger
        posture_point = lowest_capsule_point(
            scratch.geom_xpos[lab.finger], scratch.geom_xmat[lab.finger].reshape(3, 3)[:, 2],
            lab.radius, lab.half_length)
        assert outcome[2] > posture_point[2] + 0.005
        assert outcome[2] > geometry["cap_top"] - 0.015 - 0.002  # the travel, give or take
    assert np.linalg.norm(done["outcome"] - geometry["press_goals"], axis=1).max() < 0.01
    # A sturdier console (stiffer springs) is pressed less deep by the same movements.
    stiff = MovementLab()
    for b in range(5):
        stiff.model.jnt_stiffness[stiff.model.jnt(f"button{b}").id] *= 20
    stopped = stiff.perform(scripted_downs)
    assert stopped["pressed"].tolist() == [-1] * 5
    assert np.all(stopped["outcome"][:, 2] > done["outcome"][:, 2] + 0.005)


def test_rollouts_in_c_equal_the_console_stepped_from_python(lab, scripted_downs):
    # The same movement, performed by mujoco.rollout and by the physics console's
    # press (icub.Arm.move, the task watching), reaches the same outcome and presses
    # the same buttons.
    rng = np.random.default_rng(0)
    targets = np.concatenate([scripted_downs[[1, 4]], rng.uniform(lab.lower, lab.upper, (2, 7))])
    done = lab.perform(targets, retract=True)
    outcome_update = sum(lab.n_updates[:2])
    for target, outcome, touched, pressed in zip(targets, done["outcome"], done["touched"],
                                                 done["pressed"]):
        console = buttons.PhysicsButtonConsole(seed=0, press_motions=[lab.phases(target)] * 5)
        console.reset()
        states = []
        console.press(0, recorder=lambda physics: states.append(physics.data.qpos.copy()))
        point, touching = lab.measure(states[outcome_update - 1])
        assert np.allclose(point, outcome, atol=1e-9, rtol=0)
        assert touching == touched
        assert (console.task.press_log[:1] or [-1]) == [pressed]
    # The batch does not matter: one movement alone gives the same numbers.
    alone = lab.perform(targets[2:3], retract=True)
    assert np.array_equal(alone["outcome"][0], done["outcome"][2])


def test_buttons_pressed_is_measured_on_the_console(lab, scripted_downs, small):
    # Give seed 0 the scripted postures for buttons 1 and 3 and a miss for the others:
    # exactly those two are pressed.
    movements = small.press_movements.copy()
    movements[0] = lab.home
    movements[0, [1, 3]] = scripted_downs[[1, 3]]
    pressed = goal_babbling._press_each_button(lab, movements, [0, 1])
    assert pressed[0].tolist() == [False, True, False, True, False]


# --- closing the loop ----------------------------------------------------------------------

def test_formed_actions_that_press_like_the_script_give_the_scripted_run(small,
                                                                          scripted_downs):
    # Movements that press exactly like the scripted primitive: the learner on the
    # physics console makes the choices it makes on the tabular console, seed for seed.
    formed = dataclasses.replace(small, press_movements=np.stack([scripted_downs] * 2))
    run = goal_babbling.run_formed_actions(formed, n_trials=6, seed=5, progress=False)
    tabular = icm.experiments.run_goal_oriented(n_seeds=2, n_trials=6, seed=5,
                                                progress=False)
    assert run.as_scripted == 1.0 and run.n_presses == 2 * 6 * 3
    assert np.array_equal(run.learner.interest, tabular.interest)
    assert np.array_equal(run.learner.mastery_trial, tabular.mastery_trial)
    # Movements that press nothing: no box ever opens, unlike the script.
    missing = dataclasses.replace(small, press_movements=np.stack([[MovementLab().home] * 5] * 2))
    run = goal_babbling.run_formed_actions(missing, n_trials=2, seed=5, progress=False)
    assert run.learner.practice.sum() == 0 and run.as_scripted < 1.0


# --- figures -------------------------------------------------------------------------------

def test_figures_draw(small):
    motor = goal_babbling.run_goal_babbling("random_motor", n_seeds=2, n_rollouts=30, seed=3,
                                            progress=False)
    results = {"learning progress": small, "random motor": motor}
    for figure in (forming_actions.test_error_figure(results),
                   forming_actions.coverage_figure(results),
                   forming_actions.goal_choice_figure(small, n_stretches=4),
                   forming_actions.learned_presses_figure(small)):
        assert len(figure.png()) > 10_000
    record = forming_actions.record_learned_press(small, seed=1, button=2)
    assert record["frame"].shape == (240, 320, 3) and record["frame"].std() > 1
    assert "| random motor | 2 | 30 |" in goal_babbling.comparison_table(results)


# --- the claim -----------------------------------------------------------------------------

def test_learning_progress_beats_random_motor_babbling_at_the_default_budget():
    # The claims that hold at DEFAULT_N_ROLLOUTS, on this test's own seeds: a lower
    # test error than random motor babbling, and more buttons pressed. (That learning
    # progress presses at least 4 of the 5 does not hold on every set of seeds: 3.0 on
    # these two, 3.4 on 8 seeds of root seed 11, 4.1 on 8 of root seed 0.)
    progress = goal_babbling.run_goal_babbling("learning_progress", n_seeds=2, seed=11,
                                               progress=False)
    motor = goal_babbling.run_goal_babbling("random_motor", n_seeds=2, seed=11,
                                            progress=False)
    assert progress.n_rollouts == motor.n_rollouts == goal_babbling.DEFAULT_N_ROLLOUTS
    assert progress.final_test_error().max() < motor.final_test_error().min()
    assert progress.buttons_pressed.sum() > motor.buttons_pressed.sum()


def test_no_outcome_lies_inside_the_console(lab):
    # Soft contacts let a finger driven hard sink into the console's top; the outcome
    # is read on the surface. Movements into the console from random targets, seeded.
    rng = np.random.default_rng(2)
    geometry = goal_babbling.console_geometry()
    downs = np.array(buttons.ButtonsTask().motions(lab.physics).down)
    targets = downs[rng.integers(5, size=60)] + rng.normal(0, 0.15, (60, 7))
    done = lab.perform(targets)
    centre, half = geometry["console_centre"], geometry["console_half"]
    over = np.all(np.abs(done["outcome"][:, :2] - centre[:2]) <= half[:2], axis=1)
    assert over.sum() >= 10
    assert np.all(done["outcome"][over, 2] >= geometry["console_top"] - 1e-9)
