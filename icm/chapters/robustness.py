"""The chapter "What the result depends on" (book/robustness.ipynb): its claims in
words (`CHAPTER_CLAIMS`, `BOLD_CLAIMS`) and their check on the book's maps
(`chapter_claims`), its Markdown tables (`studies_table`, `dependency_table`,
`interaction_table`) and the numbers and clauses its text quotes (`chapter_numbers`,
`readings_numbers`), from the results of `icm.experiments.robustness` and
`icm.experiments.robustness_readings`.
"""

from icm import _validate
from icm.experiments.results import in_seeds
from icm.experiments.robustness import (NOT_MEASURED, STUDIES, RobustnessResult, check_study,
                                        show_value)
from icm.experiments.robustness_readings import ReadingsResult


def studies_table(studies=None):
    """A Markdown table of the studies: for each learner, the settings its maps sweep
    and the claims they measure, with the share of seeds each needs.

    Args:
      studies: names or `Study` objects (default all of `STUDIES`).
    """
    studies = [check_study(s) for s in (STUDIES if studies is None else studies)]
    lines = ["| learner | settings swept | claims (share of seeds needed) |", "|---|---|---|"]
    for study in studies:
        lines.append(f"| {study.title} | {', '.join(s.label for s in study.settings)} | "
                     + "; ".join(f"{c.text} (≥ {c.threshold:.0%})" for c in study.claims)
                     + " |")
    return "\n".join(lines)


def dependency_table(results):
    """A Markdown table: for each learner and setting, the values (of those tried) at
    which each claim holds when only that setting changes.

    Args:
      results: a list of `RobustnessResult` objects.

    Returns:
      A Markdown string.
    """
    _check_results(results)
    lines = ["| learner | setting (default) | tried | claim | holds at |",
             "|---|---|---|---|---|"]
    for result in results:
        for setting in result.study.settings:
            tried = ", ".join(show_value(v) for v in setting.values)
            for claim in result.study.claims:
                held = result.holding_values(claim.name, setting.name)
                where = "all" if len(held) == len(setting.values) else \
                    (", ".join(show_value(v) for v in held) or "none")
                lines.append(f"| {result.study.title} | {setting.label} "
                             f"({show_value(setting.default)}) | {tried} | {claim.text} "
                             f"(≥ {claim.threshold:.0%}) | {where} |")
    return "\n".join(lines)


def interaction_table(results):
    """A Markdown table: for each learner, claim and pair of settings, the strongest
    interaction on the pair's map (see `RobustnessResult.interaction`), in points of
    share, with its band and where it is, and whether the pair interacts.

    Args:
      results: a list of `RobustnessResult` objects.

    Returns:
      A Markdown string.
    """
    _check_results(results)
    lines = ["| learner | claim | pair | strongest interaction (points, band) | at | "
             "interact? |", "|---|---|---|---|---|---|"]
    for result in results:
        for claim in result.study.claims:
            for pair in result.study.pairs():
                a, b = (result.study.setting(n) for n in pair)
                contrast, low, high, va, vb = result.strongest_interaction(claim.name, pair)
                lines.append(
                    f"| {result.study.title} | {claim.text} | {a.label} x {b.label} "
                    f"| {100 * contrast:+.0f} ({100 * low:+.0f} to {100 * high:+.0f}) "
                    f"| {show_value(va)}, {show_value(vb)} "
                    f"| {'yes' if result.interacts(claim.name, pair) else 'no'} |")
    return "\n".join(lines)


def _check_results(results):
    if not isinstance(results, (list, tuple)) or not results:
        raise _validate.ArgumentTypeError(f"results must be a non-empty list of "
                                          f"RobustnessResult, got {_validate.show(results)}")
    for i, result in enumerate(results):
        _validate.instance(f"results[{i}]", result, RobustnessResult)
    return results


def readings_summary(results):
    """In words, over several `ReadingsResult` objects, which other readings change a
    claim's verdict and how many change none: a clause for the chapter (Markdown).

    Args:
      results: a list of `ReadingsResult` objects.
    """
    if not isinstance(results, (list, tuple)) or not results:
        raise _validate.ArgumentTypeError(f"results must be a non-empty list of "
                                          f"ReadingsResult, got {_validate.show(results)}")
    for i, result in enumerate(results):
        _validate.instance(f"results[{i}]", result, ReadingsResult)
    changed = [(result, r) for result in results for r in result.changes()]
    total = sum(len(result.readings) for result in results)
    if not changed:
        return f"none of the {total} other readings changes a claim's verdict"
    named = "; ".join(f"{r.label} read as {show_value(r.value)} ({result.study.title}: "
                      + ", ".join(f"{result.study.claim(c).text} {result.verdict(c, r)}"
                                  for c in result.changed(r)) + ")"
                      for result, r in changed)
    verb = "changes" if len(changed) == 1 else "change"
    return (f"{len(changed)} of the {total} other readings {verb} a claim's verdict: "
            f"{named}; the other {total - len(changed)} change none")


