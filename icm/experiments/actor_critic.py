"""The actor-critic on the tabular button console, over many seeds (Figure 6).

All seeds run at once (`icm.learners.actor_critic.ActorCriticBatch`): seed k of a batch
is seed k run alone, and the per-agent `ActorCritic` gives the same numbers (a test
runs both)."""

import dataclasses
import math

import numpy as np

from icm import _streams, _validate
from icm._settings import with_settings
from icm.envs import buttons
from icm.experiments import _grid
from icm.experiments._memory import FIXED_BYTES, check_memory
from icm.experiments._progress import progress_bar
from icm.experiments.seeding import run_seeds
from icm.experiments.results import check_results, measures_table, percent
from icm.learners import action_selection, actor_critic
from icm.stats import (PANEL_RESAMPLES, bootstrap_band, comes_first, every_nth,
                       first_from_which)

TASKS = ("red", "green")
"""Order of the task axis in the result arrays."""
LATE_TRIALS = 10
CHAPTER_SEEDS = 200
"""Runs of the chapter "The actor-critic" (its Figure 6; `python -m icm figure6`)."""
CHAPTER_TRIALS = 100
"""Trials per run in that chapter and `python -m icm figure6` (its panel runs
`panel_data.PANEL_TRIALS`)."""
"""`summary()` describes the end of a run by its last `LATE_TRIALS` trials."""


def probe_queries(red_button=buttons.DEFAULT_RED_BUTTON):
    """The test of section 4.1, as (task, state, button, true boxes) tuples.

    "We presented the robot with only the red button [...] Then we presented the robot
    with only the green button": the red query lights only the red button and presses
    it; the green queries light only the green button, at each of the 4 places it
    takes in training, and press it. Boxes are shut before the press. None of these
    states occurs in training, where two buttons are always lit.

    Args:
      red_button: the button that is always red (0-4).

    Returns:
      A list of (task, state, button, true boxes): one for red, then one for each
      place of the green button, left to right. A state is the 5 lights, then the 2
      boxes, as `ActorCritic.state` builds it.

    Raises:
      ValueError: for a red button outside 0..4.
    """
    red_button = buttons.check_red_button(red_button)
    red_only = np.full(buttons.N_BUTTONS, buttons.OFF, dtype=np.int64)
    red_only[red_button] = buttons.RED
    queries = [("red", tuple(red_only.tolist()) + (0, 0), red_button, (1, 0))]
    for green in buttons.green_candidates(red_button):
        lights = np.full(buttons.N_BUTTONS, buttons.OFF, dtype=np.int64)
        lights[green] = buttons.GREEN
        queries.append(("green", tuple(lights.tolist()) + (0, 0), green, (0, 1)))
    return queries


