"""The chapter "The simulated iCub" (book/simulated_icub.ipynb): whether the fast
tabular twins give the physics' outcomes, its claims in words (`CLAIMS`) checked on its
own runs when the book is built (`claims`), and the numbers it explains: how the steps
of a comparison split into trials (`trial_steps`, `rod_episode_ends`), the ceiling of
the goal-oriented learner's interest and the mean and band of Figure 5 under it
(`interest_ceiling`, `interest_mean_top`, `interest_band_top`), how high a mean of interest peaks and where
it starts (`interest_peaks`), the phases of a press as they run (`press_phases`,
checked on a recorded press by `press_claims`), the arm's joints as a table
(`joint_table`), and how the arm holds a posture, with and without gravity compensation
(`hold_above_red`)."""

import math

import mujoco
import numpy as np

from icm import _validate, envs, stats
from icm.envs import buttons, icub, rods
from icm.experiments.goal_oriented import GoalOrientedResult

CLAIMS = {
    "buttons_agree": "the physics and the tabular console give the same observations",
    "rods_agree": "the physics and the tabular rod table give the same observations",
    "learner_same": "the goal-oriented learner makes the same run on the physics as on "
                    "the tabular console",
    "red_more_pairs": "more (cell, move) pairs topple the red rod than the blue one",
    "forearm_topples_red": "moving right along the far row into the cell beside the red "
                           "rod topples it",
    "button_steps_make_trials": "the buttons' steps are whole trials of the presses and "
                                "one step that starts the next trial, and the last step "
                                "began one more trial",
    "interest_under_ceiling": "the interest of both runs, and the band of their means, "
                              "stay at or below the largest prediction error",
}
"""The claims the chapter states in words (`claims`)."""
PRESS_CLAIMS = {
    "press_is_its_phases": "a press (the first of a trial, the lids shut) lasts the sum "
                           "of its phases, each a whole number of updates",
    "lid_opens_during_press": "the pressed button's lid passes the open angle before the "
                              "press ends",
}
"""The claims the chapter states about one recorded press (`press_claims`)."""
PEAK_CLAIMS = {
    "icub_seeds_are_the_first": "the chapter's few seeds are the first seeds of the "
                                "wider run, their interest the same trial by trial",
}
"""The claims the chapter states about Figure 2.1's run against its own (`peak_claims`)."""
PRESS_PHASES = ("reach above the button", "push down", "hold", "lift", "return home")
"""The phases of the press primitive, in order (`buttons.PhysicsButtonConsole.press`)."""
FOREARM_PAIR = ((1, 2), rods.ACTIONS.index("right"))
"""The pair the chapter names: right, along the far row, into cell (2, 2), where the
forearm passes over the red rod."""
_RESULT_FIELDS = ("interest", "prediction_error", "mastery_trial", "practice", "button_share")


def _check_comparison(name, check):
    if not isinstance(check, dict) or not {"steps", "episodes", "ended", "acted",
                                           "terminations", "mismatches"} <= set(check):
        raise _validate.ArgumentTypeError(f"{name} must be what compare_twins returns, "
                                          f"got {_validate.show(check)}")
    return check


STRONG_WORDS = {
    "so the tests compare outcomes, not numbers: they (`tests/test_live_viewer.py`) press "
    "every button": ("tests/test_live_viewer.py::test_every_press_in_the_browser_opens_"
                     "the_lid_python_opens", "rule"),
    "replay other random presses on another seed, comparing at every step": (
        "tests/test_physics.py::test_compare_twins_finds_agreement_and_would_find_a_"
        "difference", "rule"),
}
"""The chapter's sentences with a word of strength beside what the learners did, and
the test that checks each (book/_ext/claim_words.py): what the tests compare, a rule
of the code."""


