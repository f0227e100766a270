"""The goal-oriented architecture of the paper (section 3.1, Figure 2).

Predictor, interest module and actor are separate and replaceable. For each action
the actor (1) looks at the observation, (2) asks the predictor what the action would
do, (3) hands that effect, as a task, to the interest module, and (4) gets back how
interesting the task is; it then picks an action epsilon-greedily on interest.

`GoalOrientedAgent` is one agent, as the paper describes it; `GoalOrientedBatch` runs
the same learner for many agents at once on a finite world (the experiments use it),
and a test shows that the two give identical numbers, seed by seed.
"""

import math

import numpy as np

from icm import _streams, _validate
from icm._settings import Setting, Settings, Slider, setting, setting_from, settings_class
from icm.learners import interest as _interest
from icm.learners import predictors as _predictors
from icm.learners._common import check_keys, check_values, read_observation
from icm.learners import action_selection
from icm.learners.action_selection import epsilon_greedy, epsilon_greedy_rows
from icm.learners.interest import InterestTable, make_interest
from icm.learners.predictors import NearestNeighbourPredictor, NearestNeighbourTable

INTEREST_PER = ("task", "region")
"""Where interest lives. "task" (the paper's): an action is worth the interest of the
task it is predicted to achieve (a change of the goal state). "region": an action is
worth the interest of its own region of the motor space, here the action itself (for
the buttons: the button), as in curiosity-driven learners that split the
sensorimotor space into regions (Oudeyer, Kaplan and Hafner 2007)."""

EPSILON = Setting(
    default=0.1, label="probability of a random press (epsilon)", kind="real", low=0.0,
    high=1.0,
    source='section 3.1: the actor uses "a epsilon-greedy selection method", with no '
           'epsilon given; the book takes 0.1',
    slider=Slider(live=(0.0, 1.0, 0.05), grid=(0.0, 0.1, 0.2, 0.3, 0.4)),
    others=(0.0, 0.3))
"""The goal-oriented actor's epsilon."""


@settings_class
class GoalOrientedSettings(Settings):
    """The goal-oriented learner's settings (section 3.1, Figure 2): the actor's
    epsilon, the interest module's window, new-task factor and readings, the
    predictor's action weight and ties. Each is a `icm._settings.Setting`: see
    `GoalOrientedSettings.specs()` for its range, the paper's value and where it
    comes from. Values may be one per batch row (arrays) in `GoalOrientedBatch`."""

    epsilon: float = setting_from(EPSILON)
    window: int = setting_from(_interest.WINDOW)
    new_task_factor: float = setting_from(_interest.NEW_TASK_FACTOR)
    reading: str = setting_from(_interest.READING)
    action_weight: float = setting_from(_predictors.ACTION_WEIGHT)
    interest: str = setting_from(_interest.SIGNAL)
    interest_per: str = setting(
        default="task", label="where interest lives", kind="choice", choices=INTEREST_PER,
        paper="task", per_row=False,
        source='section 3.1: the interest module "estimate[s] the interest of each goal", a '
               'task of the goal space; "region" is the chapter "Which curiosity?"\'s '
               'alternative')
    new_task_mean: str = setting_from(_interest.NEW_TASK_MEAN)
    short_history: str = setting_from(_interest.SHORT_HISTORY)
    tie: str = setting_from(_predictors.TIE)


DEFAULT_EPSILON = EPSILON.default