@dataclasses.dataclass(frozen=True)
class ActorCriticResult:
    """What `run_actor_critic` measured. Trials are counted from 1 in `zero_trial`;
    the arrays' trial axis holds trial 1 at index 0.

    Attributes:
      settings: the arguments of the run, as a dict.
      prediction_error: [seed, trial, task], after each trial, section 4.1's test:
        the Euclidean distance between the predicted and the true boxes when only the
        red button is lit and pressed (task red), and the same averaged over the 4
        places of the green button when only it is lit and pressed (task green).
      zero_trial: [seed, task], the first trial from which that error is 0 to the end
        of the run; -1 if it is not 0 at the end.
      practice: [seed, trial, task], presses in the trial that opened each box.
      press_probability: [seed, trial, task], after each trial, the actor's
        probability of pressing the red (task red) and the green (task green) button
        at the start of a trial (boxes shut), averaged over the 4 layouts.
      reward: [seed, trial], the rewards the learner received in the trial, summed.
      max_abs_value: [seed, trial], the largest absolute value of the critic after each trial.
    """

    settings: dict
    prediction_error: np.ndarray
    zero_trial: np.ndarray
    practice: np.ndarray
    press_probability: np.ndarray
    reward: np.ndarray
    max_abs_value: np.ndarray

    @property
    def n_seeds(self):
        """Number of runs (seeds)."""
        return self.prediction_error.shape[0]

    @property
    def n_trials(self):
        """Trials per run."""
        return self.prediction_error.shape[1]

    def red_first_fraction(self):
        """Share of seeds in which the red error reaches 0 (for good) strictly before
        the green one (a seed where only red reaches 0 counts as red first)."""
        red, green = self.zero_trial[:, 0], self.zero_trial[:, 1]
        return float(comes_first(red, green).mean())

    def seed_summaries(self):
        """One dict per seed of the numbers a sweep compares: the trial from which each
        task's error is 0 (-1 if never), the gap green - red (NaN unless both reach 0),
        and whether red came first."""
        rows = []
        for red, green in self.zero_trial.tolist():
            gap = float(green - red) if red >= 1 and green >= 1 else float("nan")
            rows.append({"red_zero_trial": red, "green_zero_trial": green, "zero_gap": gap,
                         "red_first": bool(comes_first(red, green))})
        return rows

    def green_below_red(self):
        """[seed, trial] True where the green error is below the red one: the learner
        is, for the moment, more familiar with the hard task than with the easy one."""
        return self.prediction_error[:, :, 1] < self.prediction_error[:, :, 0]

    def green_below_red_only_before_red_press(self):
        """Whether, in every seed, the green error is below the red one only in trials
        before the red button was first pressed (before a press opened the red box;
        none at all if it never was)."""
        below = self.green_below_red()
        pressed = self.practice[:, :, 0] > 0  # a red press opens the red box
        trials = np.arange(1, self.n_trials + 1)
        first_press = np.where(pressed.any(axis=1), np.argmax(pressed, axis=1) + 1,
                               self.n_trials + 1)
        last_below = np.where(below, trials, 0).max(axis=1)
        return bool(np.all(last_below <= first_press))

    def claims(self):
        """{claim name: whether it holds in this run}, for each of
        `icm.chapters.actor_critic.CLAIMS` (checked on the book's run when it is built, and
        by the tests on their own seeds)."""
        s = self.summary()
        return {"red_sooner": s["red_zero_mean"] < s["green_zero_mean"],
                "red_first_mostly": s["red_first"] > 0.5,
                "green_below_only_before_red_press":
                    self.green_below_red_only_before_red_press()}

    def green_below_red_fraction(self):
        """Share of seeds in which the green error is below the red one at some trial
        (the paper's "familiarity with the more complex task would temporarily
        increase above the simple task")."""
        return float(self.green_below_red().any(axis=1).mean())

    def summary(self):
        """The numbers the book quotes, as a dict.

        For each task (keys starting ``red_`` or ``green_``): the share of seeds whose
        error reaches 0 for good (``_zero_share``), the mean and median of that trial
        over those seeds, the mean final error, the share of presses opening the box in
        the last `LATE_TRIALS` trials (``_late_practice_share``) and the final
        probability of pressing its button. Also `red_first`, `green_below_red` (with
        how many trials and until when), the reward per press at the end, and the
        largest absolute critic value at the end (max and median over seeds)."""
        out = {"red_first": self.red_first_fraction(),
               "green_below_red": self.green_below_red_fraction()}
        below = self.green_below_red()
        seeds_below = below.any(axis=1)
        if seeds_below.any():
            trials = np.arange(1, self.n_trials + 1)
            last = np.where(below, trials, 0).max(axis=1)[seeds_below]
            out["green_below_red_trials"] = float(below[seeds_below].sum(axis=1).mean())
            out["green_below_red_last_mean"] = float(last.mean())
            out["green_below_red_last_max"] = int(last.max())
        else:
            out["green_below_red_trials"] = 0.0
            out["green_below_red_last_mean"] = math.nan
            out["green_below_red_last_max"] = -1
        late = slice(max(0, self.n_trials - LATE_TRIALS), None)
        presses = self.settings["presses_per_trial"]
        for i, task in enumerate(TASKS):
            zero = self.zero_trial[:, i]
            done = zero >= 1
            out[f"{task}_zero_share"] = float(done.mean())
            out[f"{task}_zero_mean"] = float(zero[done].mean()) if done.any() else math.nan
            out[f"{task}_zero_median"] = float(np.median(zero[done])) if done.any() else math.nan
            out[f"{task}_final_error"] = float(self.prediction_error[:, -1, i].mean())
            out[f"{task}_late_practice_share"] = float(
                self.practice[:, late, i].mean() / presses)
            out[f"{task}_final_press_probability"] = float(
                self.press_probability[:, -1, i].mean())
        out["late_reward_per_press"] = float(self.reward[:, late].mean() / presses)
        out["max_abs_value"] = float(self.max_abs_value[:, -1].max())
        out["median_abs_value"] = float(np.median(self.max_abs_value[:, -1]))
        return out


