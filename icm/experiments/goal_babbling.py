"""Forming actions: the simulated iCub learns to press the buttons itself, by goal
babbling (Rolf, Steil and Gienger 2010) with goals chosen by learning progress
(SAGG-RIAC, Baranes and Oudeyer 2013; IMGEP, Forestier, Mollard and Oudeyer 2017).

The experiment: the environment is `icm.envs.buttons.movements.MovementLab` (a
movement is the arm's 7 final joint targets, rolled out in physics), the agent
`icm.learners.goal_babbling.GoalBabblingAgent`, built from an inverse model
(`icm.learners.sensorimotor`) and a goal choice (`icm.learners.goal_choice`). Three
strategies spend the same budget of rollouts:

- "random_motor": uniform random joint targets within the joint ranges;
- "random_goal": uniform random goals in the goal space, through the inverse model;
- "learning_progress": goals in regions chosen by their progress.

Two remedies that the paper's discussion names can be added to any of them: a body
that grows (`maturation`, after Baranes and Oudeyer 2010: `icm.learners.maturation`)
and a teacher who shows the scripted presses of some buttons first (`demonstrations`,
after Thomaz 2006 and Nguyen and Oudeyer's socially guided intrinsic motivation).

A movement's outcome (`OUTCOME_SPACES`) is where it brought the finger (the lowest
point of the finger at the end of the hold) and, by default, how far each cap went
down. All seeds run at once: rollout k of every seed is stepped in one call of
`mujoco.rollout`, and seed k of a batch is seed k run alone.

The goal space, its regions and the outcomes are in
`icm.experiments.babbling_space`, the result class in
`icm.experiments.babbling_results`, the presses formed and the goal-oriented learner
run on them in `icm.experiments.formed_actions`.
"""

import numpy as np

from icm import _validate
from icm._settings import with_settings
from icm.envs import buttons
from icm.envs.buttons import movements as _movements
from icm.envs.buttons.movements import MovementLab
from icm.experiments import loop
from icm.experiments.babbling_results import GoalBabblingResult
from icm.experiments.babbling_space import (DEFAULT_OUTCOME_SPACE, DEPTH_WEIGHT,
                                            MAX_DEPTH_WEIGHT, OUTCOME_SPACES, REGION_GRID,
                                            console_geometry, goal_outcomes,
                                            outcome_vectors, region_grid)
from icm.experiments.formed_actions import press_each_button
from icm.experiments.loop import Transition
from icm.experiments.seeding import check_run_size, run_seeds
from icm.learners import goal_choice as _goal_choice
from icm.learners.goal_babbling import (MATURATION_FIELDS, GoalBabblingAgent,
                                        GoalBabblingSettings)

STRATEGIES = tuple(_goal_choice.STRATEGIES)
"""How the next movement is chosen (see the module docstring): the names of the
strategies registered in `icm.learners.goal_choice.STRATEGIES`."""
DEFAULT_N_ROLLOUTS = 1000
"""Rollouts per run (our choice: the paper has no goal babbling). What the strategies
reach with it is measured in the chapter "Forming actions"."""
N_CHECKPOINTS = 20
"""Checkpoints of the test error, evenly spread over a run."""
REGION_KINDS = tuple(_goal_choice.REGION_KINDS)
"""Learning progress's regions: the fixed `REGION_GRID`, or regions that split as goals
accumulate (`icm.learners.goal_choice.REGION_KINDS`)."""
DEFAULT_INVERSE_MODEL = GoalBabblingSettings.spec("inverse_model").default
"""The inverse model of a run unless told otherwise (`INVERSE_MODELS`)."""
DEFAULT_MEASURE = GoalBabblingSettings.spec("measure").default
"""How learning progress measures a region's progress unless told otherwise
(`MEASURES`)."""
DEFAULT_REGIONS = GoalBabblingSettings.spec("regions").default
"""Learning progress's regions unless told otherwise (`REGION_KINDS`)."""


