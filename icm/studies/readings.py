"""The choices the paper does not make and the robustness maps do not sweep, measured
one at a time (`run_readings`): for each, every other reading its `Setting` declares
(`icm._settings.Setting.other_readings`: an unpublished choice's other choices, or the
other values it lists), run on the same seeds as the book's reading, with the same
claims as the maps (`icm.studies.robustness.STUDIES`), kept in a `ReadingsResult`; and
what the rods' first episode is made of, which the chapter reads from the learner and
the topple map (`fewest_moves_to_topple`, `value_after_a_quiet_move`). What the chapter
says of them (its tables, clauses and checks) is `icm.chapters.robustness.readings`'.
"""

import collections
import dataclasses

import numpy as np

from icm import _validate
from icm.envs import rods
from icm.experiments.progress import progress_bar
from icm.studies.robustness import (NOT_MEASURED, STUDY_WORLDS, WORLD_SETTINGS, Study,
                                    check_study)
from icm.learners.q_learning import QLearner, QLearnerSettings
from icm.stats import share_interval, verdict


@dataclasses.dataclass(frozen=True)
class Reading:
    """Another reading of a choice the paper does not make.

    Attributes:
      name: the run function's argument.
      label: what it is, in words (the setting's label).
      default: the book's reading.
      value: the other reading.
      source: why the book reads it so (the setting's source).
    """

    name: str
    label: str
    default: object
    value: object
    source: str

    @property
    def key(self):
        """(name, value): the reading's key in a `ReadingsResult`."""
        return (self.name, self.value)


def unpublished_settings(study):
    """{name: Setting} of the settings of a study's learner and world that the paper
    does not publish, in declaration order (the learner's, then the world's)."""
    study = check_study(study)
    specs = {**study.run_fn.settings_class.specs(),
             **{n: WORLD_SETTINGS[n] for n in STUDY_WORLDS[study.name]}}
    return {name: spec for name, spec in specs.items() if not spec.published}


def readings(study):
    """The other readings `run_readings` measures for a study, as `Reading` objects:
    for each unpublished setting that its maps do not sweep (and that is not in
    `NOT_MEASURED`), each value of its `Setting.other_readings()`; and for an unpublished
    choice that the maps sweep on part of its choices, the choices off the maps' grid
    (the actor-critic's `variant`: the maps try the standard and the printed TD error,
    and the printed reward is read here), each at the other settings' defaults."""
    study = check_study(study)
    out = []
    for name, spec in unpublished_settings(study).items():
        if (study.name, name) in NOT_MEASURED:
            continue
        values = spec.other_readings()
        if spec.swept is not None and spec.kind == "choice":
            values = tuple(c for c in spec.choices if c not in spec.swept)
        for value in values:
            out.append(Reading(name, spec.label, spec.default, value, spec.source))
    return tuple(out)


@dataclasses.dataclass(frozen=True)
class ReadingsResult:
    """What `run_readings` measured for one study: the book's run and one run per
    other reading, all on the same seeds.

    Attributes:
      study: the `Study`.
      settings: the arguments of the runs (n_seeds, seed).
      readings: the `Reading` objects measured, in order.
      runs: {None: the book's run, (name, value): the run with that reading}, the run
        results (e.g. `RodTopplingResult`).
      held: {None or (name, value): {claim: bool array [seed]}}, whether each claim
        held in each seed.
    """

    study: Study
    settings: dict
    readings: tuple
    runs: dict
    held: dict

    @property
    def n_seeds(self):
        """Seeds per run."""
        return self.settings["n_seeds"]

    def _key(self, reading):
        if reading is None:
            return None
        key = reading.key if isinstance(reading, Reading) else reading
        if not isinstance(key, tuple) or key not in self.held:
            raise ValueError(f"reading must be None (the book's) or one of "
                             f"{[r.key for r in self.readings]}, got {reading!r}")
        return key

    def run(self, reading=None):
        """The run of `reading` (a `Reading` or its (name, value) key; None: the
        book's)."""
        return self.runs[self._key(reading)]

    def share(self, claim, reading=None):
        """(share, low, high): the share of seeds in which `claim` held with
        `reading` (None: the book's), and its 95% Wilson interval."""
        claim = self.study.claim(claim).name
        held = self.held[self._key(reading)][claim]
        low, high = share_interval(int(held.sum()), len(held))
        return float(held.mean()), low, high

    def verdict(self, claim, reading=None):
        """"holds", "unclear" or "fails": what `reading` says about `claim`."""
        _, low, high = self.share(claim, reading)
        return verdict(low, high, self.study.claim(claim).threshold)

    def changed(self, reading):
        """The claims (names) whose verdict `reading` changes from the book's."""
        return [c.name for c in self.study.claims
                if self.verdict(c.name, reading) != self.verdict(c.name)]

    def changes(self):
        """The readings that change the verdict of at least one claim."""
        return [r for r in self.readings if self.changed(r)]