def _check_run_arguments(n_seeds, n_trials, rewarded_box, presses_per_trial, red_button,
                         seed, settings):
    """The run's own arguments (its learner's `settings` are checked already), checked
    and normalised, with the settings' values, as the result's `settings` dict; the
    run's memory is checked too."""
    checked = dict(
        n_seeds=_validate.integer_at_least("n_seeds", n_seeds, 1),
        n_trials=_validate.integer_at_least("n_trials", n_trials, 1),
        rewarded_box=_validate.one_of("rewarded_box", rewarded_box, buttons.BOX_NAMES),
        presses_per_trial=buttons.PRESSES_PER_TRIAL.check(presses_per_trial,
                                                          "presses_per_trial"),
        red_button=buttons.check_red_button(red_button),
        seed=_validate.root_seed("seed", seed))
    checked = {**checked, **settings.as_dict()}
    check_memory("run_actor_critic", {"n_seeds": checked["n_seeds"],
                                      "n_trials": checked["n_trials"]},
                 memory_needed(checked["n_seeds"], checked["n_trials"],
                               checked["presses_per_trial"])[0])
    return checked


LOOP_ROW_BYTES = 1500
"""An upper bound on the temporaries of a press and of a trial's reduction, per row,
besides the predictor's distances (counted from their shape)."""


def memory_needed(n_rows, n_trials, presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL,
                  one_action_weight=True):
    """An upper bound on the memory a batch of `n_rows` runs of `run_actor_critic`
    adds to the process, in bytes, counted from its arrays' shapes (see
    `icm.experiments._memory`). `one_action_weight`: whether every row has the same
    action weight (a grid may vary it: the predictor then computes each row's
    distances anew at every press).

    Returns:
      (peak, kept): the bound on the run's peak, and the bytes of its result.
    """
    n_states = len(state_table()[0])
    n_tasks, n_actions = len(TASKS), buttons.N_BUTTONS
    row_trials = n_rows * n_trials
    # The result, per row and trial: prediction_error, practice, press_probability
    # [task]; reward, max_abs_value.
    kept = 8 * row_trials * (3 * n_tasks + 2)
    making = 8 * row_trials  # the masks that find the zero trials
    n_keys = n_states * n_actions
    learner = n_rows * (8 * n_states * (1 + n_actions)  # critic, actor
                        + 16 * n_keys  # the predictor: distance, effect per key
                        + 8 * n_keys * (1 if one_action_weight else 4)  # a press's distances
                        + LOOP_ROW_BYTES)
    presses = n_trials * presses_per_trial
    streams = (_streams.memory_bound(n_rows, presses * action_selection.DRAWS_PER_CHOICE)
               + _streams.memory_bound(n_rows, n_trials))  # the consoles': a layout a trial
    return FIXED_BYTES + kept + making + learner + streams, kept


