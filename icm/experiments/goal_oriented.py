"""The goal-oriented learner on the button console, over many seeds (Figure 5).

All seeds run at once (`icm.learners.goal_oriented.GoalOrientedBatch` on
`icm.envs.buttons.ButtonConsoleBatch`): seed k of a batch is seed k run alone, and the
per-agent classes give the same numbers (a test runs both).
"""

import numpy as np

from icm import _streams, _validate
from icm._settings import with_settings
from icm.envs import buttons
from icm.experiments import _grid, loop
from icm.experiments._memory import FIXED_BYTES, PHYSICS_SCENE_BYTES, check_memory
from icm.experiments.loop import Transition
from icm.experiments.goal_oriented_results import TASKS, GoalOrientedResult
from icm.experiments.seeding import run_seeds
from icm.learners import action_selection, goal_oriented, interest
from icm.stats import first_from_which

_REST = (0, 0)
TASK_KEYS = {"red": (_REST, (1, 0)), "green": (_REST, (0, 1)), "nothing": (_REST, (0, 0))}
"""The agent's task keys (boxes at rest -> boxes after the press) by name."""
_TASK_EFFECTS = (buttons.RED_BOX, buttons.GREEN_BOX)  # red, green, as TASKS
CHAPTER_SEEDS = 200
"""Runs of the chapter "Goal-oriented interest" (its Figure 5; `python -m icm figure5`)."""
CHAPTER_TRIALS = 60
"""Trials per run in that chapter: its Figure 5 and panel, its exercises' runs, its
robustness maps and `python -m icm figure5`."""


def _check_run_arguments(n_seeds, n_trials, presses_per_trial, red_button, noisy_button,
                         physics, seed, settings):
    """The run's own arguments (its learner's `settings` are checked already), checked
    and normalised, with the settings' values, as the result's `settings` dict; the
    run's memory is checked too."""
    checked = dict(
        n_seeds=_validate.integer_at_least("n_seeds", n_seeds, 1),
        n_trials=_validate.integer_at_least("n_trials", n_trials, 1),
        presses_per_trial=buttons.PRESSES_PER_TRIAL.check(presses_per_trial,
                                                          "presses_per_trial"),
        red_button=buttons.check_red_button(red_button),
        noisy_button=_validate.boolean("noisy_button", noisy_button),
        physics=_validate.boolean("physics", physics),
        seed=_validate.root_seed("seed", seed))
    checked = {**checked, **settings.as_dict()}
    check_memory("run_goal_oriented", {"n_seeds": checked["n_seeds"],
                                       "n_trials": checked["n_trials"]},
                 memory_needed(checked["n_seeds"], **_memory_arguments(checked))[0])
    return checked


LOOP_ROW_BYTES = 1500
"""An upper bound on the temporaries of a press and of a trial's reduction, per row,
besides the predictor's distances (counted from their shape)."""


def _memory_arguments(checked):
    """The arguments of `memory_needed` from checked run arguments (but n_rows)."""
    return {name: checked[name] for name in ("n_trials", "presses_per_trial", "window",
                                             "interest_per", "noisy_button", "physics")}