class GoalOrientedAgent:
    """An epsilon-greedy actor on the interest of predicted effects.

    A *task* is a transition of the goal state (for the buttons, the boxes): from the
    goal state at rest (all boxes closed: the console closes them before every press)
    to the goal state after the action. The button experiment thus has three tasks:
    no box -> no box, no box -> red box, no box -> green box.

    Args:
      n_actions: number of discrete actions (integer >= 1).
      predictor: has `predict(context, action, default)` and `update(context, action,
        effect)`; default a `NearestNeighbourPredictor()`.
      interest: has `record(task, error)` and `interest(task)`; default a
        `LearningProgressInterest()` (see `icm.learners.interest` for the others).
      epsilon: probability of a uniformly random action (in [0, 1]).
      interest_per: "task" (the paper's, default) or "region"; see `INTEREST_PER`.
      context_keys: observation entries that make the context (default the lights).
      goal_key: the observation entry that makes the goal state (default the boxes).
      goal_at_rest: the goal state every action starts from (default all zeros).
      seed: None, an int, or a `numpy.random.Generator`, for epsilon and ties
        (`DRAWS_PER_CHOICE` numbers per choice).

    Raises:
      ValueError: for n_actions < 1, epsilon outside [0, 1], a predictor or interest
        module without the methods above, keys that are not entry names, or a bad
        seed.
    """

    def __init__(self, n_actions, predictor=None, interest=None, epsilon=EPSILON.default,
                 interest_per="task", context_keys=("lights",), goal_key="boxes",
                 goal_at_rest=None, seed=None):
        self.n_actions = _validate.integer_at_least("n_actions", n_actions, 1)
        self.epsilon = EPSILON.check(epsilon, "epsilon")
        self.interest_per = GoalOrientedSettings.spec("interest_per").check(
            interest_per, "interest_per")
        self.predictor = NearestNeighbourPredictor() if predictor is None else predictor
        self.interest = make_interest() if interest is None else interest
        for name, part, methods in (("predictor", self.predictor, ("predict", "update")),
                                    ("interest", self.interest, ("record", "interest"))):
            if not all(callable(getattr(part, m, None)) for m in methods):
                raise _validate.ArgumentTypeError(
                    f"{name} must have the methods {' and '.join(methods)}, got "
                    f"{_validate.show(part)}")
        self.context_keys = check_keys("context_keys", context_keys)
        self.goal_key = _validate.text("goal_key", goal_key)
        self.goal_at_rest = None if goal_at_rest is None else check_values(
            "goal_at_rest", goal_at_rest)
        self._random = _validate.generator("seed", seed)

    @classmethod
    def from_settings(cls, n_actions, settings=None, seed=None, **arguments):
        """The agent of `settings` (a `GoalOrientedSettings` of one value each; default
        the library's): its predictor, interest module and actor built from them.
        `arguments` are the constructor's others (context_keys, goal_key, ...)."""
        settings = GoalOrientedSettings() if settings is None else _validate.instance(
            "settings", settings, GoalOrientedSettings)
        predictor = NearestNeighbourPredictor(settings.action_weight, settings.tie)
        interest = make_interest(settings.interest, settings.window,
                                 settings.new_task_factor, settings.reading,
                                 settings.new_task_mean, settings.short_history)
        return cls(n_actions, predictor, interest, settings.epsilon, settings.interest_per,
                   seed=seed, **arguments)

    def context(self, observation):
        """The predictor's context for an observation: its context entries as a tuple."""
        return read_observation("observation", observation, self.context_keys)

    def goal_state(self, observation, name="observation"):
        """The goal state of an observation (its `goal_key` entry) as a tuple."""
        return read_observation(name, observation, (self.goal_key,))

    def _rest(self, observation):
        if self.goal_at_rest is None:
            self.goal_at_rest = (0,) * len(self.goal_state(observation))
        return self.goal_at_rest

    def predicted_effects(self, observation):
        """The predicted goal state after each action, as a list of tuples."""
        context, rest = self.context(observation), self._rest(observation)
        return [self.predictor.predict(context, a, default=rest)
                for a in range(self.n_actions)]

    def action_interests(self, observation):
        """Interest of the task each action is predicted to achieve (steps 2-4 of Fig.
        2), or with `interest_per="region"` the interest of each action's region."""
        if self.interest_per == "region":
            self.context(observation)  # checks the observation
            return [self.interest.interest(a) for a in range(self.n_actions)]
        rest = self._rest(observation)
        return [self.interest.interest((rest, effect))
                for effect in self.predicted_effects(observation)]

    def select_action(self, observation):
        """Epsilon-greedy on interest; ties between the most interesting are random."""
        draws = self._random.random(action_selection.DRAWS_PER_CHOICE)
        return epsilon_greedy(self.action_interests(observation), self.epsilon, draws)

    def learn(self, observation, action, next_observation):
        """Scores the prediction of `action` against what happened, and remembers it.

        Args:
          observation: the observation the action was chosen from.
          action: the action taken.
          next_observation: the observation after the action.

        Returns:
          (key, error): the task witnessed (or, per region, the action's region) and
          the Euclidean prediction error.

        Raises:
          ValueError: for an observation without the agent's entries, or an action
            that is not an integer in 0..n_actions-1.
        """
        action = _validate.integer("action", action, 0, self.n_actions - 1)
        context, rest = self.context(observation), self._rest(observation)
        observed = self.goal_state(next_observation, "next_observation")
        predicted = self.predictor.predict(context, action, default=rest)
        error = math.dist(predicted, observed)
        key = (rest, observed) if self.interest_per == "task" else action
        self.interest.record(key, error)
        self.predictor.update(context, action, observed)
        return key, error