@with_settings(actor_critic.ActorCriticSettings)
def run_actor_critic(n_seeds=100, n_trials=100,
                     rewarded_box="green",
                     presses_per_trial=buttons.PRESSES_PER_TRIAL.default,
                     red_button=buttons.DEFAULT_RED_BUTTON,
                     seed=0,
                     progress=True,
                     settings=None):
    """Runs the actor-critic on the tabular button console, once per seed.

    Each run builds a `ButtonConsole` (paying 1.0 when `rewarded_box` opens if the
    reward is extrinsic, nothing otherwise), a `NearestNeighbourPredictor` and an
    `ActorCritic` with their own seeds (drawn from `seed`), and plays `n_trials`
    trials. After each trial it runs section 4.1's test (see `probe_queries`) and
    records the policy at the start of a trial.

    Args:
      n_seeds: number of independent runs (>= 1).
      n_trials: trials per run (>= 1).
      rewarded_box: "red" or "green", the box that pays 1.0 when the reward is
        extrinsic (ignored for an intrinsic reward).
      presses_per_trial: presses per trial (see `icm.envs.buttons.PRESSES_PER_TRIAL`).
      red_button: the button that is always red (0-4).
      seed: the root seed: an integer >= 0, a `numpy.random.Generator` (one integer
        is drawn from it) or None (fresh entropy); run i's seeds depend only on it
        and i. The integer used is kept in `settings["seed"]`.
      progress: show a progress bar when the run lasts over a second.
      settings: the learner's settings, an
        `icm.learners.actor_critic.ActorCriticSettings` (or give them one by one as
        keyword arguments, listed below).

    Returns:
      An `ActorCriticResult`.

    Raises:
      ValueError: for any argument outside its allowed range, or a run too large for
        this machine's memory.
    """
    return run_actor_critic_grid(
        [{}], n_seeds=n_seeds, n_trials=n_trials, rewarded_box=rewarded_box,
        presses_per_trial=presses_per_trial, red_button=red_button, seed=seed,
        progress=progress, settings=settings)[0]


GRID_ARGUMENTS = _grid.grid_arguments(run_actor_critic)
"""The settings that may differ between the settings of one `run_actor_critic_grid`
(the batched learner takes them per row): those of
`icm.learners.actor_critic.ActorCriticSettings` that are per row."""


def run_actor_critic_grid(grid, **arguments):
    """Runs `run_actor_critic(**arguments, **setting)` for every setting of `grid`, all in
    one batch (each setting's seeds are rows of the batched learner, which takes these
    settings per row).

    Result k is identical to the separate run of setting k (a test checks it):
    `run_actor_critic` itself is this function with one setting.

    Args:
      grid: a non-empty list of dicts, each a setting of some of `GRID_ARGUMENTS`.
      **arguments: any other arguments of `run_actor_critic`, the same for every
        setting (n_seeds, n_trials, reward, seed, progress, learner settings, ...).

    Returns:
      A list of `ActorCriticResult`, one per setting, in the grid's order.

    Raises:
      ValueError: for a malformed grid, a setting of an argument not in
        `GRID_ARGUMENTS`, or any value `run_actor_critic` refuses.
    """
    blocks, others, progress = _grid.check_settings_grid(grid, run_actor_critic, arguments)
    settings = [_check_run_arguments(**others, settings=block) for block in blocks]
    first, n = settings[0], settings[0]["n_seeds"]
    if len(settings) > 1:  # the settings' rows side by side
        check_memory("run_actor_critic_grid", {"settings": len(settings), "n_seeds": n,
                                               "n_trials": first["n_trials"]},
                     memory_needed(n * len(settings), first["n_trials"],
                                   first["presses_per_trial"],
                                   len({s["action_weight"] for s in settings}) == 1)[0])
    seeds = run_seeds(first["seed"], n, 2) * len(settings)
    red_button = first["red_button"]
    states = state_table(red_button)[0]
    env = buttons.ButtonConsoleBatch([s[0] for s in seeds], red_button)
    agent = actor_critic.ActorCriticBatch(
        [s[1] for s in seeds], states, buttons.EFFECTS, buttons.N_BUTTONS,
        settings=actor_critic.ActorCriticSettings.stack(blocks, n))
    rewarded_box = first["rewarded_box"] if first["reward"] == "extrinsic" else None
    result = play(env, agent, first["n_trials"], first["presses_per_trial"],
                  rewarded_box=rewarded_box, progress=progress, settings=first)
    return _grid.split(result, settings, n)