def memory_needed(n_rows, n_trials, presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL,
                  window=interest.DEFAULT_WINDOW, interest_per="task", noisy_button=False,
                  physics=False, one_action_weight=True):
    """An upper bound on the memory a batch of `n_rows` runs of `run_goal_oriented`
    adds to the process, in bytes, counted from its arrays' shapes (see
    `icm.experiments._memory`). `one_action_weight`: whether every row has the same
    action weight (a grid may vary it: the predictor then computes each row's
    distances anew at every press).

    Returns:
      (peak, kept): the bound on the run's peak, and the bytes of its result.
    """
    n_actions, n_tasks = buttons.n_actions(noisy_button), len(TASKS)
    n_keys = len(buttons.EFFECTS) if interest_per == "task" else n_actions
    row_trials = n_rows * n_trials
    # The result, per row and trial: interest, prediction_error, practice [task];
    # button_share, action_interest [button].
    kept = 8 * row_trials * (3 * n_tasks + 2 * n_actions)
    # While it is made: the presses counted [button], and the masks that find the
    # mastery trials.
    making = 8 * row_trials * (n_actions + 1)
    n_pairs = 4 * n_actions  # the predictor's keys: (layout, button)
    learner = n_rows * (8 * n_keys * (window + 2)  # the interest: last errors, count, progress
                        + 16 * n_pairs  # the predictor: distance, effect per key
                        + 8 * n_pairs * (1 if one_action_weight else 4)  # a press's distances
                        + LOOP_ROW_BYTES)
    slopes = 8 * (window + 1) ** 2 * window  # the interest's table of slope weights
    presses = n_trials * presses_per_trial
    streams = _streams.memory_bound(n_rows, presses * action_selection.DRAWS_PER_CHOICE)
    if physics:  # a simulated console per row
        consoles = n_rows * PHYSICS_SCENE_BYTES
    else:  # the tabular consoles' numbers: a layout per trial, one per noisy press
        consoles = _streams.memory_bound(n_rows, n_trials + (presses if noisy_button else 0))
    return FIXED_BYTES + kept + making + learner + slopes + streams + consoles, kept


@with_settings(goal_oriented.GoalOrientedSettings)
def run_goal_oriented(n_seeds=100, n_trials=100,
                      presses_per_trial=buttons.PRESSES_PER_TRIAL.default,
                      red_button=buttons.DEFAULT_RED_BUTTON,
                      noisy_button=False,
                      physics=False,
                      seed=0,
                      progress=True,
                      settings=None):
    """Runs the goal-oriented learner on the button console, all seeds at once.

    Each run has a console, a nearest-neighbour predictor, an interest module and an
    epsilon-greedy actor with its own seeds (drawn from `seed`), and plays `n_trials`
    trials. After each trial it records the interest in the red and green tasks and
    tests the predictor on every (layout, button) pair.

    Args:
      n_seeds: number of independent runs (>= 1).
      n_trials: trials per run (>= 1).
      presses_per_trial: presses per trial (see `icm.envs.buttons.PRESSES_PER_TRIAL`).
      red_button: the button that is always red (0-4).
      noisy_button: add the noisy button, action 5: never lit, each press opens the red
        box, the green box or neither, 1/3 each (on the tabular console and on the
        simulated one alike).
      physics: False for the tabular console (default), True for the simulated iCub
        (about 11 ms of computing per press). The same seeds give the same layouts
        and, the physics agreeing with its twin, the same results.
      seed: the root seed: an integer >= 0, a `numpy.random.Generator` (one integer
        is drawn from it) or None (fresh entropy); run i's seeds depend only on it
        and i. The integer used is kept in `settings["seed"]`.
      progress: show a progress bar over the trials when the run lasts over a second.
      settings: the learner's settings, a
        `icm.learners.goal_oriented.GoalOrientedSettings` (or give them one by one as
        keyword arguments, listed below).

    Returns:
      A `GoalOrientedResult`.

    Raises:
      ValueError: for any argument outside its allowed range, or a run too large for
        this machine's memory.
    """
    return run_goal_oriented_grid(
        [{}], n_seeds=n_seeds, n_trials=n_trials, presses_per_trial=presses_per_trial,
        red_button=red_button, noisy_button=noisy_button, physics=physics, seed=seed,
        progress=progress, settings=settings)[0]


GRID_ARGUMENTS = _grid.grid_arguments(run_goal_oriented)
"""The settings that may differ between the settings of one `run_goal_oriented_grid`
(the batched learner takes them per row): those of
`icm.learners.goal_oriented.GoalOrientedSettings` that are per row."""


