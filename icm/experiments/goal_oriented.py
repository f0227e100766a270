"""The goal-oriented learner on the button console, over many seeds (Figure 5).

All seeds run at once (`icm.learners.goal_oriented.GoalOrientedBatch` on
`icm.envs.buttons.ButtonConsoleBatch`): seed k of a batch is seed k run alone, and the
per-agent classes give the same numbers (a test runs both).
"""

import dataclasses

import numpy as np

from icm import _streams, _validate
from icm._settings import with_settings
from icm.envs import buttons
from icm.experiments import _grid
from icm.experiments.results import check_results, measures_table, percent
from icm.experiments._memory import FIXED_BYTES, PHYSICS_SCENE_BYTES, check_memory
from icm.experiments._progress import progress_bar
from icm.experiments.seeding import run_seeds
from icm.learners import action_selection, goal_oriented, interest
from icm.stats import (PANEL_RESAMPLES, bootstrap_band, comes_first, every_nth, first_below,
                       first_from_which)

TASKS = ("red", "green")
"""Order of the task axis in the result arrays."""
_REST = (0, 0)
TASK_KEYS = {"red": (_REST, (1, 0)), "green": (_REST, (0, 1)), "nothing": (_REST, (0, 0))}
"""The agent's task keys (boxes at rest -> boxes after the press) by name."""
_TASK_EFFECTS = (buttons.RED_BOX, buttons.GREEN_BOX)  # red, green, as TASKS
FADE_FRACTION = 0.1
"""The share of its peak below which a task's mean interest has faded (`fade_trial`)."""
CHAPTER_SEEDS = 200
"""Runs of the chapter "Goal-oriented interest" (its Figure 5; `python -m icm figure5`)."""
CHAPTER_TRIALS = 60
"""Trials per run in that chapter: its Figure 5 and panel, its exercises' runs, its
robustness maps and `python -m icm figure5`."""


