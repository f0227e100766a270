"""The goal-babbling agent (Rolf, Steil and Gienger 2010; SAGG-RIAC, Baranes and
Oudeyer 2013): an interest model proposes a goal, a sensorimotor model turns it into
a movement, and both learn from what the movement reached; explauto's agent loop
(`produce`, then `perceive`), for many agents (rows) at once, optionally with a body
that grows (`icm.learners.maturation`) and a teacher's demonstrations."""

import numpy as np

from icm import _validate
from icm._settings import Settings, setting_from, settings_class
from icm.learners import goal_choice as _goal_choice
from icm.learners import maturation as _maturation
from icm.learners import sensorimotor as _sensorimotor
from icm.learners.maturation import JointRangeMaturation
from icm.learners.sensorimotor import NearestNeighbourInverse

N_BOOTSTRAP = 20
"""The goal strategies start with this many random motor commands (the inverse model
needs outcomes to start from). Our choice; the paper has no goal babbling."""


@settings_class
class GoalBabblingSettings(Settings):
    """The goal-babbling learner's settings: its goal-choice strategy and, for learning
    progress, its measure, regions, epsilon and window; its inverse model and
    exploration noise; whether it grows up, and its maturational clock's settings
    (`maturation_start`, `maturation_window`, `maturation_plateau`, `maturation_step`:
    `icm.learners.maturation.MaturationSettings`' own, under the names
    `MATURATION_FIELDS` gives them). Each is a `icm._settings.Setting`, declared where it
    is used (`icm.learners.goal_choice`, `sensorimotor`, `maturation`): see
    `GoalBabblingSettings.specs()` for its range and where it comes from (the paper has
    no goal babbling). `icm.experiments.run_goal_babbling`, the studies (an arm's
    arguments) and the command line read it."""

    strategy: str = setting_from(_goal_choice.STRATEGY, per_row=False)
    exploration_noise: float = setting_from(_sensorimotor.EXPLORATION_NOISE, per_row=False)
    epsilon: float = setting_from(_goal_choice.EPSILON, per_row=False)
    window: int = setting_from(_goal_choice.WINDOW, per_row=False)
    inverse_model: str = setting_from(_sensorimotor.INVERSE_MODEL, per_row=False)
    measure: str = setting_from(_goal_choice.MEASURE, per_row=False)
    regions: str = setting_from(_goal_choice.REGIONS, per_row=False)
    maturation: str = setting_from(_maturation.MATURATION, per_row=False)
    maturation_start: float = setting_from(_maturation.MaturationSettings.spec("start"))
    maturation_window: int = setting_from(_maturation.MaturationSettings.spec("window"))
    maturation_plateau: float = setting_from(_maturation.MaturationSettings.spec("plateau"))
    maturation_step: float = setting_from(_maturation.MaturationSettings.spec("step"))

    def maturation_settings(self):
        """The maturational clock's settings, a `MaturationSettings` (read when
        `maturation` is "joint_range")."""
        return _maturation.MaturationSettings(**{
            name: getattr(self, field) for field, name in MATURATION_FIELDS.items()})


MATURATION_FIELDS = {f"maturation_{name}": name
                     for name in _maturation.MaturationSettings.names()}
"""{`GoalBabblingSettings` field: `MaturationSettings` field}: the clock's settings as
the learner's settings name them."""


