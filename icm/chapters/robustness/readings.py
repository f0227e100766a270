"""The chapter "What the result depends on" (book/robustness.ipynb), its other readings:
what the choices the paper does not make and the maps do not sweep do to the claims
(`readings_table`, `describe_readings`, `readings_summary`, `changed_readings`,
`readings_numbers`, of runs, each a `icm.studies.readings.ReadingsResult`); what the
rods' first episode is made of (`first_episode`, `FIRST_EPISODE_CLAIMS`); and the two
readings of "predicted well" on a run whose untried moves are worth nothing
(`strict_reading`, `STRICT_READING_CLAIMS`).
"""

from icm import _validate
from icm.experiments.rod_toppling import RodTopplingResult
from icm.stats import comes_first, share_interval, verdict
from icm.studies.readings import (ReadingsResult, fewest_moves_to_topple,
                                  value_after_a_quiet_move)
from icm.studies.robustness import CLAIM_SHARE, NOT_MEASURED, STUDIES, show_value


READINGS_SEEDS = 200
"""Seeds of each run of the other readings (`icm.studies.readings.run_readings`): the
200 seeds of root 0 that the chapters' own runs use, so that a reading's book run is the
chapter's run (Figure 7's story in the rods' run is chapter 5's)."""


def _readings(found):
    return _validate.instance("found", found, ReadingsResult,
                              "a ReadingsResult (from icm.studies.readings."
                              "run_readings)")


def readings_table(found):
    """A Markdown table of `found` (a `ReadingsResult`): the book's reading, then one row
    per other reading, with the share of seeds in which each claim held and its verdict
    (✓ holds, ✗ fails, ? unclear; in bold where it differs from the book's)."""
    found = _readings(found)
    marks = {"holds": "✓", "fails": "✗", "unclear": "?"}
    claims = found.study.claims
    lines = ["| choice | reading | " + " | ".join(
                 f"{c.text} (≥ {c.threshold:.0%})" for c in claims) + " |",
             "|---|---|" + "---|" * len(claims)]

    def cells(reading):
        out = []
        for c in claims:
            share, verdict_ = found.share(c.name, reading)[0], found.verdict(c.name, reading)
            cell = f"{share:.1%} {marks[verdict_]}"
            if reading is not None and verdict_ != found.verdict(c.name):
                cell = f"**{cell}**"
            out.append(cell)
        return out

    lines.append("| the book's | all as in the book | " + " | ".join(cells(None)) + " |")
    for r in found.readings:
        lines.append(f"| {r.label} (book: {show_value(r.default)}) | {show_value(r.value)} | "
                     + " | ".join(cells(r)) + " |")
    return "\n".join(lines)


def describe_readings(found):
    """In words, which of the other readings of `found` (a `ReadingsResult`) change a
    claim's verdict, and how: a clause for the chapter, computed from the data."""
    found = _readings(found)
    changed = found.changes()
    n = len(found.readings)
    if not changed:
        return (f"None of the {n} other readings changes the verdict of a claim: "
                f"each claim holds, fails or stays unclear as with the book's")
    parts = []
    for r in changed:
        what = ", ".join(f"\"{found.study.claim(c).text}\" {found.verdict(c, r)} "
                         f"({found.share(c, r)[0]:.1%} of the seeds; with the book's "
                         f"{show_value(r.default)}, it {found.verdict(c)}, "
                         f"{found.share(c)[0]:.1%})" for c in found.changed(r))
        parts.append(f"with {r.label} read as {show_value(r.value)}, {what}")
    rest = n - len(changed)
    changes = "changes" if len(changed) == 1 else "change"
    return (f"Of the {n} other readings, {len(changed)} {changes} a claim's verdict: "
            + "; ".join(parts) + f". The other {rest} change none")


FIRST_EPISODE_CLAIMS = {
    "quiet_move_loses": "in the first episode, a tried move that toppled nothing is worth "
                        "less than its starting value when that value is above zero, and "
                        "still zero when it is zero",
    "red_nearer": "the nearest red pair is fewer moves from the start than the nearest "
                  "blue pair",
}
"""What the chapter says of the rods' first episode (`first_episode`)."""