CHAPTER_CLAIMS = {
    "weight_threshold": "red first fails at every action weight below a threshold and "
                        "holds at every weight from it",
    "weight_above_settles_red": "above that threshold red comes first at every point of the "
                                "map, whatever the presses and the reading",
    "interest_needs_progress": "interest moves to green later with the progress reading "
                               "and fails with the literal one",
    "interest_weight_from": "interest moves to green later from some action weight on, "
                            "and not at the lowest weight tried",
    "interest_progress_any_presses": "with the progress reading and a weight from the "
                                     "threshold, interest moves later for every number of "
                                     "presses",
    "green_needs_two_presses": "green is mastered at every point but those with the fewest "
                               "presses per trial, where it fails",
    "critic_red_everywhere": "the actor-critic predicts red well first at every point",
    "printed_td_alone": "with the printed TD error and the other defaults, the actor-critic "
                        "predicts red well first and learns green",
    "printed_td_damage": "with the printed TD error, green fails with the weakest predictor "
                         "and with the fewest presses, where the standard one does not fail",
    "td_interacts": "the TD error interacts with the action weight and with the presses "
                    "for green",
    "rods_toppled_first_everywhere": "red toppled first fails at no point of the map",
    "rods_small_initial_q": "red is predicted well first only for initial values between "
                            "the smallest and the largest tried",
    "rods_epsilon": "red predicted well first holds at an epsilon other than the default, "
                    "and not at the largest tried",
    "rods_blue_needs_drive": "blue is found at every point with an initial Q above zero, "
                             "whatever epsilon, and fails with no initial Q and no random "
                             "moves (the chapter gives the other epsilons at no initial Q "
                             "by their shares and verdicts, not as a claim)",
    "presses_not_needed": "red first and the interest's order hold at every number of "
                          "presses tried",
}
"""The claims of the chapter "What the result depends on" about its maps
(`chapter_claims`)."""


BOLD_CLAIMS = {
    "Above the threshold, red comes first at every point of the maps, whatever the "
    "presses and the reading.": ("weight_above_settles_red", "all"),
    "Red is predicted well first at every point of these maps": ("critic_red_everywhere",
                                                                 "all"),
}
"""The bold claims of the chapter "What the result depends on" that use a word of
strength (book/_ext/claim_words.py), each with the claim of `CHAPTER_CLAIMS` that
checks it and the kind of that check: "all", every point's verdict "holds" (a claim
that must hold at every point of a map is the conjunction of the points' own tests,
which needs no correction for their number: it fails if any one fails)."""


def _every(result, claim, verdict_, **where):
    """Whether `claim` has the verdict `verdict_` at every measured point of `result`
    whose settings satisfy `where` ({setting: function of its value -> bool})."""
    table = result.points()
    for name, test in where.items():
        table = table[table[name].map(test)]
    return bool(len(table)) and bool((table[claim + "_verdict"] == verdict_).all())


