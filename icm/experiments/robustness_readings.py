"""The choices the paper does not make and the robustness maps do not sweep, measured
one at a time (`run_readings`): for each, every other reading its `Setting` declares
(`icm._settings.Setting.other_readings`: an unpublished choice's other choices, or the
other values it lists), run on the same seeds as the book's reading, with the same
claims as the maps (`icm.experiments.robustness.STUDIES`), kept in a `ReadingsResult`;
what the rods' first episode is made of, which the chapter reads from the learner and
the topple map (`fewest_moves_to_topple`, `value_after_a_quiet_move`,
`first_episode`); the two readings of "predicted well" on
a run whose untried moves are worth nothing (`strict_reading`); and, over several
results, which readings change a verdict, in words (`readings_summary`,
`changed_readings`).
"""

import collections
import dataclasses

import numpy as np

from icm import _validate
from icm.envs import rods
from icm.experiments._progress import progress_bar
from icm.experiments.robustness import (CLAIM_SHARE, NOT_MEASURED, STUDIES, STUDY_WORLDS,
                                        WORLD_SETTINGS, Study, check_study, show_value)
from icm.experiments.rod_toppling import RodTopplingResult
from icm.learners.q_learning import QLearner, QLearnerSettings
from icm.stats import comes_first, share_interval, verdict


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

    def table(self):
        """A Markdown table: the book's reading, then one row per other reading, with
        the share of seeds in which each claim held and its verdict (✓ holds, ✗
        fails, ? unclear; in bold where it differs from the book's)."""
        marks = {"holds": "✓", "fails": "✗", "unclear": "?"}
        claims = self.study.claims
        lines = ["| choice | reading | " + " | ".join(
                     f"{c.text} (≥ {c.threshold:.0%})" for c in claims) + " |",
                 "|---|---|" + "---|" * len(claims)]

        def cells(reading):
            out = []
            for c in claims:
                share, verdict_ = self.share(c.name, reading)[0], self.verdict(c.name, reading)
                cell = f"{share:.1%} {marks[verdict_]}"
                if reading is not None and verdict_ != self.verdict(c.name):
                    cell = f"**{cell}**"
                out.append(cell)
            return out

        lines.append("| the book's | all as in the book | " + " | ".join(cells(None)) + " |")
        for r in self.readings:
            lines.append(f"| {r.label} (book: {show_value(r.default)}) | {show_value(r.value)} | "
                         + " | ".join(cells(r)) + " |")
        return "\n".join(lines)

    def describe(self):
        """In words, which of the other readings change a claim's verdict, and how: a
        clause for the chapter, computed from the data."""
        changed = self.changes()
        n = len(self.readings)
        if not changed:
            return (f"None of the {n} other readings changes the verdict of a claim: "
                    f"each claim holds, fails or stays unclear as with the book's")
        parts = []
        for r in changed:
            what = ", ".join(f"\"{self.study.claim(c).text}\" {self.verdict(c, r)} "
                             f"({self.share(c, r)[0]:.1%} of the seeds; with the book's "
                             f"{show_value(r.default)}, it {self.verdict(c)}, "
                             f"{self.share(c)[0]:.1%})" for c in self.changed(r))
            parts.append(f"with {r.label} read as {show_value(r.value)}, {what}")
        rest = n - len(changed)
        changes = "changes" if len(changed) == 1 else "change"
        return (f"Of the {n} other readings, {len(changed)} {changes} a claim's verdict: "
                + "; ".join(parts) + f". The other {rest} change none")


def readings_summary(results):
    """In words, over several `ReadingsResult` objects, which other readings change a
    claim's verdict and how many change none: a clause for the chapter (Markdown).

    Args:
      results: a list of `ReadingsResult` objects.
    """
    named = changed_readings(results)  # checks the arguments
    changed = [(result, r) for result in results for r in result.changes()]
    total = sum(len(result.readings) for result in results)
    if not changed:
        return f"none of the {total} other readings changes a claim's verdict"
    verb = "changes" if len(changed) == 1 else "change"
    return (f"{len(changed)} of the {total} other readings {verb} a claim's verdict: "
            f"{named}; the other {total - len(changed)} change none")


