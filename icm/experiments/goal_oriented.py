"""The goal-oriented learner on the button console, over many seeds (Figure 5).

All seeds run at once (`icm.learners.goal_oriented.GoalOrientedBatch` on
`icm.envs.buttons.ButtonConsoleBatch`): seed k of a batch is seed k run alone, and the
per-agent classes give the same numbers (a test runs both).
"""

import dataclasses

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.experiments import _grid
from icm.experiments._progress import progress_bar
from icm.experiments._seeding import check_run_size, run_seeds
from icm.learners import goal_oriented, interest, predictors
from icm.stats import (PANEL_RESAMPLES, bootstrap_band, comes_first, every_nth, first_below,
                       first_from_which)

TASKS = ("red", "green")
"""Order of the task axis in the result arrays."""
_REST = (0, 0)
TASK_KEYS = {"red": (_REST, (1, 0)), "green": (_REST, (0, 1)), "nothing": (_REST, (0, 0))}
"""The agent's task keys (boxes at rest -> boxes after the press) by name."""
_TASK_EFFECTS = (buttons.RED_BOX, buttons.GREEN_BOX)  # red, green, as TASKS


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

    def fade_trial(self, task, fraction=0.1):
        """The first trial after its peak at which the mean interest in `task` falls
        below `fraction` (in (0, 1]) of that peak; -1 if it never does."""
        task = _validate.one_of("task", task, TASKS)
        fraction = _validate.real("fraction", fraction, 0.0, 1.0, low_open=True)
        index = first_below(self.mean_interest()[:, TASKS.index(task)], fraction)
        return index + 1 if index >= 0 else -1

    def interest_centre(self, task):
        """The interest-weighted mean trial of `task`: when, on average, the interest in
        it is spent (a robust "when", unlike the peak of a flat curve)."""
        task = _validate.one_of("task", task, TASKS)
        curve = self.mean_interest()[:, TASKS.index(task)]
        if curve.sum() == 0:
            return float("nan")
        return float(np.arange(1, len(curve) + 1) @ curve / curve.sum())

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


def _check_run_arguments(n_seeds, n_trials, epsilon, window, new_task_factor, reading,
                         action_weight, presses_per_trial, red_button, interest_signal,
                         interest_per, noisy_button, physics, seed, progress):
    """The arguments of `run_goal_oriented`, checked and normalised, as a dict."""
    checked = dict(
        n_seeds=_validate.integer_at_least("n_seeds", n_seeds, 1),
        n_trials=_validate.integer_at_least("n_trials", n_trials, 1),
        epsilon=_validate.in_closed_interval("epsilon", epsilon, 0.0, 1.0),
        window=_validate.integer_at_least("window", window, 2),
        new_task_factor=_validate.in_closed_interval("new_task_factor", new_task_factor,
                                                     0.0, 1.0),
        reading=_validate.one_of("reading", reading, interest.READINGS),
        action_weight=_validate.positive("action_weight", action_weight),
        presses_per_trial=_validate.integer_at_least("presses_per_trial",
                                                     presses_per_trial, 1),
        red_button=buttons.check_red_button(red_button),
        interest=_validate.one_of("interest", interest_signal, interest.SIGNALS),
        interest_per=_validate.one_of("interest_per", interest_per,
                                      goal_oriented.INTEREST_PER),
        noisy_button=_validate.boolean("noisy_button", noisy_button),
        physics=_validate.boolean("physics", physics),
        seed=_validate.root_seed("seed", seed))
    _validate.boolean("progress", progress)
    check_run_size("run_goal_oriented", checked["n_seeds"], checked["n_trials"], 160,
                   bytes_per_seed=8 * (600 + 8 * checked["window"]))
    return checked