def run_goal_oriented_grid(grid, make_env=None, observe=None, first_run=0, **arguments):
    """Runs `run_goal_oriented(**arguments, **setting)` for every setting of `grid`, all
    in one batch (each setting's seeds are rows of the batched learner, which takes
    these settings per row).

    Result k is identical to the separate run of setting k (the same seeds, the same
    numbers; a test checks it): `run_goal_oriented` itself is this function with one
    setting. A grid of many settings costs far less than the settings one by one.

    Args:
      grid: a non-empty list of dicts, each a setting of some of `GRID_ARGUMENTS`
        (those left out take their value from `arguments`, or the default).
      make_env: None (the console `physics` names), or a function that takes the
        rows' console seeds (a list of integers, one per row) and returns the batched
        console to play on (as `icm.envs.buttons.ButtonConsoleBatch`: `new_trials`,
        `press`, `n_actions`, `effects`, `red_button`), for example a physics console
        whose presses are movements the robot formed.
      observe: None, or a function called with every press of every row, a
        `icm.experiments.loop.Step` (see `play`).
      first_run: the index of the first run (>= 0): a setting's rows are runs
        first_run to first_run + n_seeds - 1 of the root seed (run 7 alone is run 7 of
        any larger batch), so that a long study can run in pieces.
      **arguments: any other arguments of `run_goal_oriented`, the same for every
        setting (n_seeds, n_trials, seed, progress, learner settings, ...).

    Returns:
      A list of `GoalOrientedResult`, one per setting, in the grid's order.

    Raises:
      ValueError: for a malformed grid, a setting of an argument not in
        `GRID_ARGUMENTS`, or any value `run_goal_oriented` refuses.
    """
    _validate.function("make_env", make_env)
    _validate.function("observe", observe)
    first_run = _validate.integer_at_least("first_run", first_run, 0)
    blocks, others, progress = _grid.check_settings_grid(grid, run_goal_oriented, arguments)
    settings = [_check_run_arguments(**others, settings=block) for block in blocks]
    first, n = settings[0], settings[0]["n_seeds"]
    if len(settings) > 1:  # the settings' rows side by side, the longest window for all
        check_memory("run_goal_oriented_grid", {"settings": len(settings), "n_seeds": n,
                                                "n_trials": first["n_trials"]},
                     memory_needed(n * len(settings), **{
                         **_memory_arguments(first),
                         "window": max(s["window"] for s in settings),
                         "one_action_weight": len({s["action_weight"] for s in settings}) == 1
                     })[0])
    seeds = run_seeds(first["seed"], n, 2, first=first_run) * len(settings)
    env, agent = make(first, seeds, goal_oriented.GoalOrientedSettings.stack(blocks, n),
                      make_env)
    result = play(env, agent, first["n_trials"], first["presses_per_trial"], observe=observe,
                  progress=progress, settings=first)
    return _grid.split(result, settings, n)


def make(settings, seeds, learner=None, make_env=None):
    """The console and the learner of a run of `run_goal_oriented`, one row per seed, as
    the run builds them.

    Args:
      settings: the run's settings, as a result keeps them (`red_button`,
        `noisy_button`, `physics`, `presses_per_trial`, and the learner's).
      seeds: one [console seed, learner seed] per row (`icm.experiments.seeding.
        run_seeds(seed, n_seeds, 2)`).
      learner: the learner's settings, a `icm.learners.goal_oriented.
        GoalOrientedSettings` whose per-row settings may hold one value per row (None:
        those of `settings`).
      make_env: as `run_goal_oriented_grid`'s (None: the console `physics` names).

    Returns:
      (env, agent): the batched console and the batched learner
      (`icm.learners.goal_oriented.GoalOrientedBatch`).
    """
    if learner is None:
        learner = goal_oriented.GoalOrientedSettings(
            **{name: settings[name] for name in goal_oriented.GoalOrientedSettings.names()})
    env_seeds, agent_seeds = [s[0] for s in seeds], [s[1] for s in seeds]
    red_button = settings["red_button"]
    if make_env is not None:
        env = make_env(env_seeds)
    elif settings["physics"]:
        env = buttons.PhysicsButtonConsoleBatch(env_seeds, red_button,
                                                settings["presses_per_trial"],
                                                settings["noisy_button"])
    else:
        env = buttons.ButtonConsoleBatch(env_seeds, red_button, settings["noisy_button"])
    agent = goal_oriented.GoalOrientedBatch(
        agent_seeds, np.array(buttons.layouts(red_button)), env.effects, env.n_actions,
        settings=learner)
    return env, agent