def changed_readings(results, shares=True):
    """In words, each other reading (of several `ReadingsResult` objects) that changes a
    claim's verdict: with `shares`, with the learner, each claim it changes, its verdict
    and its share seen, e.g. "reading of the TD error and reward formulas:
    printed_reward (actor-critic: green predicted well too fails, 2.0%)"; without, with
    the learner alone ("...: printed_reward (actor-critic)"). "none" if none does
    (Markdown).

    Args:
      results: a list of `ReadingsResult` objects.
      shares: whether to name the claims changed, with their verdicts and shares.
    """
    if not isinstance(results, (list, tuple)) or not results:
        raise _validate.ArgumentTypeError(f"results must be a non-empty list of "
                                          f"ReadingsResult, got {_validate.show(results)}")
    for i, result in enumerate(results):
        _validate.instance(f"results[{i}]", result, ReadingsResult)
    _validate.boolean("shares", shares)
    named = [f"{r.label}: {show_value(r.value)} ({result.study.short}"
             + ("".join(f"{': ' if k == 0 else ', '}{result.study.claim(c).text} "
                        f"{result.verdict(c, r)}, {result.share(c, r)[0]:.1%}"
                        for k, c in enumerate(result.changed(r))) if shares else "")
             + ")" for result in results for r in result.changes()]
    return "; ".join(named) or "none"


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


def first_episode(initial_q_values):
    """What the chapter says of the rods' first episode, for the initial values of Q its
    map sweeps: ({claim name of `icm.chapters.robustness.FIRST_EPISODE_CLAIMS`: whether
    it holds}, numbers: the
    value of a quiet move after one try at the book's initial Q, "quiet_move_before" and
    "quiet_move_after", and the fewest moves that topple each rod, "red_moves" and
    "blue_moves").

    Args:
      initial_q_values: the initial values of Q the map sweeps (a list of numbers >= 0).
    """
    if not isinstance(initial_q_values, (list, tuple)) or not initial_q_values:
        raise _validate.ArgumentTypeError(f"initial_q_values must be a non-empty list of "
                                          f"numbers, got {_validate.show(initial_q_values)}")
    after = {q: value_after_a_quiet_move(q) for q in initial_q_values}
    book = STUDIES["rod_toppling"].setting("initial_q").default
    red, blue = fewest_moves_to_topple("red"), fewest_moves_to_topple("blue")
    claims = {"quiet_move_loses": all((a < q) if q > 0 else (a == 0) for q, a in after.items()),
              "red_nearer": red < blue}
    numbers = {"quiet_move_before": book, "quiet_move_after": value_after_a_quiet_move(book),
               "red_moves": red, "blue_moves": blue}
    return claims, numbers



def strict_reading(zero_run):
    """Why the rods' map reads "red predicted well" strictly ("all", every move that
    topples red, found or not), checked on a run whose untried moves are worth nothing:
    in chapter 5's reading "toppled" (the moves the robot has toppled red from), that run
    passes; in the strict one it fails.

    Args:
      zero_run: a `RodTopplingResult` with `initial_q` 0.

    Returns:
      ({claim name of `icm.chapters.robustness.STRICT_READING_CLAIMS`: whether it
      holds}, numbers:
      "zero_red_first_toppled" and "zero_red_first_strict", the shares seen, and
      "zero_seeds", the run's seeds).
    """
    _validate.instance("zero_run", zero_run, RodTopplingResult)
    if zero_run.settings["initial_q"] != 0:
        raise ValueError(f"zero_run must be a run with initial_q 0, got initial_q "
                         f"{zero_run.settings['initial_q']!r}")
    claims, numbers = {}, {"zero_seeds": zero_run.n_seeds}
    for reading, name in (("toppled", "toppled"), ("all", "strict")):
        well = zero_run.well_predicted(reading)
        held = comes_first(well[:, 0], well[:, 1])
        low, high = share_interval(int(held.sum()), len(held))
        numbers[f"zero_red_first_{name}"] = float(held.mean())
        numbers[f"zero_{name}_verdict"] = verdict(low, high, CLAIM_SHARE)
    claims["zero_passes_toppled"] = numbers["zero_toppled_verdict"] == "holds"
    claims["zero_fails_strict"] = numbers["zero_strict_verdict"] == "fails"
    return claims, numbers