def chapter_claims(goal, critic, rods_result):
    """{claim name: whether it holds}, for each of `CHAPTER_CLAIMS`: what the chapter
    "What the result depends on" states in words about its three maps, checked on the
    book's maps when it is built (and by the tests on theirs).

    Args:
      goal, critic, rods_result: the `RobustnessResult` objects of the studies
        "goal_oriented", "actor_critic" and "rod_toppling".
    """
    for name, result, study in (("goal", goal, "goal_oriented"), ("critic", critic,
                                "actor_critic"), ("rods_result", rods_result, "rod_toppling")):
        _validate.instance(name, result, RobustnessResult)
        if result.study.name != study:
            raise ValueError(f"{name} must be the study {study!r}, got "
                             f"{result.study.name!r}")
    weights = goal.study.setting("action_weight").values
    presses = goal.study.setting("presses_per_trial").values
    threshold = goal.holds_from("red_first", "action_weight")
    below = [w for w in weights if threshold is None or w < threshold]
    interest_from = goal.holds_from("interest_later", "action_weight")
    critic_weights = critic.study.setting("action_weight").values
    critic_presses = critic.study.setting("presses_per_trial").values
    qs = list(rods_result.study.setting("initial_q").values)
    epsilons = rods_result.study.setting("epsilon").values
    q_held = rods_result.holding_values("red_first", "initial_q")
    epsilon_held = rods_result.holding_values("red_first", "epsilon")
    default_epsilon = rods_result.study.setting("epsilon").default
    return {
        "weight_threshold": threshold is not None and bool(below) and all(
            goal.verdict("red_first", action_weight=w) == "fails" for w in below),
        "weight_above_settles_red": threshold is not None and _every(
            goal, "red_first", "holds", action_weight=lambda w: w >= threshold),
        "interest_needs_progress": goal.verdict("interest_later") == "holds"
        and goal.verdict("interest_later", reading="literal") == "fails",
        "interest_weight_from": interest_from is not None and interest_from > weights[0],
        "interest_progress_any_presses": threshold is not None and _every(
            goal, "interest_later", "holds", action_weight=lambda w: w >= threshold,
            reading=lambda r: r == "progress"),
        "green_needs_two_presses": _every(goal, "green_mastered", "fails",
                                          presses_per_trial=lambda p: p == presses[0])
        and _every(goal, "green_mastered", "holds",
                   presses_per_trial=lambda p: p != presses[0]),
        "critic_red_everywhere": _every(critic, "red_first", "holds"),
        "printed_td_alone": critic.verdict("red_first", variant="printed_td") == "holds"
        and critic.verdict("green_learned", variant="printed_td") == "holds",
        "printed_td_damage": all(
            critic.verdict("green_learned", variant="printed_td", **point) == "fails"
            and critic.verdict("green_learned", **point) != "fails"
            for point in ({"action_weight": critic_weights[0]},
                          {"presses_per_trial": critic_presses[0]})),
        "td_interacts": critic.interacts("green_learned", ("action_weight", "variant"))
        and critic.interacts("green_learned", ("presses_per_trial", "variant")),
        "rods_toppled_first_everywhere": not (rods_result.points()["red_toppled_first_verdict"]
                                              == "fails").any(),
        "rods_small_initial_q": bool(q_held) and q_held[0] != qs[0]
        and q_held[-1] != qs[-1]
        and q_held == qs[qs.index(q_held[0]):qs.index(q_held[-1]) + 1],
        "rods_epsilon": any(e != default_epsilon for e in epsilon_held)
        and epsilons[-1] not in epsilon_held,
        "rods_blue_needs_drive": _every(rods_result, "blue_found", "holds",
                                        initial_q=lambda q: q > 0)
        and rods_result.verdict("blue_found", initial_q=qs[0], epsilon=epsilons[0])
        == "fails" and qs[0] == 0 and epsilons[0] == 0,
        "presses_not_needed": all(goal.verdict(c, presses_per_trial=p) == "holds"
                                  for c in ("red_first", "interest_later") for p in presses),
    }