@dataclasses.dataclass(frozen=True)
class GoalOrientedResult:
    """What `run_goal_oriented` measured. Trials are counted from 1 in `mastery_trial`;
    the arrays' trial axis holds trial 1 at index 0.

    Attributes:
      settings: the arguments of the run, as a dict.
      interest: [seed, trial, task], interest in each task (red, green) at the end of
        each trial (0 before the task was first witnessed).
      prediction_error: [seed, trial, task], after each trial, the share of the 20
        (layout, button) pairs for which the predictor is wrong about that task's box
        (predicts it opens when it stays shut, or the reverse). 0 means mastered.
      mastery_trial: [seed, task], the first trial after which the predictor is right
        for that task in every layout and for every button, and stays right to the end
        of the run; -1 if that never happens.
      practice: [seed, trial, task], presses in the trial that opened each box.
      button_share: [seed, trial, button], the share of the trial's presses on each
        button (5 buttons, or 6 with the noisy button).
      action_interest: [seed, trial, button], at the end of each trial, how
        interesting each button is to the learner (the interest of the task it is
        predicted to achieve, or of its region with `interest_per="region"`), the mean
        over the four layouts.

    With `interest_per="region"`, `interest` holds the interest of the red button's
    region (task red) and the mean over the four buttons that green takes (task green).
    """

    settings: dict
    interest: np.ndarray
    prediction_error: np.ndarray
    mastery_trial: np.ndarray
    practice: np.ndarray
    button_share: np.ndarray
    action_interest: np.ndarray

    @property
    def n_seeds(self):
        return self.interest.shape[0]

    @property
    def n_trials(self):
        return self.interest.shape[1]

    def red_first_fraction(self):
        """Share of seeds in which red is mastered strictly before green (a seed where
        green is never mastered but red is counts as red first)."""
        red, green = self.mastery_trial[:, 0], self.mastery_trial[:, 1]
        return float(comes_first(red, green).mean())

    def mean_interest(self):
        """Mean interest over seeds, [trial, task]."""
        return self.interest.mean(axis=0)

    def peak_trial(self, task):
        """The trial (from 1) at which the mean interest in `task` ("red" or "green")
        is highest."""
        task = _validate.one_of("task", task, TASKS)
        return int(np.argmax(self.mean_interest()[:, TASKS.index(task)])) + 1

    def claims(self):
        """{claim name: whether it holds in this run}, for each of
        `icm.chapters.goal_oriented_interest.CLAIMS`: what the chapter states in words,
        checked on the book's run when it is built (and by the tests on their own
        seeds)."""
        s = self.summary()
        return {
            "red_first_mostly": s["red_first"] > 0.5,
            "red_sooner": s["red_mastery_mean"] < s["green_mastery_mean"],
            "red_fades_first": 0 < s["red_fade_trial"] < s["green_fade_trial"]
            or (s["red_fade_trial"] > 0 > s["green_fade_trial"]),
            "green_stays_longer": s["green_interest_centre"] > s["red_interest_centre"],
        }

    def describe_peaks(self):
        """In words, whether the mean interest in green peaks after the mean interest
        in red, as the paper's "interest rise slower" would have it: a clause that
        the chapter quotes, phrased from the data."""
        red, green = self.peak_trial("red"), self.peak_trial("green")
        if green > red:
            return (f"the mean curves agree, green's peaking at trial {green}, after red's "
                    f"at trial {red}")
        if green == red:
            return f"the mean curves do not show it: both peak at trial {red}"
        return (f"the mean curves show the opposite, green's peaking at trial {green}, "
                f"before red's at trial {red}")

    def fade_trial(self, task, fraction=None):
        """The first trial after its peak at which the mean interest in `task` falls
        below `fraction` (in (0, 1]) of that peak; -1 if it never does."""
        task = _validate.one_of("task", task, TASKS)
        fraction = FADE_FRACTION if fraction is None else _validate.real(
            "fraction", fraction, 0.0, 1.0, low_open=True)
        index = first_below(self.mean_interest()[:, TASKS.index(task)], fraction)
        return index + 1 if index >= 0 else -1

    def interest_centre(self, task):
        """The interest-weighted mean trial of `task`: when, on average, the interest in
        it is spent (a robust "when", unlike the peak of a flat curve)."""
        task = _validate.one_of("task", task, TASKS)
        curve = self.mean_interest()[:, TASKS.index(task)]
        if curve.sum() == 0:
            return float("nan")
        return float((np.arange(1, len(curve) + 1) * curve).sum() / curve.sum())

    def summary(self):
        """The numbers the book quotes, as a dict."""
        mastery = self.mean_mastery_trial()
        out = {"red_first": self.red_first_fraction()}
        for i, task in enumerate(TASKS):
            mastered = self.mastery_trial[:, i]
            out[f"{task}_mastery_mean"] = mastery[task][0]
            out[f"{task}_mastery_median"] = (float(np.median(mastered[mastered >= 1]))
                                            if (mastered >= 1).any() else float("nan"))
            out[f"{task}_mastered_share"] = mastery[task][1]
            out[f"{task}_peak_interest"] = float(self.mean_interest()[:, i].max())
            out[f"{task}_peak_trial"] = self.peak_trial(task)
            out[f"{task}_fade_trial"] = self.fade_trial(task)
            out[f"{task}_interest_centre"] = self.interest_centre(task)
            share = self.practice[:, :, i].mean(axis=0) / self.settings["presses_per_trial"]
            out[f"{task}_practice_peak_share"] = float(share.max())
            out[f"{task}_practice_peak_trial"] = int(np.argmax(share)) + 1
        return out

    def seed_summaries(self):
        """One dict per seed of the numbers a sweep compares: each task's mastery trial
        (-1 if never), the gap green - red (NaN unless both are mastered), and whether
        red came first."""
        rows = []
        for red, green in self.mastery_trial.tolist():
            gap = float(green - red) if red >= 1 and green >= 1 else float("nan")
            rows.append({"red_mastery_trial": red, "green_mastery_trial": green,
                         "mastery_gap": gap,
                         "red_first": bool(comes_first(red, green))})
        return rows

    def mean_mastery_trial(self):
        """Mean mastery trial of (red, green) over the seeds that master each task, and
        the share of seeds that do."""
        out = {}
        for i, task in enumerate(TASKS):
            done = self.mastery_trial[:, i] >= 1
            mean = float(self.mastery_trial[done, i].mean()) if done.any() else float("nan")
            out[task] = (mean, float(done.mean()))
        return out


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
      observe: None, or a function called after every press (see `play`).
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
    env_seeds, agent_seeds = [s[0] for s in seeds], [s[1] for s in seeds]
    red_button, presses = first["red_button"], first["presses_per_trial"]
    if make_env is not None:
        env = make_env(env_seeds)
    elif first["physics"]:
        env = buttons.PhysicsButtonConsoleBatch(env_seeds, red_button, presses,
                                                first["noisy_button"])
    else:
        env = buttons.ButtonConsoleBatch(env_seeds, red_button, first["noisy_button"])
    agent = goal_oriented.GoalOrientedBatch(
        agent_seeds, np.array(buttons.layouts(red_button)), env.effects, env.n_actions,
        settings=goal_oriented.GoalOrientedSettings.stack(blocks, n))
    result = play(env, agent, first["n_trials"], presses, observe=observe, progress=progress,
                  settings=first)
    return _grid.split(result, settings, n)


