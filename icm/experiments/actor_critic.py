"""The actor-critic on the tabular button console, over many seeds (Figure 6).

All seeds run at once (`icm.learners.actor_critic.ActorCriticBatch`): seed k of a batch
is seed k run alone, and the per-agent `ActorCritic` gives the same numbers (a test
runs both)."""

import math

import numpy as np

from icm import _streams, _validate
from icm._settings import with_settings
from icm.envs import buttons
from icm.experiments import _grid, loop
from icm.experiments._memory import FIXED_BYTES, check_memory
from icm.experiments.loop import Transition
from icm.experiments.actor_critic_results import TASKS, ActorCriticResult
from icm.experiments.seeding import run_seeds
from icm.learners import action_selection, actor_critic
from icm.stats import first_from_which

CHAPTER_SEEDS = 200
"""Runs of the chapter "The actor-critic" (its Figure 6; `python -m icm figure6`)."""
CHAPTER_TRIALS = 100
"""Trials per run in that chapter and `python -m icm figure6` (its panel runs
`panel_data.PANEL_TRIALS`)."""


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
    env, agent = make(first, seeds, actor_critic.ActorCriticSettings.stack(blocks, n))
    rewarded_box = first["rewarded_box"] if first["reward"] == "extrinsic" else None
    result = play(env, agent, first["n_trials"], first["presses_per_trial"],
                  rewarded_box=rewarded_box, progress=progress, settings=first)
    return _grid.split(result, settings, n)


def make(settings, seeds, learner=None):
    """The console and the learner of a run of `run_actor_critic`, one row per seed, as
    the run builds them.

    Args:
      settings: the run's settings, as a result keeps them (`red_button`, and the
        learner's).
      seeds: one [console seed, learner seed] per row (`icm.experiments.seeding.
        run_seeds(seed, n_seeds, 2)`).
      learner: the learner's settings, an `icm.learners.actor_critic.
        ActorCriticSettings` whose per-row settings may hold one value per row (None:
        those of `settings`).

    Returns:
      (env, agent): the tabular batched console and the batched actor-critic
      (`icm.learners.actor_critic.ActorCriticBatch`), its states `state_table`'s.
    """
    if learner is None:
        learner = actor_critic.ActorCriticSettings(
            **{name: settings[name] for name in actor_critic.ActorCriticSettings.names()})
    red_button = settings["red_button"]
    env = buttons.ButtonConsoleBatch([s[0] for s in seeds], red_button)
    agent = actor_critic.ActorCriticBatch([s[1] for s in seeds], state_table(red_button)[0],
                                          buttons.EFFECTS, buttons.N_BUTTONS,
                                          settings=learner)
    return env, agent


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


class ConsoleStates:
    """A batched button console as the actor-critic plays it, for the one loop
    (`icm.experiments.loop.play`): an episode is a trial; a state is the layout and
    what the last press left open (`state_table`'s numbering: layout * 3 + effect, the
    boxes shut at the start); a press's outcome is its effect, its reward 1 where it
    opened `rewarded_box` (the extrinsic reward), with a discount of 1; the trial ends
    after `presses_per_trial` presses.

    Args:
      env: a batched console (as `icm.envs.buttons.ButtonConsoleBatch`).
      presses_per_trial: presses per trial.
      rewarded_box: None, "red" or "green".
    """

    def __init__(self, env, presses_per_trial, rewarded_box=None):
        self.env, self.presses_per_trial = env, presses_per_trial
        self.start_states = state_table(env.red_button)[1]
        self.rewarded = -1 if rewarded_box is None else \
            buttons.RED_BOX if rewarded_box == "red" else buttons.GREEN_BOX
        self._presses, self._layout = 0, None
        self._going, self._ending = np.zeros(len(env), dtype=bool), np.ones(len(env), dtype=bool)

    def __len__(self):
        return len(self.env)

    def reset(self, rows):
        """A new trial in every row: the start states of its layouts, [rows]."""
        self._presses = 0
        self._layout = self.env.new_trials()
        return self.start_states[self._layout]

    def step(self, rows, states, actions):
        """Presses `actions` (one button per row)."""
        observed = self.env.press(actions)
        self._presses += 1
        ended = self._ending if self._presses == self.presses_per_trial else self._going
        return Transition(self._layout * len(buttons.EFFECTS) + observed, observed,
                          (observed == self.rewarded).astype(float), 1.0, ended)


class Learner:
    """A batched actor-critic as the one loop drives it: `act` is its `select_actions`,
    `learn` its `learn` of the press ((rewards, TD errors) are the step's `learned`).

    Args:
      agent: the learner (as `icm.learners.actor_critic.ActorCriticBatch`).
    """

    def __init__(self, agent):
        self.agent = agent

    def act(self, rows, states):
        """Each row's press in its state."""
        return self.agent.select_actions(states), None

    def learn(self, step):
        """The learner learns the press; returns (rewards, TD errors) [rows]."""
        return self.agent.learn(step.before, step.action, step.after, step.outcome,
                                step.reward, step.discount)