def check_demonstrations(demonstrations):
    """`demonstrations` as a tuple of distinct buttons (0 to 4), in the order shown:
    None or an empty sequence for no teacher.

    Raises:
      ValueError: for a button outside 0..4 or shown twice (an `ArgumentTypeError` for
        what is not a sequence of integers).
    """
    if demonstrations is None:
        return ()
    if isinstance(demonstrations, (str, bytes)) or not isinstance(
            demonstrations, (tuple, list, np.ndarray)):
        raise _validate.ArgumentTypeError(
            f"demonstrations must be a tuple of buttons (0 to {buttons.N_BUTTONS - 1}), "
            f"each shown at most once, got {_validate.show(demonstrations)}")
    if len(demonstrations) == 0:
        return ()
    shown = _validate.integer_array("demonstrations", demonstrations, ndim=1)
    if np.any((shown < 0) | (shown >= buttons.N_BUTTONS)) or len(set(shown.tolist())) \
            != len(shown):
        raise ValueError(f"demonstrations must be buttons 0 to {buttons.N_BUTTONS - 1}, "
                         f"each shown at most once, got {_validate.show(demonstrations)}")
    return tuple(int(b) for b in shown)


LEARNER_ARGUMENTS = GoalBabblingSettings.names()
"""The arguments of `run_goal_babbling` that are the learner's settings
(`icm.learners.goal_babbling.GoalBabblingSettings`: their ranges, defaults and checks
live there; `with_settings` makes them its keywords, or `settings=`)."""


def _check_run_arguments(learner, n_seeds, n_rollouts, seed, progress, outcome_space,
                         depth_weight, retract, threads, demonstrations):
    checked = dict(
        strategy=learner.strategy,
        n_seeds=_validate.integer_at_least("n_seeds", n_seeds, 1),
        n_rollouts=_validate.integer_at_least("n_rollouts", n_rollouts, 1),
        seed=_validate.root_seed("seed", seed),
        exploration_noise=learner.exploration_noise,
        epsilon=learner.epsilon,
        window=learner.window,
        outcome_space=_validate.one_of("outcome_space", outcome_space, OUTCOME_SPACES),
        inverse_model=learner.inverse_model,
        measure=learner.measure,
        regions=learner.regions,
        depth_weight=_validate.real("depth_weight", depth_weight, 0.0, MAX_DEPTH_WEIGHT,
                                    low_open=True),
        retract=_validate.boolean("retract", retract),
        maturation=learner.maturation,
        **{name: getattr(learner, name) for name in MATURATION_FIELDS},
        demonstrations=check_demonstrations(demonstrations))
    if checked["n_rollouts"] < len(checked["demonstrations"]):
        raise ValueError(f"n_rollouts must be at least the number of demonstrations "
                         f"({len(checked['demonstrations'])}), got {checked['n_rollouts']}")
    _validate.boolean("progress", progress)
    if threads is not None:
        _validate.integer_in_range("threads", threads, 1, _movements.MAX_THREADS)
    n_goals = len(console_geometry()["test_goals"])
    # Per rollout: movement, outcome, depths, goal, flags and two distances per test
    # goal; per seed: one rollout's simulated states.
    check_run_size("run_goal_babbling", checked["n_seeds"], checked["n_rollouts"],
                   8 * (7 + 8 + 5 + 3 + 3 + 1 + 2 * n_goals + int(np.prod(REGION_GRID))),
                   bytes_per_seed=150_000)
    return checked


def checkpoints_of(n_rollouts):
    """The rollouts (counted from 1) after which the test error is measured: up to
    `N_CHECKPOINTS` evenly spread, the last at `n_rollouts`, none at 0."""
    n_rollouts = _validate.integer_at_least("n_rollouts", n_rollouts, 1)
    spread = np.linspace(0, n_rollouts, N_CHECKPOINTS + 1)[1:].round().astype(np.int64)
    return np.unique(np.maximum(spread, 1))