def play(env, agent, n_trials, presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL,
         observe=None, progress=False, settings=None):
    """Plays `n_trials` trials of a batched learner on a batched console, and gathers
    a `GoalOrientedResult`: the loop of `run_goal_oriented`, open to any console and
    learner of the same shape.

    After each trial the loop reduces what happened (the presses, their outcomes, the
    interest and the predictor) to the result's numbers for that trial, so that a run
    keeps its result and nothing per press.

    Args:
      env: a batched console, one row per run (as `icm.envs.buttons.ButtonConsoleBatch`:
        `new_trials()` gives the rows' layout indices, `press(actions)` their effect
        indices; `n_actions`, `red_button`).
      agent: a batched learner with a row per console row (as
        `icm.learners.goal_oriented.GoalOrientedBatch`: `select_actions(layouts)`,
        `learn(layouts, actions, effects)`, `interest.values()`, `interest_per`,
        `predictor.effect`, `effects`).
      n_trials: trials to play (>= 1).
      presses_per_trial: presses per trial (see `icm.envs.buttons.PRESSES_PER_TRIAL`).
      observe: None, or a function called after every press as
        `observe(trial, layouts, actions, effects)` (index arrays, one entry per row):
        a recorder of the presses, for example.
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
    red_button = env.red_button
    n_seeds, n_actions = len(env), env.n_actions
    practice = np.zeros((n_seeds, n_trials, len(TASKS)), dtype=np.int64)
    presses = np.zeros((n_seeds, n_trials, n_actions), dtype=np.int64)
    interest_out = np.zeros((n_seeds, n_trials, len(TASKS)))
    action_interest = np.zeros((n_seeds, n_trials, n_actions))
    error_out = np.zeros((n_seeds, n_trials, len(TASKS)))
    # The share of the 20 (layout, button) pairs on which the predictor is wrong about
    # each box: wrong[predicted effect, true effect, box] is 1 where they differ.
    effects = agent.effects  # buttons.EFFECTS, and on the physics both boxes too
    wrong = np.abs(effects[:, None, :] - effects[None, :, :]).astype(float)
    truth = buttons.outcome_table(red_button)
    greens = buttons.green_candidates(red_button)
    rows = np.arange(n_seeds)
    trials = progress_bar(range(n_trials), n_trials, "goal-oriented learner", progress,
                          unit="trial")
    for trial in trials:
        layout = env.new_trials()
        for press in range(presses_per_trial):
            chosen = agent.select_actions(layout)
            observed = env.press(chosen)
            agent.learn(layout, chosen, observed)
            if observe is not None:
                observe(trial, layout, chosen, observed)
            both = observed == buttons.BOTH_BOXES  # a press of both: practice of both
            for i, box in enumerate(_TASK_EFFECTS):
                practice[:, trial, i] += (observed == box) | both
            presses[rows, trial, chosen] += 1
        values = agent.interest.values()
        per_layout = agent.predictor.effect.reshape(n_seeds, 4, n_actions)
        if agent.interest_per == "task":
            interest_out[:, trial] = values[:, list(_TASK_EFFECTS)]
            per_layout_interest = np.take_along_axis(values[:, None, :], per_layout, axis=2)
        else:
            interest_out[:, trial] = np.stack([values[:, red_button],
                                               values[:, greens].mean(axis=1)], axis=1)
            per_layout_interest = np.broadcast_to(values[:, None, :], per_layout.shape)
        action_interest[:, trial] = np.moveaxis(per_layout_interest, 1, 0).mean(axis=0)
        pairs = (per_layout[..., :buttons.N_BUTTONS] * len(effects) + truth).reshape(n_seeds, -1)
        for box in range(len(TASKS)):
            error_out[:, trial, box] = wrong[..., box].reshape(-1).take(pairs).mean(axis=1)

    mastery = first_from_which(np.moveaxis(error_out, 1, 2) == 0)
    mastery = np.where(mastery >= 0, mastery + 1, -1)
    share = presses / presses_per_trial
    return GoalOrientedResult(settings, interest_out, error_out, mastery, practice, share,
                              action_interest)


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
    learned. Row k is the same run as seed k of `run_goal_oriented` (a test checks it).

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

    learner = goal_oriented.GoalOrientedSettings()
    settings = _check_run_arguments(n_seeds, n_trials, buttons.DEFAULT_PRESSES_PER_TRIAL,
                                    buttons.DEFAULT_RED_BUTTON, False, False, seed,
                                    learner)
    seeds = run_seeds(settings["seed"], settings["n_seeds"], 2)
    env = buttons.ButtonConsoleBatch([s[0] for s in seeds])
    agent = goal_oriented.GoalOrientedBatch(
        [s[1] for s in seeds], np.array(buttons.layouts()), env.effects, env.n_actions,
        settings=learner)
    agent.streams = _RecordedDraws(agent.streams)
    lights = np.array(["-", "R", "G"])[np.array(buttons.layouts())]  # by light value
    letters = np.array(["-", "G", "R"])  # by effect index
    effects = np.array(buttons.EFFECTS)
    truth = effects[buttons.outcome_table().reshape(-1)]  # [pair, box]
    names = ["nothing", "green", "red"]  # by effect index
    rows, n = [], len(env)
    for trial in range(1, n_trials + 1):
        layout = env.new_trials()
        for press in range(1, buttons.DEFAULT_PRESSES_PER_TRIAL + 1):
            interest = agent.interest.values().copy()
            predicted = agent.predicted_effects(layout)
            values = agent.action_interests(layout)
            chosen = agent.select_actions(layout)
            ties = (values == values.max(axis=1, keepdims=True)).sum(axis=1) > 1
            explore = agent.streams.last[:, 0] < agent.epsilon
            why = np.where(explore, "random", np.where(ties, "tie", "most interesting"))
            observed = env.press(chosen)
            errors = agent.learn(layout, chosen, observed)
            wrong = (effects[agent.predictor.effect] != truth).sum(axis=1)
            for k in range(n):
                rows.append({
                    "seed": k, "trial": trial, "press": press,
                    "lights": "".join(lights[layout[k]]),
                    "predicts": "".join(letters[predicted[k]]),
                    "nothing": interest[k, 0], "red": interest[k, 2],
                    "green": interest[k, 1], "button": int(chosen[k]), "why": why[k],
                    "opened": names[observed[k]], "error": float(errors[k]),
                    "wrong_red": int(wrong[k, 0]), "wrong_green": int(wrong[k, 1])})
    return pd.DataFrame(rows).sort_values(["seed", "trial", "press"], ignore_index=True)


def comparison_table(results):
    """A Markdown table of the numbers that tell runs apart, one column per run.

    Args:
      results: a dict {column label: GoalOrientedResult}.

    Returns:
      A Markdown string (display it with `IPython.display.Markdown`).
    """
    check_results("results", results, GoalOrientedResult)
    summaries = {id(r): r.summary() for r in results.values()}

    def pair(key, fmt):
        return lambda r: (f"{summaries[id(r)]['red_' + key]:{fmt}} / "
                          f"{summaries[id(r)]['green_' + key]:{fmt}}")

    return measures_table(results, [
        ("seeds", lambda r: str(r.n_seeds)),
        ("mastered, mean trial: red / green", pair("mastery_mean", ".1f")),
        ("red mastered first", lambda r: percent(summaries[id(r)]['red_first'])),
        ("peak interest: red / green", pair("peak_interest", ".3f")),
        ("centre of interest, trial: red / green", pair("interest_centre", ".1f")),
        ("interest below 10% of its peak from trial: red / green", pair("fade_trial", "")),
        ("most practised at trial: red / green", pair("practice_peak_trial", "")),
    ])


def panel_curves(result, every=1):
    """What the Figure 5 panel draws, as numbers: the mean interest in each task per
    trial over the seeds, with a 95% percentile-bootstrap band.

    The interactive panel and the book's precomputed static panel both draw this, so
    the two show the same numbers for the same settings.

    Args:
      result: a `GoalOrientedResult`.
      every: keep every `every`-th trial (and the last); each kept point's numbers do
        not depend on it.

    Returns:
      {"x": trials [trial], "xlabel", "groups": [{"title", "ylabel", "series":
      {task: (mean, low, high)}}]}.
    """
    _validate.instance("result", result, GoalOrientedResult,
                       "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    keep = every_nth(result.n_trials, every)
    series = {task: bootstrap_band(result.interest[:, keep, i], resamples=PANEL_RESAMPLES)
              for i, task in enumerate(TASKS)}
    return {"x": keep + 1, "xlabel": "trial",
            "groups": [{"title": f"Interest in each task, {result.n_seeds} seeds",
                        "ylabel": "interest (mean, 95% band)", "series": series}]}