JOINT_MOTIONS = {
    "r_shoulder_pitch": "swings the arm forward (negative) or back (positive)",
    "r_shoulder_roll": "lifts the arm sideways, away from the body (positive)",
    "r_shoulder_yaw": "turns the upper arm about its length: positive swings the bent "
                      "forearm out, to the robot's right",
    "r_elbow": "bends the elbow (positive); near 0 the arm is straight",
    "r_wrist_prosup": "turns the forearm about its length, palm down or palm up",
    "r_wrist_pitch": "bends the hand at the wrist: negative, the way the elbow bends",
    "r_wrist_yaw": "tilts the hand sideways: positive, towards the robot's left when the "
                   "elbow is bent",
}
"""What turning each joint of the right arm does, from the arm hanging straight along
the torso (every angle 0); tests/test_icub_figures.py checks each direction on the
model."""


def joint_table(physics):
    """The right arm's joints as a Markdown table a newcomer can read: each joint in
    the iCub's order, what turning it does (`JOINT_MOTIONS`: from 0 degrees, the arm
    hanging straight along the torso), its range in degrees and its motor's gain kp.

    Args:
      physics: a physics of one of the scenes (`icm.envs.buttons.load_physics()`).

    Returns:
      A Markdown string (display it with `IPython.display.Markdown`).
    """
    from dm_control import mujoco as dm_mujoco

    _validate.instance("physics", physics, dm_mujoco.Physics, "a dm_control Physics")
    lines = ["| # | joint | what turning it does | range (degrees) | motor's gain kp "
             "(N m per radian) |", "|---|---|---|---|---|"]
    for i, name in enumerate(icub.ARM_JOINTS, start=1):
        low, high = np.rad2deg(physics.named.model.jnt_range[name])
        kp = physics.named.model.actuator_gainprm[name][0]
        lines.append(f"| {i} | {name} | {JOINT_MOTIONS[name]} | {low:.1f} to {high:.1f} "
                     f"| {kp:g} |")
    return "\n".join(lines)


def trial_steps(button_check, presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL):
    """How the steps of a comparison of the buttons (`icm.envs.compare_twins`) split
    into trials.

    dm_env's first step after an episode's end starts the next episode and ignores its
    action: a trial of `presses_per_trial` presses takes one step more.

    Args:
      button_check: what `compare_twins("buttons", ...)` returned.
      presses_per_trial: the console's presses per trial.

    Returns:
      A dict: "steps" (steps played), "steps_per_trial" (presses per trial + 1),
      "whole_trials" (trials that ended), "presses" (steps that pressed a button),
      "begun" (trials begun, the first included), "terminations".
    """
    check = _check_comparison("button_check", button_check)
    presses_per_trial = _validate.integer("presses_per_trial", presses_per_trial, 1)
    return {"steps": check["steps"], "steps_per_trial": presses_per_trial + 1,
            "whole_trials": check["ended"], "presses": check["acted"],
            "begun": check["episodes"], "terminations": check["terminations"]}


def rod_episode_ends(rod_check):
    """How the episodes of a comparison of the rods (`icm.envs.compare_twins`) ended.

    Returns:
      A dict: "steps", "moves" (steps that moved the hand), "begun" (episodes begun),
      "ended" (episodes that ended), "topples" (ended with a topple: a termination) and
      "limits" (ended at the move limit, a time limit).
    """
    check = _check_comparison("rod_check", rod_check)
    return {"steps": check["steps"], "moves": check["acted"], "begun": check["episodes"],
            "ended": check["ended"], "topples": check["terminations"],
            "limits": check["ended"] - check["terminations"]}


def interest_ceiling():
    """The largest prediction error of the goal-oriented learner: the distance between
    two effects of a press, largest between "red box open" and "green box open",
    sqrt(2).

    The interest of a task is its learning progress, the fall of its prediction error
    per press (the least-squares slope of its last errors), or a new task's half share
    of the others' mean. A slope of errors between 0 and this ceiling is at most the
    ceiling (reached when one error falls from the ceiling to 0 in two presses), so no
    interest passes it; `claims` checks that the chapter's runs stay under it.
    """
    return max(math.dist(a, b) for a in buttons.EFFECTS for b in buttons.EFFECTS)