@with_settings(GoalBabblingSettings, positional=("strategy",))
def run_goal_babbling(n_seeds=5, n_rollouts=DEFAULT_N_ROLLOUTS, seed=0, progress=True,
                      outcome_space=DEFAULT_OUTCOME_SPACE, depth_weight=DEPTH_WEIGHT,
                      retract=False, threads=None, demonstrations=(), first_run=0,
                      settings=None):
    """Runs goal babbling on the simulated iCub, all seeds at once.

    Every rollout is a movement performed in physics from the start of a trial
    (`mujoco.rollout`, in C). The goal strategies start with `N_BOOTSTRAP` random
    motor commands; then each rollout has a goal, drawn uniformly in the goal space
    ("random_goal") or in a region chosen by its progress ("learning_progress": with
    probability `epsilon` a region drawn uniformly, otherwise one drawn with
    probability proportional to its interest, uniformly while every interest is 0),
    and the inverse model gives a movement for it, plus exploration noise (see
    `icm.learners.sensorimotor`).

    With `maturation="joint_range"` the arm grows up: it reaches a range of joint
    angles around its resting posture that grows as its competence stops progressing
    (`icm.learners.maturation.JointRangeMaturation`, its clock set by the
    `maturation_*` settings). With
    `demonstrations`, a teacher first moves the arm to the scripted press's lowest
    posture of each button listed, one rollout each, counted in `n_rollouts`: the
    movement and what it did enter the inverse model's memory, and the robot then
    babbles as without a teacher (see `icm.learners.goal_babbling`).

    At the end, each seed's movement whose outcome lies nearest each button's press
    goal is run on the physics console, the button lit red.

    Args:
      strategy: one of `STRATEGIES` (a setting of the learner, which may also come
        first, by position).
      n_seeds: independent runs (>= 1).
      n_rollouts: movements per run (>= 1).
      seed: the root seed: an integer >= 0, a `numpy.random.Generator` or None; run
        i's seeds depend only on it and i (kept in `settings["seed"]`).
      progress: show a progress bar over the rollouts when the run lasts over a
        second.
      outcome_space: one of `OUTCOME_SPACES`.
      depth_weight: how much a cap's depth counts in "point_and_depths", in (0,
        `MAX_DEPTH_WEIGHT`].
      retract: also simulate each movement's return home while babbling (the depths
        then cover it too); the outcome is read at the end of the hold either way.
      threads: threads stepping the rollouts, 1 to `movements.MAX_THREADS` (None:
        the cores this process may use). The results do not depend on it.
      demonstrations: the buttons the teacher shows, in order, each at most once (a
        tuple of integers 0 to 4; empty or None: no teacher).
      first_run: the index of the first run (>= 0): the seeds are runs first_run to
        first_run + n_seeds - 1 of the root seed, so that a large study can be run in
        pieces (run 7 alone is run 7 of any larger batch; kept in
        `settings["first_run"]`).

    Returns:
      A `GoalBabblingResult`.

    Raises:
      ValueError: for any argument outside its allowed range, or a run too large for
        this machine's memory.
    """
    settings = _check_run_arguments(settings, n_seeds, n_rollouts, seed, progress,
                                    outcome_space, depth_weight, retract, threads,
                                    demonstrations)
    settings["first_run"] = _validate.integer_at_least("first_run", first_run, 0)
    lab = MovementLab(threads)
    seeds = run_seeds(settings["seed"], n_seeds, 2, first=settings["first_run"])
    arrays = _babble(settings, lab, [s[0] for s in seeds], progress)
    geometry = console_geometry()
    outcomes, movements = arrays["outcomes"], arrays["movements"]
    space = settings["outcome_space"]
    checkpoints = checkpoints_of(n_rollouts)
    test_goals = geometry["test_goals"]
    weight = settings["depth_weight"]
    reached = outcome_vectors(outcomes, arrays["depths"], space, weight)
    wanted = goal_outcomes(test_goals, space, weight)
    distance = np.sqrt(((reached[:, :, None, :] - wanted[None, None]) ** 2).sum(axis=3))
    best = np.minimum.accumulate(distance, axis=1)  # [seed, rollout, goal]
    test_error = best[:, checkpoints - 1].mean(axis=2)
    to_press = distance[:, :, :buttons.N_BUTTONS].argmin(axis=1)  # [seed, button]
    press_movements = np.take_along_axis(movements, to_press[:, :, None], axis=1)
    press_outcomes = np.take_along_axis(outcomes, to_press[:, :, None], axis=1)
    buttons_pressed = press_each_button(lab, press_movements, [s[1] for s in seeds])
    return GoalBabblingResult(settings, checkpoints, test_goals.copy(), test_error,
                              buttons_pressed, press_movements, press_outcomes, movements,
                              outcomes, arrays["depths"], arrays["touched"],
                              arrays["pressed"], arrays["goals"], arrays["regions"],
                              arrays["interest"], arrays["maturity"])


