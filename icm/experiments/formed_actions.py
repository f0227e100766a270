"""The actions goal babbling formed: whether the movement a run learned for each button
presses it, alone, on the physics console (`press_each_button`, `presses_formed` at
any budget, `press_failures` for those that do not), and the paper's goal-oriented
learner run on the physics console with those movements as its five press actions
(`run_formed_actions`, a `FormedActionsResult`)."""

import dataclasses

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.envs.buttons.movements import MovementLab
from icm.experiments.babbling_results import GoalBabblingResult
from icm.experiments.babbling_space import console_geometry, goal_outcomes, outcome_vectors
from icm.experiments.goal_oriented import run_goal_oriented_grid
from icm.experiments.goal_oriented_results import GoalOrientedResult
from icm.experiments.seeding import run_seeds
from icm.stats import comes_first

DEFAULT_TRIALS = 30
"""Trials of the goal-oriented learner on the formed actions (`run_formed_actions`)."""


def presses_formed(result, rollouts):
    """Whether each seed had formed a press for each button after `rollouts` rollouts:
    the movement among its first n rollouts whose outcome lies nearest the button's
    press goal, tested on the physics console as at the end of a run (so that at
    n = `n_rollouts` it is `buttons_pressed`).

    Args:
      result: a `GoalBabblingResult`.
      rollouts: increasing whole rollout counts in 1..n_rollouts.

    Returns:
      A bool array [len(rollouts), seed, button].
    """
    _validate.instance("result", result, GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    rollouts = _validate.integer_array("rollouts", rollouts, ndim=1)
    if not len(rollouts) or np.any(np.diff(rollouts) <= 0) or rollouts[0] < 1 \
            or rollouts[-1] > result.n_rollouts:
        raise ValueError(f"rollouts must be increasing rollout counts in 1.."
                         f"{result.n_rollouts}, got {_validate.show(rollouts)}")
    settings = result.settings
    space, weight = settings["outcome_space"], settings["depth_weight"]
    reached = outcome_vectors(result.outcomes, result.depths, space, weight)
    wanted = goal_outcomes(console_geometry()["press_goals"], space, weight)
    distance = np.sqrt(((reached[:, :, None, :] - wanted[None, None]) ** 2).sum(axis=3))
    seeds = [s[1] for s in run_seeds(settings["seed"], result.n_seeds, 2,
                                     first=settings.get("first_run", 0))]
    lab = MovementLab(1)
    out = np.zeros((len(rollouts), result.n_seeds, buttons.N_BUTTONS), dtype=bool)
    tested = np.full((result.n_seeds, buttons.N_BUTTONS), -1)  # rollout tested last
    for i, n in enumerate(rollouts):
        nearest = distance[:, :n].argmin(axis=1)  # [seed, button]
        movements = np.take_along_axis(result.movements, nearest[:, :, None], axis=1)
        # A press test depends on the movement, the seed and the button only: a
        # movement still the nearest at this budget keeps the result it had.
        changed = nearest != tested
        out[i] = np.where(changed, press_each_button(lab, movements, seeds, changed),
                          out[i - 1] if i else False)
        tested = nearest
    return out


PRESS_FAILURES = ("formed", "not pushed in far enough", "off the cap",
                  "a neighbour pushed too", "a neighbour pushed instead", "other")
"""What became of the movement formed for each button (`press_failures`), by code."""


def press_failures(result):
    """What became of the movement formed for each button: a code into
    `PRESS_FAILURES` per [seed, button].

    "formed" where `buttons_pressed` holds. Otherwise the movement is rolled out again
    with its return home and read: "a neighbour pushed too" if the button and
    another went past the press depth, "a neighbour pushed instead" if only another
    did, "not pushed in far enough" if none did and the finger ended over the cap
    (within its radius of its centre), "off the cap" if none did and it ended
    elsewhere, and "other" if the button alone was pushed yet the red box alone did
    not open.

    Args:
      result: a `GoalBabblingResult`.
    """
    _validate.instance("result", result, GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    geometry = console_geometry()
    lab = MovementLab(1)
    n_seeds = result.n_seeds
    done = lab.perform(result.press_movements.reshape(-1, 7), retract=True)
    over = done["depths"].reshape(n_seeds, buttons.N_BUTTONS, buttons.N_BUTTONS) \
        > buttons.PRESS_DEPTH  # [seed, movement for button, button pushed]
    across = np.linalg.norm(result.press_outcomes[..., :2] - geometry["caps"][:, :2], axis=2)
    codes = np.full((n_seeds, buttons.N_BUTTONS), PRESS_FAILURES.index("other"))
    for b in range(buttons.N_BUTTONS):
        own, others = over[:, b, b], np.delete(over[:, b], b, axis=1).any(axis=1)
        on_cap = across[:, b] <= geometry["cap_radius"]
        codes[own & others, b] = PRESS_FAILURES.index("a neighbour pushed too")
        codes[~own & others, b] = PRESS_FAILURES.index("a neighbour pushed instead")
        codes[~own & ~others & on_cap, b] = PRESS_FAILURES.index("not pushed in far enough")
        codes[~own & ~others & ~on_cap, b] = PRESS_FAILURES.index("off the cap")
    codes[result.buttons_pressed] = PRESS_FAILURES.index("formed")
    return codes


def press_each_button(lab, press_movements, seeds, which=None):
    """[seed, button]: whether the movement for each button, run on a physics console
    where that button is lit red (one console per button), presses that button and
    no other, and opens the red box only; only where `which` ([seed, button] bools)
    holds, if given (False elsewhere)."""
    n_seeds = len(press_movements)
    out = np.zeros((n_seeds, buttons.N_BUTTONS), dtype=bool)
    which = np.ones_like(out) if which is None else which
    check = buttons.physics.check_press_motions
    for button in range(buttons.N_BUTTONS):
        if not which[:, button].any():
            continue
        console = buttons.PhysicsButtonConsole(red_button=button)
        for k in np.flatnonzero(which[:, button]):
            console.press_motions = check([lab.phases(m) for m in press_movements[k]])
            console.reseed(seeds[k])
            console.reset()
            boxes = console.press(button)
            out[k, button] = (set(console.task.press_log) == {button}
                              and boxes.tolist() == [1, 0])
    return out


@dataclasses.dataclass(frozen=True)
class FormedActionsResult:
    """What `run_formed_actions` measured.

    Attributes:
      settings: the arguments of the run, as a dict.
      learner: the goal-oriented learner's `GoalOrientedResult` on the console whose
        five actions are the formed movements.
      as_scripted: the share of the learner's presses whose effect (which box
        opened) is what the scripted press of the same button gives in that layout.
      n_presses: the presses the learner made, over all seeds.
      as_scripted_per_seed: [seed], that share in each seed's presses (every seed
        makes the same number of presses).
    """

    settings: dict
    learner: GoalOrientedResult
    as_scripted: float
    n_presses: int
    as_scripted_per_seed: np.ndarray

    def red_first_fraction(self):
        """Share of seeds in which red is mastered strictly before green (see
        `GoalOrientedResult.red_first_fraction`)."""
        return self.learner.red_first_fraction()

    def red_first(self):
        """[seed], whether red is mastered strictly before green in each seed."""
        mastery = self.learner.mastery_trial
        return comes_first(mastery[:, 0], mastery[:, 1])


def run_formed_actions(babbling, n_trials=DEFAULT_TRIALS, seed=0, progress=True,
                       first_run=0):
    """Runs the paper's goal-oriented learner on the physics console, with the movements
    the robot formed by goal babbling as its five press actions.

    Row k of the learner uses seed k's learned movements (`press_movements`) and the
    seeds `run_goal_oriented(n_seeds, n_trials, seed=seed)` gives its run k, so the two
    can be compared seed by seed. The learner keeps its defaults (the paper's).

    Args:
      babbling: a `GoalBabblingResult`.
      n_trials: trials per run (>= 1).
      seed: the root seed of the learner's runs (as in `run_goal_oriented`).
      progress: show a progress bar over the trials.
      first_run: the index of the learner's first run (>= 0): row k uses run
        first_run + k of `seed` (pass the babbling's own `first_run` to keep the
        seed-by-seed pairing of a run made in pieces).

    Returns:
      A `FormedActionsResult`.

    Raises:
      ValueError: for a bad argument.
    """
    _validate.instance("babbling", babbling, GoalBabblingResult,
                       "a GoalBabblingResult (from icm.experiments.run_goal_babbling)")
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    _validate.boolean("progress", progress)
    first_run = _validate.integer_at_least("first_run", first_run, 0)
    lab = MovementLab()
    motions = [[lab.phases(m) for m in movements] for movements in babbling.press_movements]
    red, presses = buttons.DEFAULT_RED_BUTTON, buttons.DEFAULT_PRESSES_PER_TRIAL
    log = []

    def formed_console(env_seeds):
        return buttons.PhysicsButtonConsoleBatch(env_seeds, red, presses,
                                                 press_motions=motions)

    def record(step):  # every press: the layouts, the buttons pressed, their effects
        log.append((step.before.copy(), np.asarray(step.action).copy(), step.outcome.copy()))

    learner, = run_goal_oriented_grid(
        [{}], n_seeds=babbling.n_seeds, n_trials=n_trials, presses_per_trial=presses,
        red_button=red, physics=True, seed=seed, progress=progress,
        make_env=formed_console, observe=record, first_run=first_run)
    settings = learner.settings
    settings["formed_by"] = babbling.strategy
    settings["first_run"] = first_run
    table = buttons.outcome_table(red)
    matches = np.array([table[layout, actions] == effects
                        for layout, actions, effects in log])  # [press, seed]
    return FormedActionsResult(settings, learner, float(np.mean(matches)), int(np.size(matches)),
                               matches.mean(axis=0))