class ConsoleTrials:
    """A batched button console as the goal-oriented learner plays it, for the one loop
    (`icm.experiments.loop.play`): an episode is a trial; its state, the layout of the
    lights (an index into `buttons.layouts`), which every press leaves as it was (the
    boxes shut before every press); a press's outcome is the effect it had (an index
    into the console's `effects`); the trial ends after `presses_per_trial` presses.
    Every row moves at every press.

    Args:
      env: a batched console (as `icm.envs.buttons.ButtonConsoleBatch`: `new_trials()`
        gives the rows' layout indices, `press(actions)` their effect indices).
      presses_per_trial: presses per trial.
    """

    def __init__(self, env, presses_per_trial):
        self.env, self.presses_per_trial = env, presses_per_trial
        self._presses = 0
        self._going, self._ending = np.zeros(len(env), dtype=bool), np.ones(len(env), dtype=bool)

    def __len__(self):
        return len(self.env)

    def reset(self, rows):
        """A new trial in every row: the layouts [rows]."""
        self._presses = 0
        return self.env.new_trials()

    def step(self, rows, layouts, actions):
        """Presses `actions` (one button per row)."""
        effects = self.env.press(actions)
        self._presses += 1
        ended = self._ending if self._presses == self.presses_per_trial else self._going
        return Transition(layouts, effects, None, 1.0, ended)


class Chooser:
    """A batched goal-oriented learner as the one loop drives it: `act` is its
    `select_actions`, `learn` its `learn` of the press (the errors it returns are the
    step's `learned`).

    Args:
      agent: the learner (as `icm.learners.goal_oriented.GoalOrientedBatch`).
      explain: also give, as each step's `info`, what the learner knew when it chose:
        {"interest": its interest in every task, "predicted": the effect it predicts
        for each action, "values": each action's interest} (for `trace`).
    """

    def __init__(self, agent, explain=False):
        self.agent, self.explain = agent, explain

    def act(self, rows, layouts):
        """Each row's press in its layout, and what the learner knew (None unless
        `explain`)."""
        if not self.explain:
            return self.agent.select_actions(layouts), None
        info = {"interest": self.agent.interest.values().copy(),
                "predicted": self.agent.predicted_effects(layouts),
                "values": self.agent.action_interests(layouts)}
        return self.agent.select_actions(layouts), info

    def learn(self, step):
        """The learner learns the press; returns its prediction errors [rows]."""
        return self.agent.learn(step.before, step.action, step.outcome)