def _babble(settings, lab, seeds, progress):
    """The rollouts of a run, all seeds at once (one generator per seed, from `seeds`):
    a dict of the arrays `GoalBabblingResult` keeps per rollout."""
    learner = GoalBabblingSettings(**{name: settings[name] for name in LEARNER_ARGUMENTS})
    agent = make_agent(lab, seeds, settings["n_rollouts"], learner, settings["outcome_space"],
                       settings["depth_weight"], settings["demonstrations"])
    return babble(agent, lab, settings["n_rollouts"], settings["outcome_space"],
                  settings["depth_weight"], settings["retract"], progress,
                  description=f"goal babbling ({settings['strategy']}, {len(seeds)} seeds "
                              f"at once)")


def make_agent(lab, seeds, n_rollouts, settings=None, outcome_space=DEFAULT_OUTCOME_SPACE,
               depth_weight=DEPTH_WEIGHT, demonstrations=()):
    """The goal-babbling learner of a run on `lab`, one row per seed, as
    `run_goal_babbling` builds it (`GoalBabblingAgent.from_settings` on this
    experiment's goal space, its goals turned into outcomes of `outcome_space`).

    Args:
      lab: the `icm.envs.buttons.movements.MovementLab` it babbles on.
      seeds: one integer seed per row (each row's generator).
      n_rollouts: the rollouts it will make (its inverse model keeps them all).
      settings: a `icm.learners.goal_babbling.GoalBabblingSettings` (None: the
        library's).
      outcome_space, depth_weight: as `run_goal_babbling`'s.
      demonstrations: the buttons the teacher shows, as `run_goal_babbling`'s.

    Returns:
      A `GoalBabblingAgent`.
    """
    _validate.instance("lab", lab, MovementLab)
    n_rollouts = _validate.integer_at_least("n_rollouts", n_rollouts, 1)
    space = _validate.one_of("outcome_space", outcome_space, OUTCOME_SPACES)
    weight = _validate.real("depth_weight", depth_weight, 0.0, MAX_DEPTH_WEIGHT, low_open=True)
    shown = lab.press_postures[list(check_demonstrations(demonstrations))]
    n_outcome = 3 if space == "point" else 3 + buttons.N_BUTTONS
    return GoalBabblingAgent.from_settings(
        settings, [np.random.default_rng(s) for s in seeds], lab.lower, lab.upper,
        n_rollouts, n_outcome, region_grid(), lab.home,
        lambda goals: goal_outcomes(goals, space, weight), demonstrations=shown)


class Rollouts:
    """A `MovementLab` as the goal-babbling learner plays it, for the one loop
    (`icm.experiments.loop.play`): an episode is one rollout from the resting posture
    (no state); its action the arm's joint targets; its outcome what
    `MovementLab.perform` measured, its state after the outcome vector the learner
    perceives (in `outcome_space`, `outcome_vectors`). Every row moves at every
    rollout.

    Args:
      lab: the `MovementLab` the movements are rolled out on.
      n_rows: the rows (seeds).
      outcome_space, depth_weight: how a movement's outcome is read (as
        `run_goal_babbling`'s).
      retract: also simulate each movement's return home.
    """

    def __init__(self, lab, n_rows, outcome_space=DEFAULT_OUTCOME_SPACE,
                 depth_weight=DEPTH_WEIGHT, retract=False):
        self.lab, self.n_rows = lab, n_rows
        self.outcome_space, self.depth_weight, self.retract = outcome_space, depth_weight, retract
        self._ended = np.ones(n_rows, dtype=bool)

    def __len__(self):
        return self.n_rows

    def reset(self, rows):
        """A new rollout, from the resting posture: no state."""
        return None

    def step(self, rows, states, targets):
        """Rolls out the movements `targets` [rows, joints]."""
        done = self.lab.perform(targets, self.retract)
        reached = outcome_vectors(done["point"], done["depths"], self.outcome_space,
                                  self.depth_weight)
        return Transition(reached, done, None, 1.0, self._ended)


class Babbler:
    """A `GoalBabblingAgent` as the one loop drives it: `act` is its `produce` (each
    step's `info`, its goals and their regions, None while it babbles at random),
    `learn` its `perceive` of what the movements reached (the distances to the goals
    are the step's `learned`).

    Args:
      agent: the `GoalBabblingAgent`.
    """

    def __init__(self, agent):
        self.agent = agent

    def act(self, rows, states):
        """Every row's next movement, and its (goals, regions)."""
        targets, goal, region = self.agent.produce()
        return targets, (goal, region)

    def learn(self, step):
        """Every row learns what its movement reached."""
        return self.agent.perceive(step.action, step.after)