class TrialSummary:
    """The observer that reduces a run of the actor-critic to its `ActorCriticResult`:
    after each press the reward and the boxes opened; after each trial section 4.1's
    test of the predictor on the probes, the actor's policy at the start states and
    the critic's largest value, so that a run keeps its result and nothing per press.

    Args:
      env: the batched console (its `red_button`).
      agent: the batched actor-critic (read after each trial: `predictor`, `actor`,
        `critic`, `policy_of`).
      n_trials: the run's trials.
    """

    def __init__(self, env, agent, n_trials):
        self.agent = agent
        self.red_button = env.red_button
        _, self.start_states, self.probes = state_table(self.red_button)
        n_seeds = len(env)
        self.practice = np.zeros((n_seeds, n_trials, len(TASKS)), dtype=np.int64)
        self.reward = np.zeros((n_seeds, n_trials))
        self.max_abs_value = np.zeros((n_seeds, n_trials))
        self.error = np.zeros((n_seeds, n_trials, len(TASKS)))
        self.press_probability = np.zeros((n_seeds, n_trials, len(TASKS)))
        self.probe_keys = agent.predictor.keys(np.array([p[1] for p in self.probes]),
                                               np.array([p[2] for p in self.probes]))
        self.effects = np.asarray(buttons.EFFECTS)
        # Section 4.1's test: the predictor's error on the probes, red alone, and green
        # averaged over its four places (added in order, as one run at a time would).
        self.errors = np.array([[math.dist(p, o) for o in buttons.EFFECTS]
                                for p in buttons.EFFECTS])
        self.n_green = sum(1 for task, *_ in self.probes if task == "green")

    def __call__(self, step):
        trial = step.episode[0]
        self.reward[:, trial] += step.learned[0]
        self.practice[:, trial] += self.effects[step.outcome]  # the boxes opened
        if step.ended[0]:
            self._end_of_trial(trial)

    def _end_of_trial(self, trial):
        agent = self.agent
        answers = agent.predictor.effect[:, self.probe_keys]
        for i, (task, _, _, truth) in enumerate(self.probes):
            error = self.errors[answers[:, i], truth]
            if task == "red":
                self.error[:, trial, 0] = error
            else:
                self.error[:, trial, 1] += error / self.n_green
        # The policy at the start of a trial, averaged over the layouts.
        policy = agent.policy_of(agent.actor[:, self.start_states])  # [seed, layout, action]
        n_layouts = len(self.start_states)
        for layout, green in enumerate(buttons.green_candidates(self.red_button)):
            self.press_probability[:, trial, 0] += policy[:, layout, self.red_button] / n_layouts
            self.press_probability[:, trial, 1] += policy[:, layout, green] / n_layouts
        self.max_abs_value[:, trial] = np.abs(agent.critic).max(axis=1)

    def result(self, settings):
        """The `ActorCriticResult` of the run, keeping `settings` (a dict)."""
        zero = first_from_which(np.moveaxis(self.error, 1, 2) == 0)
        zero = np.where(zero >= 0, zero + 1, -1)
        return ActorCriticResult(settings, self.error, zero, self.practice,
                                 self.press_probability, self.reward, self.max_abs_value)


def play(env, agent, n_trials, presses_per_trial=buttons.DEFAULT_PRESSES_PER_TRIAL,
         rewarded_box=None, observe=None, progress=False, settings=None):
    """Plays `n_trials` trials of a batched actor-critic on a batched console through
    the one loop (`icm.experiments.loop.play`) and gathers an `ActorCriticResult`
    (`TrialSummary`): what `run_actor_critic` does once it has built them (`make`),
    open to any console and learner of the same shape.

    Args:
      env: a batched console (as `icm.envs.buttons.ButtonConsoleBatch`).
      agent: a batched actor-critic whose states are `state_table(env.red_button)`'s
        (as `icm.learners.actor_critic.ActorCriticBatch`).
      n_trials: trials to play (>= 1).
      presses_per_trial: presses per trial (see `icm.envs.buttons.PRESSES_PER_TRIAL`).
      rewarded_box: None (no extrinsic reward), "red" or "green": the box whose opening
        pays the extrinsic reward.
      observe: None, or a function called with every press, a
        `icm.experiments.loop.Step` of every row (its `before` and `after` the states,
        `outcome` the effects, `reward` the extrinsic reward, `learned` the learner's
        rewards and TD errors).
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
    summary = TrialSummary(env, agent, n_trials)
    bar = loop.progress(n_trials, "actor-critic", progress, "trial", per=len(env))
    try:
        loop.play(ConsoleStates(env, presses_per_trial, rewarded_box), Learner(agent),
                  n_trials, [summary, bar, observe])
    finally:
        if bar is not None:
            bar.close()
    return summary.result(settings)