def state_table(red_button=buttons.DEFAULT_RED_BUTTON):
    """The states of the actor-critic on the button console, as the batched learner
    numbers them.

    Returns:
      (features, start_states, probes): features [17, 7], the 5 lights and the 2
      boxes of every state (state layout * 3 + effect for the 12 training states: the
      four layouts with the boxes shut or as a press left them; then the 5 probe
      states of section 4.1's test); start_states [4], the training states of each
      layout with the boxes shut; probes, one (task, state, button, true effect) per
      query of `probe_queries`.
    """
    effects = np.asarray(buttons.EFFECTS)
    features = [np.concatenate([lights, effect]) for lights in buttons.layouts(red_button)
                for effect in effects]
    probes = []
    for task, state, button, truth in probe_queries(red_button):
        probes.append((task, len(features), button, buttons.EFFECTS.index(truth)))
        features.append(np.array(state))
    return np.array(features), np.arange(4) * len(effects), probes


def play(env, agent, n_trials, presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL,
         rewarded_box=None, observe=None, progress=False, settings=None):
    """Plays `n_trials` trials of a batched actor-critic on a batched console and
    gathers an `ActorCriticResult`: the loop of `run_actor_critic`, open to any console
    and learner of the same shape.

    After each trial the loop reduces what happened to the result's numbers for that
    trial: the boxes opened, section 4.1's test of the predictor on the probes, the
    actor's policy at the start states and the critic's largest value; a run keeps its
    result and nothing per press.

    Args:
      env: a batched console (as `icm.envs.buttons.ButtonConsoleBatch`).
      agent: a batched actor-critic whose states are `state_table(env.red_button)`'s
        (as `icm.learners.actor_critic.ActorCriticBatch`).
      n_trials: trials to play (>= 1).
      presses_per_trial: presses per trial (see `icm.envs.buttons.PRESSES_PER_TRIAL`).
      rewarded_box: None (no extrinsic reward), "red" or "green": the box whose opening
        pays the extrinsic reward.
      observe: None, or a function called after every press as
        `observe(trial, layouts, actions, effects)` (index arrays, one entry per row).
      progress: show a progress bar over the trials when the run lasts over a second.
      settings: the dict the result keeps as its `settings` (None: an empty dict).

    Returns:
      An `ActorCriticResult`.

    Raises:
      ValueError: for a bad `n_trials`, `presses_per_trial` or `rewarded_box`.
    """
    n_trials = _validate.integer_at_least("n_trials", n_trials, 1)
    presses_per_trial = buttons.PRESSES_PER_TRIAL.check(presses_per_trial, "presses_per_trial")
    if rewarded_box is not None:
        _validate.one_of("rewarded_box", rewarded_box, TASKS)
    observe = _validate.function("observe", observe)
    _validate.boolean("progress", progress)
    settings = {} if settings is None else _validate.instance("settings", settings, dict)
    red_button = env.red_button
    _, start_states, probes = state_table(red_button)
    rewarded = -1 if rewarded_box is None else \
        buttons.RED_BOX if rewarded_box == "red" else buttons.GREEN_BOX
    n_seeds, n_effects = len(env), len(buttons.EFFECTS)
    practice = np.zeros((n_seeds, n_trials, len(TASKS)), dtype=np.int64)
    reward_out = np.zeros((n_seeds, n_trials))
    max_abs_value = np.zeros((n_seeds, n_trials))
    error_out = np.zeros((n_seeds, n_trials, len(TASKS)))
    press_probability = np.zeros((n_seeds, n_trials, len(TASKS)))
    probe_keys = agent.predictor.keys(np.array([p[1] for p in probes]),
                                      np.array([p[2] for p in probes]))
    effects = np.asarray(buttons.EFFECTS)
    # Section 4.1's test: the predictor's error on the probes, red alone, and green
    # averaged over its four places (added in order, as one run at a time would).
    errors = np.array([[math.dist(p, o) for o in buttons.EFFECTS] for p in buttons.EFFECTS])
    n_green = sum(1 for task, *_ in probes if task == "green")
    trials = progress_bar(range(n_trials), n_trials, "actor-critic", progress, unit="trial")
    for trial in trials:
        layout = env.new_trials()
        state = start_states[layout]
        for press in range(presses_per_trial):
            actions = agent.select_actions(state)
            observed = env.press(actions)
            next_state = layout * n_effects + observed
            external = (observed == rewarded).astype(float)
            r, _ = agent.learn(state, actions, next_state, observed, external, 1.0)
            if observe is not None:
                observe(trial, layout, actions, observed)
            reward_out[:, trial] += r
            practice[:, trial] += effects[observed]  # the boxes opened
            state = next_state
        answers = agent.predictor.effect[:, probe_keys]
        for i, (task, _, _, truth) in enumerate(probes):
            error = errors[answers[:, i], truth]
            if task == "red":
                error_out[:, trial, 0] = error
            else:
                error_out[:, trial, 1] += error / n_green
        # The policy at the start of a trial, averaged over the layouts.
        policy = agent.policy_of(agent.actor[:, start_states])  # [seed, layout, action]
        for layout, green in enumerate(buttons.green_candidates(red_button)):
            press_probability[:, trial, 0] += policy[:, layout, red_button] / len(start_states)
            press_probability[:, trial, 1] += policy[:, layout, green] / len(start_states)
        max_abs_value[:, trial] = np.abs(agent.critic).max(axis=1)

    zero = first_from_which(np.moveaxis(error_out, 1, 2) == 0)
    zero = np.where(zero >= 0, zero + 1, -1)
    return ActorCriticResult(settings, error_out, zero, practice, press_probability,
                             reward_out, max_abs_value)