def run_goal_oriented(n_seeds=100, n_trials=100,
                      epsilon=goal_oriented.DEFAULT_EPSILON,
                      window=interest.DEFAULT_WINDOW,
                      new_task_factor=interest.DEFAULT_NEW_TASK_FACTOR,
                      reading="progress",
                      action_weight=predictors.DEFAULT_ACTION_WEIGHT,
                      presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL,
                      red_button=buttons.DEFAULT_RED_BUTTON,
                      interest="learning_progress",
                      interest_per="task",
                      noisy_button=False,
                      physics=False,
                      seed=0,
                      progress=True):
    """Runs the goal-oriented learner on the button console, all seeds at once.

    Each run has a console, a nearest-neighbour predictor, an interest module and an
    epsilon-greedy actor with its own seeds (drawn from `seed`), and plays `n_trials`
    trials. After each trial it records the interest in the red and green tasks and
    tests the predictor on every (layout, button) pair.

    Args:
      n_seeds: number of independent runs (>= 1).
      n_trials: trials per run (>= 1).
      epsilon: probability of a random press, in [0, 1].
      window: errors in the progress slope (k), >= 2 (and in the mean of the
        prediction-error signal).
      new_task_factor: share of the mean interest given to a task seen once, [0, 1].
      reading: "progress" (errors going down are interesting) or "literal".
      action_weight: the predictor's cost of a different button (> 0).
      presses_per_trial: presses per trial (>= 1).
      red_button: the button that is always red (0-4).
      interest: the interest signal: "learning_progress" (the paper's, default),
        "prediction_error", "novelty" or "random" (see `icm.learners.interest`).
      interest_per: "task" (the paper's, default) or "region" (each button's own
        interest); see `icm.learners.goal_oriented.INTEREST_PER`.
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

    Returns:
      A `GoalOrientedResult`.

    Raises:
      ValueError: for any argument outside its allowed range, or a run too large for
        this machine's memory.
    """
    return run_goal_oriented_grid(
        [{}], n_seeds=n_seeds, n_trials=n_trials, epsilon=epsilon, window=window,
        new_task_factor=new_task_factor, reading=reading, action_weight=action_weight,
        presses_per_trial=presses_per_trial, red_button=red_button, interest=interest,
        interest_per=interest_per, noisy_button=noisy_button, physics=physics, seed=seed,
        progress=progress)[0]


GRID_ARGUMENTS = ("epsilon", "window", "new_task_factor", "reading", "action_weight")
"""The arguments that may differ between the settings of one `run_goal_oriented_grid`
(the batched learner takes them per row)."""


def run_goal_oriented_grid(grid, **arguments):
    """Runs `run_goal_oriented(**arguments, **setting)` for every setting of `grid`, all
    in one batch (each setting's seeds are rows of the batched learner, which takes
    these settings per row).

    Result k is identical to the separate run of setting k (the same seeds, the same
    numbers; a test checks it): `run_goal_oriented` itself is this function with one
    setting. A grid of many settings costs far less than the settings one by one.

    Args:
      grid: a non-empty list of dicts, each a setting of some of `GRID_ARGUMENTS`
        (those left out take their value from `arguments`, or the default).
      **arguments: any other arguments of `run_goal_oriented`, the same for every
        setting (n_seeds, n_trials, seed, progress, ...).

    Returns:
      A list of `GoalOrientedResult`, one per setting, in the grid's order.

    Raises:
      ValueError: for a malformed grid, a setting of an argument not in
        `GRID_ARGUMENTS`, or any value `run_goal_oriented` refuses.
    """
    full, progress = _grid.check_grid(grid, GRID_ARGUMENTS, run_goal_oriented, arguments)
    settings = [_check_run_arguments(
        a["n_seeds"], a["n_trials"], a["epsilon"], a["window"], a["new_task_factor"],
        a["reading"], a["action_weight"], a["presses_per_trial"], a["red_button"],
        a["interest"], a["interest_per"], a["noisy_button"], a["physics"], a["seed"],
        progress) for a in full]
    first, n = settings[0], settings[0]["n_seeds"]
    if len(settings) > 1:
        check_run_size("run_goal_oriented_grid", n * len(settings), first["n_trials"], 160,
                       bytes_per_seed=8 * (600 + 8 * max(s["window"] for s in settings)))
    seeds = run_seeds(first["seed"], n, 2) * len(settings)
    env_seeds, agent_seeds = [s[0] for s in seeds], [s[1] for s in seeds]
    red_button, presses = first["red_button"], first["presses_per_trial"]
    if first["physics"]:
        env = buttons.PhysicsButtonConsoleBatch(env_seeds, red_button, presses,
                                                first["noisy_button"])
    else:
        env = buttons.ButtonConsoleBatch(env_seeds, red_button, first["noisy_button"])
    rows = {name: _grid.per_row(settings, name, n) for name in GRID_ARGUMENTS}
    agent = goal_oriented.GoalOrientedBatch(
        agent_seeds, np.array(buttons.layouts(red_button)), env.effects, env.n_actions,
        interest=first["interest"], interest_per=first["interest_per"], **rows)
    result = _play(first, env, agent, first["n_trials"], presses, red_button, progress)
    return _grid.split(result, settings, n)