class TrialSummary:
    """The observer that reduces a run of the goal-oriented learner to its
    `GoalOrientedResult`: after each press the boxes opened and the button pressed,
    after each trial the interest and what the predictor gets wrong, so that a run
    keeps its result and nothing per press.

    Args:
      env: the batched console (its `red_button`, `n_actions`).
      agent: the batched learner (read after each trial: `interest.values()`,
        `interest_per`, `predictor.effect`, `effects`).
      n_trials: the run's trials.
      presses_per_trial: its presses per trial.
    """

    def __init__(self, env, agent, n_trials, presses_per_trial):
        self.agent, self.presses_per_trial = agent, presses_per_trial
        self.red_button = env.red_button
        n_seeds, n_actions = len(env), env.n_actions
        self.n_actions = n_actions
        self.practice = np.zeros((n_seeds, n_trials, len(TASKS)), dtype=np.int64)
        self.presses = np.zeros((n_seeds, n_trials, n_actions), dtype=np.int64)
        self.interest = np.zeros((n_seeds, n_trials, len(TASKS)))
        self.action_interest = np.zeros((n_seeds, n_trials, n_actions))
        self.error = np.zeros((n_seeds, n_trials, len(TASKS)))
        # The share of the 20 (layout, button) pairs on which the predictor is wrong
        # about each box: wrong[predicted effect, true effect, box] is 1 where they differ.
        effects = agent.effects  # buttons.EFFECTS, and on the physics both boxes too
        self.n_effects = len(effects)
        self.wrong = np.abs(effects[:, None, :] - effects[None, :, :]).astype(float)
        self.truth = buttons.outcome_table(self.red_button)
        self.greens = buttons.green_candidates(self.red_button)

    def __call__(self, step):
        trial, observed = step.episode[0], step.outcome
        both = observed == buttons.BOTH_BOXES  # a press of both: practice of both
        for i, box in enumerate(_TASK_EFFECTS):
            self.practice[:, trial, i] += (observed == box) | both
        self.presses[step.rows, trial, step.action] += 1
        if step.ended[0]:
            self._end_of_trial(trial)

    def _end_of_trial(self, trial):
        agent = self.agent
        n_seeds = len(self.practice)
        values = agent.interest.values()
        per_layout = agent.predictor.effect.reshape(n_seeds, 4, self.n_actions)
        if agent.interest_per == "task":
            self.interest[:, trial] = values[:, list(_TASK_EFFECTS)]
            per_layout_interest = np.take_along_axis(values[:, None, :], per_layout, axis=2)
        else:
            self.interest[:, trial] = np.stack([values[:, self.red_button],
                                                values[:, self.greens].mean(axis=1)], axis=1)
            per_layout_interest = np.broadcast_to(values[:, None, :], per_layout.shape)
        self.action_interest[:, trial] = np.moveaxis(per_layout_interest, 1, 0).mean(axis=0)
        pairs = (per_layout[..., :buttons.N_BUTTONS] * self.n_effects
                 + self.truth).reshape(n_seeds, -1)
        for box in range(len(TASKS)):
            self.error[:, trial, box] = self.wrong[..., box].reshape(-1).take(pairs).mean(axis=1)

    def result(self, settings):
        """The `GoalOrientedResult` of the run, keeping `settings` (a dict)."""
        mastery = first_from_which(np.moveaxis(self.error, 1, 2) == 0)
        mastery = np.where(mastery >= 0, mastery + 1, -1)
        share = self.presses / self.presses_per_trial
        return GoalOrientedResult(settings, self.interest, self.error, mastery, self.practice,
                                  share, self.action_interest)


def play(env, agent, n_trials, presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL,
         observe=None, progress=False, settings=None):
    """Plays `n_trials` trials of a batched learner on a batched console through the one
    loop (`icm.experiments.loop.play`), and gathers a `GoalOrientedResult`
    (`TrialSummary`): what `run_goal_oriented` does once it has built them (`make`),
    open to any console and learner of the same shape.

    Args:
      env: a batched console, one row per run (see `ConsoleTrials`; its `n_actions`,
        `red_button`).
      agent: a batched learner with a row per console row (as
        `icm.learners.goal_oriented.GoalOrientedBatch`: `select_actions(layouts)`,
        `learn(layouts, actions, effects)`, `interest.values()`, `interest_per`,
        `predictor.effect`, `effects`).
      n_trials: trials to play (>= 1).
      presses_per_trial: presses per trial (see `icm.envs.buttons.PRESSES_PER_TRIAL`).
      observe: None, or a function called with every press, a
        `icm.experiments.loop.Step` of every row: its `episode` the trial, its `before`
        the layouts, `action` the buttons pressed, `outcome` the effects (indices into
        the console's `effects`) and `learned` the prediction errors: a recorder of
        the presses, for example.
      progress: show a progress bar over the trials when the run lasts over a second.
      settings: the dict the result keeps as its `settings` (None: an empty dict).

    Returns:
      A `GoalOrientedResult`.

    Raises:
      ValueError: for a bad `n_trials` or `presses_per_trial`.
    """
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    presses_per_trial = buttons.PRESSES_PER_TRIAL.check(presses_per_trial, "presses_per_trial")
    observe = _validate.function("observe", observe)
    _validate.boolean("progress", progress)
    settings = {} if settings is None else _validate.instance("settings", settings, dict)
    summary = TrialSummary(env, agent, n_trials, presses_per_trial)
    bar = loop.progress(n_trials, "goal-oriented learner", progress, "trial", per=len(env))
    try:
        loop.play(ConsoleTrials(env, presses_per_trial), Chooser(agent), n_trials,
                  [summary, bar, observe])
    finally:
        if bar is not None:
            bar.close()
    return summary.result(settings)