class RolloutLog:
    """The observer that keeps, per rollout, what a `GoalBabblingResult` holds of it:
    the movement, where it brought the finger, the caps' depths, whether it touched and
    pressed, its goal and region, the regions' interest and the maturational clock.

    Args:
      agent: the `GoalBabblingAgent` (its goal choice and clock, read after each
        rollout).
      n_rollouts: the run's rollouts.
    """

    def __init__(self, agent, n_rollouts):
        self.agent = agent
        n_seeds = agent.n_rows
        self.arrays = {
            "movements": np.zeros((n_seeds, n_rollouts, 7)),
            "outcomes": np.zeros((n_seeds, n_rollouts, 3)),
            "depths": np.zeros((n_seeds, n_rollouts, buttons.N_BUTTONS)),
            "touched": np.zeros((n_seeds, n_rollouts), dtype=bool),
            "pressed": np.zeros((n_seeds, n_rollouts), dtype=np.int64),
            "goals": np.full((n_seeds, n_rollouts, 3), np.nan),
            "regions": np.full((n_seeds, n_rollouts), -1, dtype=np.int64),
            "interest": np.zeros((n_seeds, n_rollouts, region_grid().n_regions)),
            "maturity": np.ones((n_seeds, n_rollouts))}

    def __call__(self, step):
        i, done, (goal, region) = step.episode[0], step.outcome, step.info
        out = self.arrays
        out["movements"][:, i], out["outcomes"][:, i] = step.action, done["point"]
        out["depths"][:, i] = done["depths"]
        out["touched"][:, i], out["pressed"][:, i] = done["touched"], done["pressed"]
        if goal is not None:
            out["goals"][:, i], out["regions"][:, i] = goal, region
            # The regions' interest (0 everywhere for goals that do not follow it).
            out["interest"][:, i] = self.agent.goal_choice.values()
        if self.agent.maturation is not None:
            out["maturity"][:, i] = self.agent.maturation.psi


def babble(agent, lab, n_rollouts, outcome_space=DEFAULT_OUTCOME_SPACE,
           depth_weight=DEPTH_WEIGHT, retract=False, progress=False, observe=None,
           description="goal babbling"):
    """Plays `n_rollouts` rollouts of a goal-babbling learner on `lab`, all rows at
    once, through the one loop (`icm.experiments.loop.play`: `Rollouts`, `Babbler`,
    `RolloutLog`): what `run_goal_babbling` does once it has built them (then it tests
    the presses), open to any learner of the same shape.

    Args:
      agent: a `GoalBabblingAgent` (`make_agent` builds the run's), one row per seed.
      lab: the `icm.envs.buttons.movements.MovementLab` the movements are rolled out
        on.
      n_rollouts: rollouts to play (>= 1).
      outcome_space, depth_weight: how a movement's outcome is read (as
        `run_goal_babbling`'s).
      retract: also simulate each movement's return home.
      progress: show a progress bar over the rollouts when they last over a second.
      observe: None, or a function called with every rollout, a
        `icm.experiments.loop.Step` of every row: its `episode` the rollout, `action`
        the movements, `info` their (goals, regions), `outcome` what
        `MovementLab.perform` measured, `after` the outcome vectors perceived.
      description: the progress bar's words.

    Returns:
      A dict of the arrays `GoalBabblingResult` keeps per rollout ("movements",
      "outcomes", "depths", "touched", "pressed", "goals", "regions", "interest",
      "maturity"), each [seed, rollout, ...].

    Raises:
      ValueError: for a bad argument.
    """
    _validate.instance("agent", agent, GoalBabblingAgent)
    _validate.instance("lab", lab, MovementLab)
    n_rollouts = _validate.integer_at_least("n_rollouts", n_rollouts, 1)
    space = _validate.one_of("outcome_space", outcome_space, OUTCOME_SPACES)
    weight = _validate.real("depth_weight", depth_weight, 0.0, MAX_DEPTH_WEIGHT, low_open=True)
    retract = _validate.boolean("retract", retract)
    observe = _validate.function("observe", observe)
    log = RolloutLog(agent, n_rollouts)
    bar = loop.progress(n_rollouts, description, progress, "rollout", per=agent.n_rows)
    try:
        loop.play(Rollouts(lab, agent.n_rows, space, weight, retract), Babbler(agent),
                  n_rollouts, [log, bar, observe])
    finally:
        if bar is not None:
            bar.close()
    return log.arrays