def _play(settings, env, agent, n_trials, presses_per_trial, red_button, progress):
    """Plays every trial of a batched run and gathers a GoalOrientedResult.

    The loop only plays and keeps what happened (the presses, their outcomes, the
    interest and the predictor after each trial); everything the result reports is
    computed from those afterwards, for all trials at once."""
    n_seeds, n_actions = len(env), env.n_actions
    actions = np.zeros((n_seeds, n_trials, presses_per_trial), dtype=np.int64)
    outcomes = np.zeros((n_seeds, n_trials, presses_per_trial), dtype=np.int64)
    values = np.zeros((n_seeds, n_trials, agent.interest.n_keys))
    predictions = np.zeros((n_seeds, n_trials) + agent.predictor.effect.shape[1:], dtype=np.int64)
    trials = progress_bar(range(n_trials), n_trials, "goal-oriented learner", progress,
                          unit="trial")
    for trial in trials:
        layout = env.new_trials()
        for press in range(presses_per_trial):
            chosen = agent.select_actions(layout)
            observed = env.press(chosen)
            agent.learn(layout, chosen, observed)
            actions[:, trial, press], outcomes[:, trial, press] = chosen, observed
        values[:, trial] = agent.interest.values()
        predictions[:, trial] = agent.predictor.effect

    effects = agent.effects  # buttons.EFFECTS, and on the physics both boxes too
    both = outcomes == buttons.BOTH_BOXES
    practice = np.stack([((outcomes == buttons.RED_BOX) | both).sum(axis=2),
                         ((outcomes == buttons.GREEN_BOX) | both).sum(axis=2)], axis=2)
    presses = np.stack([(actions == a).sum(axis=2) for a in range(n_actions)], axis=2)
    per_layout = predictions.reshape(n_seeds, n_trials, 4, n_actions)
    if agent.interest_per == "task":
        interest_out = values[..., list(_TASK_EFFECTS)]
        per_layout_interest = np.take_along_axis(values[:, :, None, :], per_layout, axis=3)
    else:
        greens = buttons.green_candidates(red_button)
        interest_out = np.stack([values[..., red_button], values[..., greens].mean(axis=2)],
                                axis=2)
        per_layout_interest = np.broadcast_to(values[:, :, None, :], per_layout.shape)
    action_interest = np.moveaxis(per_layout_interest, 2, 0).mean(axis=0)
    # The share of the 20 (layout, button) pairs on which the predictor is wrong about
    # each box: wrong[predicted effect, true effect, box] is 1 where they differ.
    wrong = np.abs(effects[:, None, :] - effects[None, :, :]).astype(float)
    pairs = (per_layout[..., :buttons.N_BUTTONS] * len(effects)
             + buttons.outcome_table(red_button)).reshape(n_seeds, n_trials, -1)
    error_out = np.stack([wrong[..., box].reshape(-1).take(pairs).mean(axis=2)
                          for box in range(2)], axis=2)
    mastery = first_from_which(np.moveaxis(error_out, 1, 2) == 0)
    mastery = np.where(mastery >= 0, mastery + 1, -1)
    share = presses / presses_per_trial
    return GoalOrientedResult(settings, interest_out, error_out, mastery, practice, share,
                              action_interest)


def check_results(name, results, cls):
    """Returns `results` if it is a non-empty dict {label: `cls` instance}, else raises
    (an ArgumentTypeError naming the label of a wrong entry)."""
    if not isinstance(results, dict) or not results:
        raise _validate.ArgumentTypeError(
            f"{name} must be a non-empty dict {{label: {cls.__name__}}}, got "
            f"{_validate.show(results)}")
    for label, result in results.items():
        _validate.instance(f"{name}[{label!r}]", result, cls)
    return results


def measures_table(results, measures):
    """A Markdown table with one column per run and one row per measure: narrow enough
    for a book page however many measures there are.

    Args:
      results: a dict {column label: result}.
      measures: a list of (row label, function of a result giving the cell's text).
    """
    labels = list(results)
    lines = ["| | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    for name, cell in measures:
        lines.append(f"| {name} | " + " | ".join(cell(r) for r in results.values()) + " |")
    return "\n".join(lines)


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
        ("red mastered first", lambda r: f"{summaries[id(r)]['red_first']:.0%}"),
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