def run_readings(study, n_seeds=200, seed=0, progress=True):
    """Runs a study's learner with the book's readings and with each other reading
    (`readings`), one at a time, all on the same seeds, and measures its claims.

    Args:
      study: "goal_oriented", "actor_critic" or "rod_toppling" (see `STUDIES`), or a
        `Study`.
      n_seeds: seeds per run (>= 1; the book uses 200).
      seed: the root seed (an integer >= 0, a Generator or None).
      progress: show a progress bar over the runs.

    Returns:
      A `ReadingsResult`.

    Raises:
      ValueError: for an unknown study or a bad n_seeds or seed.
    """
    study = check_study(study)
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    seed = _validate.root_seed("seed", seed)
    _validate.boolean("progress", progress)
    found = readings(study)
    runs, held = {}, {}
    for reading in progress_bar([None] + list(found), len(found) + 1,
                                f"other readings: {study.name}", progress, unit="run"):
        point = {} if reading is None else {reading.name: reading.value}
        key = None if reading is None else reading.key
        runs[key] = study.run_fn(n_seeds=n_seeds, seed=seed, progress=False, **study.fixed,
                                 **point)
        rows = study.per_seed(runs[key])
        held[key] = {c.name: np.array([row[c.name] for row in rows], dtype=bool)
                     for c in study.claims}
    return ReadingsResult(study, {"n_seeds": n_seeds, "seed": seed}, found, runs, held)


def fewest_moves_to_topple(rod):
    """The fewest moves from the start cell that topple `rod` ("red" or "blue") on the
    stored topple map: the moves through cells that topple nothing, then the move that
    topples it (a breadth-first search)."""
    rod = _validate.one_of("rod", rod, rods.ROD_NAMES)
    topples = rods.load_topple_map()["topples"]
    start = rods.DEFAULT_START_CELL
    moves = {start: 0}
    queue = collections.deque([start])
    while queue:
        cell = queue.popleft()
        for action in range(len(rods.ACTIONS)):
            toppled = topples.get((cell, action))
            if toppled == rod:
                return moves[cell] + 1
            if toppled is None:
                after = rods.next_cell(cell, action)
                if after not in moves:
                    moves[after] = moves[cell] + 1
                    queue.append(after)
    raise ValueError(f"no move of the stored topple map topples the {rod} rod")


def value_after_a_quiet_move(initial_q):
    """What the chapter's Q-learner values a move at after trying it once in its first
    episode, when the move toppled nothing: the teaching class `QLearner` (the book's
    settings, `initial_q` as given) moves right from the start cell with the rods
    standing, and the move's Q is read back.

    Args:
      initial_q: the value of a move never tried (a finite number >= 0).
    """
    settings = QLearnerSettings().replace(initial_q=initial_q)
    learner = QLearner.from_settings(rods.N_CELLS, len(rods.ACTIONS),
                                     n_outputs=len(rods.ROD_NAMES), settings=settings,
                                     seed=0)
    start = rods.DEFAULT_START_CELL
    right = rods.ACTIONS.index("right")
    state, after = (rods.cell_number(c) for c in
                    (start, rods.next_cell(start, right)))
    learner.learn(state, right, [0.0] * len(rods.ROD_NAMES), after)
    return float(learner.q[state, right])