class _RecordedDraws:
    """A learner's streams that keep the last numbers drawn (`trace` reads them)."""

    def __init__(self, streams):
        self.streams, self.last = streams, None

    def draw(self, rows=None, k=1):
        self.last = self.streams.draw(rows, k).copy()
        return self.last


def trace(n_trials=2, n_seeds=1, seed=0):
    """The first `n_trials` trials of `run_goal_oriented(n_seeds=n_seeds, seed=seed)`
    (the library's settings), press by press: what the learner knew, chose and
    learned. Row k is the same run as seed k of `run_goal_oriented` (a test checks it):
    the run's console and learner (`make`) played through the one loop, observed.

    Lights and predictions are written one letter a button: "R" red, "G" green, "-"
    off; under `predicts`, the box the predictor expects the press to open ("-" none),
    so that it is right about a layout where `predicts` reads like `lights`.

    Returns:
      A pandas DataFrame, one row per press: `seed`, `trial` and `press` (from 1);
      `lights`; `predicts`; the interest of each task before the press (`nothing`,
      `red`, `green`); `button`, the button pressed; `why`: "most interesting", "tie"
      (the most interesting buttons tie, one is drawn at random) or "random" (an
      epsilon press); `opened`, the task that happened, whose history gets `error`,
      the prediction error; `wrong_red`, `wrong_green`: after the press, of the 20
      (layout, button) pairs, those whose box the predictor gets wrong (0: mastered).

    Raises:
      ValueError: for an argument `run_goal_oriented` refuses.
    """
    import pandas as pd  # here: pandas is slow to import

    settings = _check_run_arguments(n_seeds, n_trials, buttons.DEFAULT_PRESSES_PER_TRIAL,
                                    buttons.DEFAULT_RED_BUTTON, False, False, seed,
                                    goal_oriented.GoalOrientedSettings())
    env, agent = make(settings, run_seeds(settings["seed"], settings["n_seeds"], 2))
    agent.streams = _RecordedDraws(agent.streams)
    lights = np.array(["-", "R", "G"])[np.array(buttons.layouts())]  # by light value
    letters = np.array(["-", "G", "R"])  # by effect index
    effects = np.array(buttons.EFFECTS)
    truth = effects[buttons.outcome_table().reshape(-1)]  # [pair, box]
    names = ["nothing", "green", "red"]  # by effect index
    rows, presses = [], [0]

    def record(step):
        presses[0] = presses[0] % buttons.DEFAULT_PRESSES_PER_TRIAL + 1
        values, interest = step.info["values"], step.info["interest"]
        ties = (values == values.max(axis=1, keepdims=True)).sum(axis=1) > 1
        explore = agent.streams.last[:, 0] < agent.epsilon
        why = np.where(explore, "random", np.where(ties, "tie", "most interesting"))
        wrong = (effects[agent.predictor.effect] != truth).sum(axis=1)
        for k, layout in enumerate(step.before.tolist()):
            rows.append({
                "seed": k, "trial": int(step.episode[k]) + 1, "press": presses[0],
                "lights": "".join(lights[layout]),
                "predicts": "".join(letters[step.info["predicted"][k]]),
                "nothing": interest[k, 0], "red": interest[k, 2], "green": interest[k, 1],
                "button": int(step.action[k]), "why": why[k],
                "opened": names[step.outcome[k]], "error": float(step.learned[k]),
                "wrong_red": int(wrong[k, 0]), "wrong_green": int(wrong[k, 1])})

    loop.play(ConsoleTrials(env, buttons.DEFAULT_PRESSES_PER_TRIAL), Chooser(agent, True),
              settings["n_trials"], [record])
    return pd.DataFrame(rows).sort_values(["seed", "trial", "press"], ignore_index=True)