def first_episode(initial_q_values):
    """What the chapter says of the rods' first episode, for the initial values of Q its
    map sweeps: ({claim name of `FIRST_EPISODE_CLAIMS`: whether
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


STRICT_READING_CLAIMS = {
    "zero_passes_toppled": "with untried moves worth nothing, red is predicted well first "
                           "in chapter 5's reading \"toppled\"",
    "zero_fails_strict": "with untried moves worth nothing, red predicted well first fails "
                         "in the strict reading \"all\" of the rods' map",
}
"""What the chapter says of the reading of "predicted well" behind the rods' map
(`strict_reading` checks it)."""


def strict_reading(zero_run):
    """Why the rods' map reads "red predicted well" strictly ("all", every move that
    topples red, found or not), checked on a run whose untried moves are worth nothing:
    in chapter 5's reading "toppled" (the moves the robot has toppled red from), that run
    passes; in the strict one it fails.

    Args:
      zero_run: a `RodTopplingResult` with `initial_q` 0.

    Returns:
      ({claim name of `STRICT_READING_CLAIMS`: whether it
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


def readings_numbers(found):
    """The numbers and clauses the chapter "What the result depends on" quotes from
    its other readings, by the names its text uses.

    Args:
      found: {study name: `ReadingsResult`}, for the three studies.

    Returns:
      (numbers, clauses), as `maps.chapter_numbers`: per study `describe_readings`; over
      all of them `readings_summary` and `changed_readings`; k, the errors of the
      interest's slope ("k"), and the Q-learner's step size and discount ("alpha",
      "gamma"), as the book's runs used them; for the rods, the book's run, the run
      without a limit on moves and the run whose moves off the grid end the episode:
      the share of episodes that end on the time limit, of moves that run into the
      edge, of episodes that end there, the mean and the longest episode, the share of
      first episodes that end with red toppled, and Figure 7's story and order
      (`RodTopplingResult.tells_the_papers_story`, `in_paper_order`) in the strict
      reading "all" (`<run>_story`, `<run>_order`) and in chapter 5's reading
      "toppled", Figure 7's moment (b) (`<run>_story_toppled`, `<run>_order_toppled`).
    """
    if not isinstance(found, dict) or set(found) != set(STUDIES):
        raise _validate.ArgumentTypeError(f"found must be a dict of ReadingsResult by "
                                          f"study name ({', '.join(STUDIES)}), got "
                                          f"{_validate.show(found)}")
    for name, result in found.items():
        _validate.instance(f"found[{name!r}]", result, ReadingsResult)
    clauses = {f"readings_{name}": describe_readings(result) for name, result in found.items()}
    clauses["readings_summary"] = readings_summary(list(found.values()))
    clauses["readings_changed_list"] = changed_readings(list(found.values()), shares=False)
    clauses["not_measured_epsilon"] = NOT_MEASURED[("actor_critic", "epsilon")]
    rod_runs = found["rod_toppling"]
    book = rod_runs.run()
    numbers = {"max_moves": book.settings["max_moves"],
               "time_limit_share": book.time_limit_share(), "edge_share": book.edge_share(),
               "edge_ended_share": rod_runs.run(("off_grid", "end")).edge_ended_share(),
               "k": found["goal_oriented"].run().settings["window"],
               "alpha": book.settings["alpha"], "gamma": book.settings["gamma"]}
    for name, run in (("book", book), ("no_limit", rod_runs.run(("max_moves", None))),
                      ("off_grid_ends", rod_runs.run(("off_grid", "end")))):
        numbers[f"{name}_length"] = float(run.episode_length.mean())
        numbers[f"{name}_longest"] = int(run.episode_length.max())
        numbers[f"{name}_first_red"] = float(run.topple_share("red", slice(0, 1)))
        for reading, suffix in (("all", ""), ("toppled", "_toppled")):
            numbers[f"{name}_order{suffix}"] = run.red_before_blue_begins(reading)
            numbers[f"{name}_story{suffix}"] = float(
                run.tells_the_papers_story(reading).mean())
    return numbers, clauses