def interest_mean_top(result):
    """The highest point of Figure 5's mean curves for `result`: the largest mean over
    seeds of the interest, over trials and tasks (a band's top is `interest_band_top`)."""
    _validate.instance("result", result, GoalOrientedResult,
                       "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    return float(result.interest.mean(axis=0).max())


def interest_band_top(result):
    """The highest point of Figure 5's bands for `result`: the upper end of the
    percentile-bootstrap band of the mean interest (`icm.stats.bootstrap_band`, with
    the figures' `PANEL_RESAMPLES`), over trials and tasks."""
    _validate.instance("result", result, GoalOrientedResult,
                       "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    return max(float(stats.bootstrap_band(result.interest[:, :, i],
                                          resamples=stats.PANEL_RESAMPLES)[2].max())
               for i in range(result.interest.shape[2]))


def press_phases(physics=None):
    """How long each phase of the press primitive runs, in seconds of simulated time.

    Each phase asks for a duration (`buttons.PhysicsButtonConsole.REACH_TIME`, ...), and
    the arm runs it as a whole number of updates of the motors' targets
    (`icub.Arm.n_updates`, one every `icub.SUBSTEPS` physics steps), so a phase of
    0.45 s runs 22 updates of 20 ms, 0.44 s.

    Args:
      physics: a `ButtonsPhysics` (default: a fresh one), whose time step counts.

    Returns:
      A dict {phase (`PRESS_PHASES`): seconds as run}.
    """
    physics = buttons.load_physics() if physics is None else _validate.instance(
        "physics", physics, buttons.ButtonsPhysics, "a ButtonsPhysics (buttons.load_physics())")
    arm = icub.Arm(physics)
    update = physics.model.opt.timestep * icub.SUBSTEPS
    console = buttons.PhysicsButtonConsole
    asked = (console.REACH_TIME, console.PUSH_TIME, console.HOLD_TIME, console.LIFT_TIME,
             console.RETURN_TIME)
    return {phase: arm.n_updates(seconds) * update for phase, seconds in zip(PRESS_PHASES, asked)}


def press_claims(press):
    """{claim name: whether it holds}, for each of `PRESS_CLAIMS`, on a press recorded by
    `icm.figures.record_press` (the first press of a trial).

    Args:
      press: the dict `record_press` returned ("time", "lids", "button", "lights").
    """
    if not isinstance(press, dict) or not {"time", "lids", "button", "lights"} <= set(press):
        raise _validate.ArgumentTypeError(f"press must be what icm.figures.record_press "
                                          f"returns, got {_validate.show(press)}")
    colour = int(press["lights"][press["button"]])
    box = {buttons.RED: 0, buttons.GREEN: 1}.get(colour)
    opened = box is not None and bool(
        (press["lids"][:, box] >= np.rad2deg(buttons.BOX_OPEN_ANGLE)).any())
    return {
        "press_is_its_phases": math.isclose(float(press["time"][-1]),
                                            sum(press_phases().values()), abs_tol=1e-9),
        "lid_opens_during_press": opened,
    }