def comparison_table(results):
    """A Markdown table of the numbers that tell actor-critic runs apart, one column per
    run.

    Args:
      results: a dict {column label: ActorCriticResult}.

    Returns:
      A Markdown string (display it with `IPython.display.Markdown`); the trials
      marked † are means over the seeds whose error does reach 0.
    """
    check_results("results", results, ActorCriticResult)
    summaries = {id(r): r.summary() for r in results.values()}

    def shown(value, fmt):  # fmt: a format spec, or a function such as `percent`
        return fmt(value) if callable(fmt) else f"{value:{fmt}}"

    def number(key, fmt):
        return lambda r: shown(summaries[id(r)][key], fmt)

    def pair(key, fmt):
        return lambda r: (f"{shown(summaries[id(r)]['red_' + key], fmt)} / "
                          f"{shown(summaries[id(r)]['green_' + key], fmt)}")

    table = measures_table(results, [
        ("seeds", lambda r: str(r.n_seeds)),
        ("error 0 from trial (mean†): red / green", pair("zero_mean", ".1f")),
        ("green learned", number("green_zero_share", percent)),
        ("red first", number("red_first", percent)),
        ("green below red at some trial", number("green_below_red", percent)),
        (f"presses opening red / green, last {LATE_TRIALS} trials",
         pair("late_practice_share", percent)),
        ("largest abs(V)", number("max_abs_value", ".3g")),
    ])
    return table + "\n\n† mean over the seeds whose error reaches 0 for good within the run."


def panel_curves(result, every=1):
    """What the Figure 6 panel draws, as numbers: section 4.1's prediction error for
    each task per trial, the mean over the seeds with a 95% percentile-bootstrap band
    (which, unlike mean +/- t standard errors, never dips below an error of 0).

    Args:
      result: an `ActorCriticResult`.
      every: keep every `every`-th trial (and the last); each kept point's numbers do
        not depend on it.

    Returns:
      {"x": trials, "xlabel", "groups": [{"title", "ylabel", "series": {task: (mean,
      low, high)}}]}.
    """
    _validate.instance("result", result, ActorCriticResult,
                       "an ActorCriticResult (from icm.experiments.run_actor_critic)")
    keep = every_nth(result.n_trials, every)
    series = {task: bootstrap_band(result.prediction_error[:, keep, i],
                                   resamples=PANEL_RESAMPLES)
              for i, task in enumerate(TASKS)}
    return {"x": keep + 1, "xlabel": "trial",
            "groups": [{"title": f"Prediction error, {result.n_seeds} seeds",
                        "ylabel": "prediction error (mean, 95% band)", "series": series}]}