def chapter_numbers(goal, critic, rods_result):
    """The numbers and clauses the chapter "What the result depends on" quotes from
    its three maps, by the names its text uses.

    Args:
      goal, critic, rods_result: the `RobustnessResult` objects of the studies
        "goal_oriented", "actor_critic" and "rod_toppling".

    Returns:
      (numbers, clauses): two dicts, {name: a number or a word} and {name: a clause in
      Markdown}. Each study's `summary()` is there too, its keys prefixed with the study
      (``goal_``, ``critic_``, ``rods_``).
    """
    chapter_claims(goal, critic, rods_result)  # checks the arguments
    numbers, clauses = {}, {}
    for prefix, result in (("goal_", goal), ("critic_", critic), ("rods_", rods_result)):
        numbers.update({prefix + k: v for k, v in result.summary().items()})
    # The goal-oriented learner.
    weight = goal.study.setting("action_weight")
    presses = goal.study.setting("presses_per_trial").values
    threshold = goal.holds_from("red_first", "action_weight")
    above = goal.points().query("action_weight >= @threshold")
    numbers.update(
        default_weight=weight.default, goal_lowest_weight=threshold,
        goal_highest_failing_weight=max(w for w in weight.values if w < threshold),
        goal_red_first_above_min=float(above.red_first.min()),
        goal_later_progress_min=float(above.query("reading == 'progress'")
                                      .interest_later.min()),
        lowest_weight=weight.values[0],
        goal_later_lowest_weight=goal.share("interest_later",
                                            action_weight=weight.values[0])[0],
        goal_later_lowest_weight_verdict=goal.verdict("interest_later",
                                                      action_weight=weight.values[0]),
        goal_later_literal=goal.share("interest_later", reading="literal")[0],
        goal_later_weights_lowest=goal.holds_from("interest_later", "action_weight"),
        presses_low=min(presses), presses_high=max(presses),
        goal_green_one_press=goal.share("green_mastered", presses_per_trial=min(presses))[0],
        goal_presses_in_run=min(presses) * goal.study.fixed["n_trials"])
    clauses["goal_red_first_by_weight"] = goal.shares_along("red_first", "action_weight")
    # The actor-critic.
    weakest = critic.study.setting("action_weight").values[0]
    fewest = critic.study.setting("presses_per_trial").values[0]
    numbers.update(critic_weakest=weakest, critic_fewest=fewest)
    for name, point in (("printed", {"variant": "printed_td"}),
                        ("printed_weakest", {"variant": "printed_td", "action_weight": weakest}),
                        ("printed_fewest", {"variant": "printed_td",
                                            "presses_per_trial": fewest}),
                        ("weakest", {"action_weight": weakest}),
                        ("fewest", {"presses_per_trial": fewest})):
        numbers[f"critic_green_{name}"] = critic.share("green_learned", **point)[0]
    # The Q-learner on the rods.
    qs = rods_result.study.setting("initial_q").values
    epsilon = rods_result.study.setting("epsilon")
    held = rods_result.holding_values("red_first", "initial_q")
    numbers.update(
        rods_q_lowest=min(held), rods_q_highest=max(held), rods_q_none=qs[0],
        rods_epsilon_default=epsilon.default, rods_epsilon_largest=epsilon.values[-1],
        rods_epsilon_largest_verdict=rods_result.verdict("red_first",
                                                         epsilon=epsilon.values[-1]),
        rods_blue_positive_q_min=float(rods_result.points().query("initial_q > 0")
                                       .blue_found.min()))
    clauses.update(
        rods_red_first_by_q=rods_result.shares_along("red_first", "initial_q"),
        rods_red_first_by_epsilon=rods_result.shares_along("red_first", "epsilon"),
        rods_blue_q_none_by_epsilon=rods_result.shares_along("blue_found", "epsilon",
                                                             initial_q=qs[0]))
    toppled = rods_result.points()["red_toppled_first_verdict"]
    holds = int((toppled == "holds").sum())
    clauses["rods_toppled_first_points"] = (
        f"it holds at every one of the {len(toppled)} points" if holds == len(toppled) else
        f"it holds at {holds} of the {len(toppled)} points and is unclear at the others")
    # The fewest seeds, in words ("in every seed" rather than "in at least 100.0%").
    for name in ("goal_red_first_above_min", "critic_red_first_min",
                 "rods_red_toppled_first_min", "rods_blue_positive_q_min"):
        clauses[name.replace("_min", "_in")] = in_seeds(numbers[name])
    return numbers, clauses


def readings_numbers(found):
    """The numbers and clauses the chapter "What the result depends on" quotes from
    its other readings, by the names its text uses.

    Args:
      found: {study name: `ReadingsResult`}, for the three studies.

    Returns:
      (numbers, clauses), as `chapter_numbers`: per study its `describe()`; over
      all of them `readings_summary`; for the rods, the book's run, the run without a
      limit on moves and the run whose moves off the grid end the episode: the share
      of episodes that end on the time limit, of moves that run into the edge, of
      episodes that end there, the mean and the longest episode, and Figure 7's
      story and order (`RodTopplingResult.tells_the_papers_story`, `in_paper_order`).
    """
    if not isinstance(found, dict) or set(found) != set(STUDIES):
        raise _validate.ArgumentTypeError(f"found must be a dict of ReadingsResult by "
                                          f"study name ({', '.join(STUDIES)}), got "
                                          f"{_validate.show(found)}")
    for name, result in found.items():
        _validate.instance(f"found[{name!r}]", result, ReadingsResult)
    clauses = {f"readings_{name}": result.describe() for name, result in found.items()}
    clauses["readings_summary"] = readings_summary(list(found.values()))
    clauses["not_measured_epsilon"] = NOT_MEASURED[("actor_critic", "epsilon")]
    rod_runs = found["rod_toppling"]
    book = rod_runs.run()
    numbers = {"max_moves": book.settings["max_moves"],
               "time_limit_share": book.time_limit_share(), "edge_share": book.edge_share(),
               "edge_ended_share": rod_runs.run(("off_grid", "end")).edge_ended_share()}
    for name, run in (("book", book), ("no_limit", rod_runs.run(("max_moves", None))),
                      ("off_grid_ends", rod_runs.run(("off_grid", "end")))):
        numbers[f"{name}_length"] = float(run.episode_length.mean())
        numbers[f"{name}_longest"] = int(run.episode_length.max())
        numbers[f"{name}_order"] = run.red_before_blue_begins()
        numbers[f"{name}_story"] = float(run.tells_the_papers_story().mean())
    return numbers, clauses