class GoalOrientedBatch:
    """The goal-oriented learner for many agents (rows) at once, in a finite world:
    the contexts an agent can meet and the effects an action can have are listed in
    advance, and observations are their indices.

    Every row draws `DRAWS_PER_CHOICE` numbers from its own seed at each choice and
    follows `GoalOrientedAgent`'s steps with `NearestNeighbourTable` and
    `InterestTable` in place of the one-agent predictor and interest module, so row k
    makes exactly the choices of a `GoalOrientedAgent` seeded like it. Settings may
    differ per row.

    Args:
      seeds: one seed per row (the agents' own streams).
      contexts: the contexts, an array [n_contexts, entries] (for the buttons: the
        four light layouts).
      effects: the goal states an action can lead to, [n_effects, entries]; effect 0
        is the goal state at rest, which an empty predictor predicts.
      n_actions: actions per context.
      settings: a `GoalOrientedSettings` (default the library's); its per-row settings
        may hold one value per row (arrays).
      **values: settings given one by one instead (e.g. epsilon=0.2), checked like a
        new `GoalOrientedSettings`.

    Raises:
      ValueError: for a setting its `icm._settings.Setting` refuses (or with as many
        values as there are rows), or settings given both ways.
    """

    def __init__(self, seeds, contexts, effects, n_actions, settings=None, **values):
        self.streams = _streams.Streams(seeds)
        n = len(self.streams)
        if settings is None:
            settings = GoalOrientedSettings.from_arguments(values, "GoalOrientedBatch")
        elif values:
            raise ValueError(f"give the settings either as settings or one by one, got "
                             f"both (settings and {', '.join(values)})")
        self.settings = _validate.instance("settings", settings, GoalOrientedSettings)
        self.n_actions = n_actions
        self.effects = np.asarray(effects, dtype=float)
        self.epsilon = settings.per_row("epsilon", n)
        self.interest_per = settings.interest_per
        self.predictor = NearestNeighbourTable(n, contexts, n_actions,
                                               settings.per_row("action_weight", n),
                                               tie=settings.per_row("tie", n))
        n_keys = len(self.effects) if self.interest_per == "task" else n_actions
        self.interest = InterestTable(
            n, n_keys, settings.interest, settings.per_row("window", n),
            settings.per_row("new_task_factor", n), settings.per_row("reading", n),
            settings.per_row("new_task_mean", n), settings.per_row("short_history", n))
        # errors[p, o]: the Euclidean distance between effects p and o.
        self.errors = np.array([[math.dist(p, o) for o in self.effects] for p in self.effects])
        self.rows = np.arange(n)

    def predicted_effects(self, contexts):
        """The effect each action is predicted to have in each row's context, [rows,
        actions]."""
        n_contexts = self.predictor.effect.shape[1] // self.n_actions
        by_context = self.predictor.effect.reshape(-1, self.n_actions)
        return by_context.take(self.rows * n_contexts + contexts, axis=0)

    def action_interests(self, contexts):
        """The interest of each action in each row's context, [rows, actions]."""
        values = self.interest.values()
        if self.interest_per == "region":
            return values
        offsets = (self.rows * values.shape[1])[:, None]
        return values.reshape(-1).take(offsets + self.predicted_effects(contexts))

    def mean_action_interests(self):
        """The interest of each action, averaged over the contexts, [rows, actions]."""
        values = self.interest.values()
        n_contexts = self.predictor.effect.shape[1] // self.n_actions
        if self.interest_per == "region":  # the same in every context
            return np.stack([values] * n_contexts).mean(axis=0)
        effects = self.predictor.effect.reshape(len(values), n_contexts, self.n_actions)
        per_context = np.take_along_axis(values[:, None, :], effects, axis=2)
        return np.moveaxis(per_context, 1, 0).mean(axis=0)

    def select_actions(self, contexts):
        """Epsilon-greedy on interest, one action per row."""
        draws = self.streams.draw(k=action_selection.DRAWS_PER_CHOICE)
        return epsilon_greedy_rows(self.action_interests(contexts), self.epsilon, draws)

    def learn(self, contexts, actions, observed):
        """Every row scores its prediction of `actions` against the observed effects
        and remembers it; returns the prediction errors [rows]."""
        keys = self.predictor.keys(contexts, actions)
        predicted = self.predictor.predict(self.rows, keys)
        errors = self.errors[predicted, observed]
        witnessed = observed if self.interest_per == "task" else actions
        self.interest.record(None, witnessed, errors)
        self.predictor.update(None, keys, observed)
        return errors