def interest_peaks(result):
    """How high the mean interest in red peaks in `result`, against each seed's own
    peak, and how many seeds start with some interest.

    Args:
      result: a `GoalOrientedResult`.

    Returns:
      A dict: "mean_peak" (the highest point of the mean over seeds of the interest in
      red), "seed_peak" (the mean over seeds of each seed's highest interest in red),
      "first_peak_trial" and "last_peak_trial" (the earliest and the latest trial, from
      1, at which a seed's interest in red is highest, its first such trial), "quartile_trials"
      (the 25th and 75th percentiles of those trials), "started" (how many seeds have
      an interest above zero in a task after trial 1) and "seeds".
    """
    _validate.instance("result", result, GoalOrientedResult,
                       "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    red = result.interest[:, :, 0]
    peak_trials = np.argmax(red, axis=1) + 1
    low, high = np.percentile(peak_trials, [25, 75])
    return {"mean_peak": float(red.mean(axis=0).max()), "seed_peak": float(red.max(axis=1).mean()),
            "first_peak_trial": int(peak_trials.min()), "last_peak_trial": int(peak_trials.max()),
            "quartile_trials": (float(low), float(high)),
            "started": int((result.interest[:, 0, :] > 0).any(axis=1).sum()),
            "seeds": result.n_seeds}


def peak_claims(wide_run, few_run):
    """{claim name: whether it holds}, for each of `PEAK_CLAIMS`.

    Args:
      wide_run: the run of Figure 2.1 (`run_goal_oriented(n_seeds=200, n_trials=60,
        seed=0)`).
      few_run: the chapter's run on the same root seed, fewer seeds and trials.
    """
    for name, run in (("wide_run", wide_run), ("few_run", few_run)):
        _validate.instance(name, run, GoalOrientedResult,
                           "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    seeds, trials = few_run.n_seeds, few_run.n_trials
    return {"icub_seeds_are_the_first": wide_run.n_seeds >= seeds
            and wide_run.n_trials >= trials
            and np.array_equal(wide_run.interest[:seeds, :trials], few_run.interest)}


def hold_above_red(seed=0, seconds=1.0, gravity_compensation=True):
    """The chapter's continuous example: the arm's targets are set, once, to the
    posture that puts the fingertip above the red button, and held for `seconds`.

    Args:
      seed: the task's seed (the lights' layout).
      seconds: how long (simulated) the targets are held, in (0, 60].
      gravity_compensation: False switches off the compensation of the arm's weight
        (MuJoCo's `gravcomp` of every body, set to 0 in this task's own model).

    Returns:
      A dict: "targets" (the 7 joint targets, radians), "joints" (the joint angles at
      the end), "fingertip" (its position at the end, metres), "aimed" (where the
      targets put the fingertip: forward kinematics of the targets, metres),
      "observation" (the last time step's observation).
    """
    gravity_compensation = _validate.boolean("gravity_compensation", gravity_compensation)
    seconds = _validate.real("seconds", seconds, 0.0, 60.0, low_open=True)
    continuous = envs.load_continuous("buttons", seed=seed, time_limit=seconds)
    physics = continuous.physics
    if not gravity_compensation:
        physics.model.body_gravcomp[:] = 0.0
    targets = continuous.task.motions(physics).above[continuous.task.red_button]
    step = continuous.reset()
    while not step.last():
        step = continuous.step(targets)
    arm = icub.Arm(physics)
    scratch = mujoco.MjData(physics.model.ptr)
    scratch.qpos[:] = physics.data.qpos
    scratch.qpos[arm.qpos_index] = targets
    mujoco.mj_kinematics(physics.model.ptr, scratch)
    return {"targets": np.array(targets), "joints": arm.joint_positions(),
            "fingertip": arm.fingertip(), "aimed": scratch.site_xpos[arm.site_id].copy(),
            "observation": step.observation}


def claims(button_check, rod_check, topple_map, physics_run, tabular_run):
    """{claim name: whether it holds}, for each of `CLAIMS`.

    Args:
      button_check, rod_check: what `icm.envs.compare_twins` returned for the
        buttons and the rods.
      topple_map: the measured topple map (`icm.envs.rods.load_topple_map()`).
      physics_run, tabular_run: `GoalOrientedResult` objects of the same call, with
        `physics=True` and without.

    Returns:
      A dict of bools.
    """
    for name, check in (("button_check", button_check), ("rod_check", rod_check)):
        _check_comparison(name, check)
    for name, run in (("physics_run", physics_run), ("tabular_run", tabular_run)):
        _validate.instance(name, run, GoalOrientedResult,
                           "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    counts = rods.topple_counts(topple_map)
    trials = trial_steps(button_check)
    ceiling = interest_ceiling()
    return {
        "buttons_agree": button_check["mismatches"] == 0,
        "rods_agree": rod_check["mismatches"] == 0,
        "learner_same": all(np.array_equal(getattr(physics_run, f), getattr(tabular_run, f))
                            for f in _RESULT_FIELDS),
        "red_more_pairs": counts["red"] > counts["blue"],
        "forearm_topples_red": topple_map["topples"].get(FOREARM_PAIR) == "red",
        "button_steps_make_trials": (
            trials["steps"] == trials["whole_trials"] * trials["steps_per_trial"]
            and trials["presses"] == trials["whole_trials"] * (trials["steps_per_trial"] - 1)
            and trials["begun"] == trials["whole_trials"] + 1),
        "interest_under_ceiling": all(
            float(run.interest.max()) <= ceiling and interest_band_top(run) <= ceiling
            for run in (physics_run, tabular_run)),
    }