REPLICATION_SEEDS = 200
"""Seeds at every point of the replication's maps: as many as the chapter's, so that
each point's interval is as narrow as the one it replicates."""


def run_replication(n_seeds=REPLICATION_SEEDS, progress=False):
    """The chapter's claims (`chapter_claims`) rechecked on its three maps run again on a
    root seed that no study, chapter or other test uses
    (`icm.experiments.replication.REPLICATION_ROOTS["robustness"]`), `n_seeds` at every
    point: {"root", "n_seeds", "claims": {name: whether it held again}, "critic_lowest":
    the actor-critic's lowest share of red predicted well first over its map, with its
    interval, verdict and point} (the point behind the chapter's bold "every point"
    claim of the actor-critic, the claim most exposed to one point's chance)."""
    from icm.experiments import replication, robustness

    root = replication.REPLICATION_ROOTS["robustness"]
    maps = {name: robustness.run_robustness(name, n_seeds=n_seeds, seed=root,
                                            progress=progress)
            for name in ("goal_oriented", "actor_critic", "rod_toppling")}
    claims = chapter_claims(maps["goal_oriented"], maps["actor_critic"],
                            maps["rod_toppling"])
    points = maps["actor_critic"].points()
    lowest = points.loc[points["red_first"].idxmin()]
    settings = [s.name for s in maps["actor_critic"].study.settings]
    return {"root": root, "n_seeds": n_seeds,
            "claims": {name: bool(held) for name, held in claims.items()},
            "critic_lowest": {"share": float(lowest["red_first"]),
                              "low": float(lowest["red_first_low"]),
                              "high": float(lowest["red_first_high"]),
                              "verdict": str(lowest["red_first_verdict"]),
                              "point": {name: show_value(lowest[name])
                                        for name in settings}}}


def replication_sentences(stored):
    """What the chapter says of its replication (`run_replication`, as
    assets/replications.json keeps it under "robustness"): {"summary": how many of the
    claims held again and which did not, "critic_everywhere": the sentence beside the
    bold claim that red is predicted well first at every point}."""
    claims = stored["claims"]
    failed = [CHAPTER_CLAIMS[name] for name, held in claims.items() if not held]
    summary = (f"On a fresh root seed ({stored['root']}, {stored['n_seeds']} seeds at "
               f"every point), {len(claims) - len(failed)} of the {len(claims)} claims "
               f"held again")
    summary += (": all of them." if not failed else
                "; not replicated: " + "; ".join(f'"{f}"' for f in failed) + ".")
    low = stored["critic_lowest"]
    where = ", ".join(f"{name} = {value}" for name, value in low["point"].items())
    if claims["critic_red_everywhere"]:
        critic = (f"On a fresh root seed it held again: red was predicted well first "
                  f"in at least {low['share']:.1%} of the seeds, at {where}.")
    else:
        critic = (f"Not replicated on a fresh root seed: there, at {where}, red was "
                  f"predicted well first in {low['share']:.1%} of the seeds "
                  f"({low['low']:.1%} to {low['high']:.1%}; verdict: {low['verdict']}, "
                  f"not holds). A claim about every point is as weak as its weakest "
                  f"point.")
    return {"summary": summary, "critic_everywhere": critic}


def main():
    """`python -m icm.chapters.robustness`: runs `run_replication` and writes it into
    assets/replications.json under "robustness" (the other chapters' entries kept)."""
    import json

    from icm.envs._assets import ASSETS
    from icm.experiments import replication

    out = replication.load_replications()
    out["robustness"] = run_replication(progress=True)
    path = ASSETS / replication.REPLICATION_FILE
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