class GoalBabblingAgent:
    """Goal babbling for many agents (rows) at once, each with its own generator.

    `produce` gives each row's next movement: first the teacher's `demonstrations`,
    one per rollout, the same for every row (no random number drawn); then, for
    `n_bootstrap` rollouts, and always without an interest model (random motor
    babbling), joint targets uniform within the joints' ranges (7 numbers from the
    row's generator); afterwards, a goal from the interest model
    (`goal_choice.sample`), turned into an outcome by `goal_outcome`, and a movement
    for it from the sensorimotor model (`inverse_model.explore`). `perceive` gives
    both what the movement reached: a demonstration enters the sensorimotor model's
    memory like any movement, and the interest model learns nothing from it (it
    had no goal).

    With `maturation`, the joints' ranges are the row's reachable ranges now
    (`maturation.bounds()`): random commands are uniform within them, the inverse
    model's movements are clipped to them, and after each goal the maturation
    learns the distance to it. A demonstration is performed as shown, whatever
    the range (the teacher moves the arm).

    Args:
      inverse_model: a sensorimotor model (`icm.learners.sensorimotor`), with one
        row per agent.
      goal_choice: an interest model (`icm.learners.goal_choice.RandomGoals`,
        `RegionProgress` or `SplittingRegionProgress`), or None for random motor
        babbling.
      generators: one `numpy.random.Generator` per row.
      goal_outcome: a function from goals [rows, dims] to the outcomes they ask for
        [rows, n_outcome] (default: the goals themselves).
      n_bootstrap: random motor commands before the first goal (>= 1).
      maturation: a `icm.learners.maturation.JointRangeMaturation` with one row per
        agent, or None (the full ranges from the start).
      demonstrations: the teacher's movements, an array [demonstration, joints]
        within the joints' ranges, or None (no teacher).
    """

    def __init__(self, inverse_model, goal_choice, generators, goal_outcome=None,
                 n_bootstrap=N_BOOTSTRAP, maturation=None, demonstrations=None):
        self.inverse_model = _validate.instance("inverse_model", inverse_model,
                                                NearestNeighbourInverse)
        if goal_choice is not None and not all(
                callable(getattr(goal_choice, m, None)) for m in ("sample", "update", "values")):
            raise _validate.ArgumentTypeError(
                f"goal_choice must be a goal choice (with sample, update and values, as "
                f"icm.learners.goal_choice.make_goal_choice makes) or None, got "
                f"{_validate.show(goal_choice)}")
        self.goal_choice = goal_choice
        self.generators = list(generators)
        if len(self.generators) != inverse_model.n_rows:
            raise ValueError(f"generators must be one per row ({inverse_model.n_rows}), "
                             f"got {len(self.generators)}")
        for k, rng in enumerate(self.generators):
            _validate.instance(f"generators[{k}]", rng, np.random.Generator)
        self.goal_outcome = _validate.function("goal_outcome", goal_outcome) or (lambda g: g)
        self.n_bootstrap = _validate.integer_at_least("n_bootstrap", n_bootstrap, 1)
        if maturation is not None:
            _validate.instance("maturation", maturation, JointRangeMaturation,
                               "a JointRangeMaturation or None")
            if maturation.n_rows != inverse_model.n_rows:
                raise ValueError(f"maturation must have one row per agent "
                                 f"({inverse_model.n_rows}), got {maturation.n_rows}")
        self.maturation = maturation
        if demonstrations is None:
            demonstrations = np.zeros((0, len(inverse_model.lower)))
        demonstrations = _validate.finite_array("demonstrations", demonstrations, ndim=2)
        if demonstrations.shape[1] != len(inverse_model.lower) or np.any(
                (demonstrations < inverse_model.lower) | (demonstrations > inverse_model.upper)):
            raise ValueError(f"demonstrations must be movements [demonstration, "
                             f"{len(inverse_model.lower)}] within the joints' ranges, got "
                             f"{_validate.show(demonstrations)}")
        self.demonstrations = demonstrations
        self.n_produced = 0
        self._goal_outcomes = None

    @classmethod
    def from_settings(cls, settings, generators, lower, upper, capacity, n_outcome, grid,
                      home, goal_outcome=None, demonstrations=None):
        """The agent of `settings`: its inverse model, goal choice and (if it grows up)
        maturational clock built from them, one row per generator.

        Args:
          settings: a `GoalBabblingSettings` (None: the library's).
          generators: one `numpy.random.Generator` per row.
          lower, upper: the joints' ranges, arrays [joints].
          capacity: the movements each row's inverse model keeps (>= 1).
          n_outcome: the outcomes' dimensions.
          grid: the goals' `icm.learners.goal_choice.RegionGrid`.
          home: the resting posture, where a growing arm starts.
          goal_outcome, demonstrations: as the constructor's.

        Returns:
          A `GoalBabblingAgent`.
        """
        settings = GoalBabblingSettings() if settings is None else _validate.instance(
            "settings", settings, GoalBabblingSettings)
        generators = list(generators)
        n_rows = len(generators)
        model = _sensorimotor.make_inverse_model(
            settings.inverse_model, n_rows, capacity, lower, upper, n_outcome,
            exploration_noise=settings.exploration_noise)
        choice = _goal_choice.make_goal_choice(settings.strategy, grid, n_rows,
                                               settings.measure, settings.epsilon,
                                               settings.window, settings.regions)
        clock = None if settings.maturation == "none" else \
            JointRangeMaturation.from_settings(n_rows, home, lower, upper,
                                               settings.maturation_settings())
        return cls(model, choice, generators, goal_outcome, maturation=clock,
                   demonstrations=demonstrations)

    @property
    def n_rows(self):
        return self.inverse_model.n_rows

    def produce(self):
        """The next movement of every row: (movements [rows, joints], goals [rows, dims]
        or None while babbling randomly, regions [rows] or None)."""
        model = self.inverse_model
        self.n_produced += 1
        n_shown = len(self.demonstrations)
        self._goal_outcomes = None
        if self.n_produced <= n_shown:
            shown = self.demonstrations[self.n_produced - 1]
            return np.tile(shown, (self.n_rows, 1)), None, None
        if self.maturation is None:
            lower, upper = [model.lower] * self.n_rows, [model.upper] * self.n_rows
        else:
            lower, upper = self.maturation.bounds()
        if self.goal_choice is None or self.n_produced <= n_shown + self.n_bootstrap:
            return (np.array([rng.uniform(low, high) for rng, low, high
                              in zip(self.generators, lower, upper)]), None, None)
        goals, regions = self.goal_choice.sample(self.generators)
        self._goal_outcomes = self.goal_outcome(goals)
        self._regions = regions
        movements = model.explore(self._goal_outcomes, self.generators)
        if self.maturation is not None:
            movements = self.maturation.clip(movements)
        return movements, goals, regions

    def perceive(self, movements, outcomes):
        """Every row learns what its last movement reached: `movements` [rows, joints]
        (as performed), `outcomes` [rows, n_outcome]. Returns the distances between
        the goals and the outcomes [rows] (None after a random motor command)."""
        self.inverse_model.update(movements, outcomes)
        if self._goal_outcomes is None:
            return None
        distances = np.sqrt(((self._goal_outcomes - outcomes) ** 2).sum(axis=1))
        self.goal_choice.update(self._regions, distances)
        if self.maturation is not None:
            self.maturation.update(distances)
        return distances
