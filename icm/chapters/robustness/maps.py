"""The chapter "What the result depends on" (book/robustness.ipynb), its maps: the
claims about them in words (`CHAPTER_CLAIMS`) and their check on the book's maps
(`chapter_claims`), the Markdown tables (`studies_table`, `dependency_table`,
`interaction_table`), the numbers and clauses the text quotes (`chapter_numbers`,
`shares_along`), and the maps' replication on a fresh root (`run_replication`,
`replication_sentences`), from the results of `icm.studies.robustness`.
"""

from icm import _validate
from icm.chapters.words import in_seeds
from icm.experiments.rod_episodes import WELL_PREDICTED_ERROR
from icm.studies.maps import RobustnessResult
from icm.studies.robustness import CLAIM_SHARE, STUDIES, check_study, show_value
from icm.stats import LEVEL, share_interval


MAP_SEEDS = {"goal_oriented": 1000, "actor_critic": 1000, "rod_toppling": 1000}
"""Seeds at every point of each learner's map in the chapter "What the result depends
on" (and in its replication, `run_replication`).

A claim about every point of a map needs each point to clear its threshold, and some
shares lie near it: the actor-critic's "red predicted well first" at 94% to 99%, the
rods' "red toppled first" at 93% to 96%. A true share of 95% clears 90% on 200 seeds
about 70% of the time (`chance_to_hold`), on 1,000 seeds 99.999%. Measured (2026-12-05,
roots 0 to 8 and 9003): at 200 seeds, one of the actor-critic's points was unclear on
root 9003 and the rods' "red toppled first" was unclear at 0 to 12 of its 20 points; at
1,000 seeds both held at every point on each of the ten roots, and every claim of
`CHAPTER_CLAIMS` held on each. The three maps cost about 20 CPU-seconds. A single point
whose share lies near its threshold stays unsure on any number of seeds (the
goal-oriented learner's "interest moves to green later" at the lowest weights, about
55% against 50%): the chapter quotes its share and verdict and claims only what holds
with room to spare."""


def seeds_needed(n_seeds, threshold=CLAIM_SHARE):
    """The fewest of `n_seeds` seeds in which a claim must hold for it to *hold* at a
    point: the whole 95% interval of its share at or above `threshold`
    (`icm.stats.share_interval`); None if not even all of them do.

    Args:
      n_seeds: seeds at the point (integer >= 1).
      threshold: the share the claim needs, in (0, 1).
    """
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    threshold = _validate.real("threshold", threshold, 0.0, 1.0, low_open=True,
                               high_open=True)
    for held in range(n_seeds + 1):
        if share_interval(held, n_seeds)[0] >= threshold:
            return held
    return None


def chance_to_hold(share, n_seeds, threshold=CLAIM_SHARE):
    """The chance that a claim whose true share of seeds is `share` *holds* at a point
    measured on `n_seeds` fresh seeds: that at least `seeds_needed(n_seeds, threshold)`
    of them show it (a binomial tail, scipy.stats.binom).

    Args:
      share: the true share, in [0, 1].
      n_seeds: seeds at the point (integer >= 1).
      threshold: the share the claim needs, in (0, 1).
    """
    from scipy.stats import binom

    share = _validate.real("share", share, 0.0, 1.0)
    needed = seeds_needed(n_seeds, threshold)
    if needed is None:
        return 0.0
    return float(binom.sf(needed - 1, n_seeds, share))


def studies_table(studies=None):
    """A Markdown table of the claims the maps count: for each learner (with the paper's
    figure), each claim, when it holds in one run, and the share its seeds' whole 95%
    interval must clear (a threshold on a share, not a number of runs).

    Args:
      studies: names or `Study` objects (default all of `STUDIES`).
    """
    studies = [check_study(s) for s in (STUDIES if studies is None else studies)]
    lines = ["| learner | claim | holds in one run when "
             f"| threshold for the whole {LEVEL:.0%} interval of the share |",
             "|---|---|---|---|"]
    for study in studies:
        for i, claim in enumerate(study.claims):
            learner = study.title if i == 0 else ""
            lines.append(f"| {learner} | {claim.text} | {claim.meaning} | "
                         f"≥ {claim.threshold:.0%} |")
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
                lines.append(f"| {result.study.short} | {setting.label} "
                             f"({show_value(setting.default)}) | {tried} | {claim.text} "
                             f"(≥ {claim.threshold:.0%}) | {where} |")
    return "\n".join(lines)


def interaction_table(results):
    """A Markdown table: for each learner, claim and pair of settings, the strongest
    interaction on the pair's map (see `RobustnessResult.interaction`), in percentage
    points of share, with its band, where it is (the pair's two settings and their
    values) and whether the pair interacts.

    Args:
      results: a list of `RobustnessResult` objects.

    Returns:
      A Markdown string.
    """
    _check_results(results)

    def points(share):
        shown = round(100 * share)
        return f"{shown:+d}" if shown else "0"

    lines = ["| learner | claim | contrast, points (band) | where | interact? |",
             "|---|---|---|---|---|"]
    for result in results:
        for claim in result.study.claims:
            for pair in result.study.pairs():
                contrast, low, high, va, vb = result.strongest_interaction(claim.name, pair)
                lines.append(
                    f"| {result.study.short} | {claim.text} | {points(contrast)} "
                    f"({points(low)} to {points(high)}) | `{pair[0]}` = {show_value(va)}, "
                    f"`{pair[1]}` = {show_value(vb)} "
                    f"| {'yes' if result.interacts(claim.name, pair) else 'no'} |")
    return "\n".join(lines)


def _check_results(results):
    if not isinstance(results, (list, tuple)) or not results:
        raise _validate.ArgumentTypeError(f"results must be a non-empty list of "
                                          f"RobustnessResult, got {_validate.show(results)}")
    for i, result in enumerate(results):
        _validate.instance(f"results[{i}]", result, RobustnessResult)
    return results


CHAPTER_CLAIMS = {
    "weight_threshold": "red first fails at each action weight up to some weight and holds "
                        "at each weight above it",
    "weight_above_settles_red": "above that weight red comes first at every point of the "
                                "map, whatever the presses and the reading",
    "interest_needs_progress": "interest moves to green later with the progress reading "
                               "and fails with the literal one",
    "interest_weight_from": "interest moves to green later at each action weight from the "
                            "highest at which red first fails on",
    "interest_progress_any_presses": "with the progress reading and a weight above the "
                                     "highest at which red first fails, interest moves "
                                     "later for every number of presses",
    "green_needs_two_presses": "green is mastered at every point but those with the fewest "
                               "presses per trial, where it fails",
    "critic_red_everywhere": "the actor-critic predicts red well first at every point",
    "printed_td_alone": "with only the TD error changed to the printed one, the "
                        "actor-critic predicts red well first and green well too",
    "printed_td_damage": "with the printed TD error, green fails with the weakest predictor "
                         "and with the fewest presses, where the standard one does not fail",
    "td_interacts": "the TD error interacts with the action weight and with the presses "
                    "for green",
    "rods_toppled_first_everywhere": "red toppled first holds at every point of the map",
    "rods_small_initial_q": "red is predicted well first only for initial values between "
                            "the smallest and the largest tried",
    "rods_epsilon": "red predicted well first holds at an epsilon other than the default, "
                    "and its share is lowest at the largest epsilon tried",
    "rods_blue_needs_drive": "blue is found at every point with an initial Q above zero, "
                             "whatever epsilon, and fails with no initial Q and no random "
                             "moves (the chapter gives the other epsilons at no initial Q "
                             "by their shares and verdicts, not as a claim)",
    "presses_not_needed": "red first and the interest's order hold at every number of "
                          "presses tried",
    "rods_epsilon_up_to_default": "the Q-learner predicts red well first at each epsilon "
                                  "from 0 to its default",
}
"""The claims of the chapter "What the result depends on" about its maps
(`chapter_claims`)."""


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
    critic_weights = critic.study.setting("action_weight").values
    critic_presses = critic.study.setting("presses_per_trial").values
    qs = list(rods_result.study.setting("initial_q").values)
    epsilons = rods_result.study.setting("epsilon").values
    q_held = rods_result.holding_values("red_first", "initial_q")
    epsilon_held = rods_result.holding_values("red_first", "epsilon")
    epsilon_shares = [rods_result.share("red_first", epsilon=e)[0] for e in epsilons]
    default_epsilon = rods_result.study.setting("epsilon").default
    return {
        "weight_threshold": threshold is not None and bool(below) and all(
            goal.verdict("red_first", action_weight=w) == "fails" for w in below),
        "weight_above_settles_red": threshold is not None and _every(
            goal, "red_first", "holds", action_weight=lambda w: w >= threshold),
        "interest_needs_progress": goal.verdict("interest_later") == "holds"
        and goal.verdict("interest_later", reading="literal") == "fails",
        "interest_weight_from": bool(below) and all(
            goal.verdict("interest_later", action_weight=w) == "holds"
            for w in weights if w >= below[-1]),
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
        "rods_toppled_first_everywhere": _every(rods_result, "red_toppled_first", "holds"),
        "rods_small_initial_q": bool(q_held) and q_held[0] != qs[0]
        and q_held[-1] != qs[-1]
        and q_held == qs[qs.index(q_held[0]):qs.index(q_held[-1]) + 1],
        "rods_epsilon": any(e != default_epsilon for e in epsilon_held)
        and epsilon_shares[-1] < min(epsilon_shares[:-1]),
        "rods_blue_needs_drive": _every(rods_result, "blue_found", "holds",
                                        initial_q=lambda q: q > 0)
        and rods_result.verdict("blue_found", initial_q=qs[0], epsilon=epsilons[0])
        == "fails" and qs[0] == 0 and epsilons[0] == 0,
        "presses_not_needed": all(goal.verdict(c, presses_per_trial=p) == "holds"
                                  for c in ("red_first", "interest_later") for p in presses),
        "rods_epsilon_up_to_default": epsilons[0] == 0 and all(
            e in epsilon_held for e in epsilons if e <= default_epsilon),
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
    tie = max(w for w in weight.values if w < threshold)
    progress_above = above.query("reading == 'progress'")
    numbers.update(
        default_weight=weight.default, goal_lowest_weight=threshold,
        goal_highest_failing_weight=tie,
        goal_red_first_at_tie=goal.share("red_first", action_weight=tie)[0],
        goal_red_first_above_min=float(above.red_first.min()),
        goal_later_progress_min=float(progress_above.interest_later.min()),
        goal_later_progress_min_presses=int(progress_above.sort_values(
            "interest_later", kind="stable").iloc[0].presses_per_trial),
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
    clauses["goal_red_first_by_weight"] = shares_along(goal, "red_first", "action_weight")
    clauses["goal_later_by_weight"] = shares_along(goal, "interest_later", "action_weight")
    # The actor-critic.
    weakest = critic.study.setting("action_weight").values[0]
    fewest = critic.study.setting("presses_per_trial").values[0]
    printed_held = [w for w in critic.study.setting("action_weight").values
                    if critic.verdict("green_learned", variant="printed_td", action_weight=w)
                    == "holds"]
    numbers.update(critic_weakest=weakest, critic_fewest=fewest,
                   critic_printed_green_from=min(printed_held) if printed_held else None)
    clauses["critic_red_first_weakest"] = weakest_point(critic, "red_first")
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
        well_error=WELL_PREDICTED_ERROR,
        rods_q_lowest=min(held), rods_q_highest=max(held), rods_q_none=qs[0],
        rods_q_too_large=min(q for q in qs if q > max(held)),
        rods_blue_none=rods_result.share("blue_found", initial_q=qs[0],
                                         epsilon=epsilon.values[0])[0],
        rods_epsilon_largest_share=rods_result.share("red_first",
                                                     epsilon=epsilon.values[-1])[0],
        rods_epsilon_default=epsilon.default, rods_epsilon_largest=epsilon.values[-1],
        rods_epsilon_lowest=epsilon.values[0],
        rods_epsilon_largest_verdict=rods_result.verdict("red_first",
                                                         epsilon=epsilon.values[-1]),
        rods_blue_positive_q_min=float(rods_result.points().query("initial_q > 0")
                                       .blue_found.min()))
    clauses.update(
        rods_red_first_by_q=shares_along(rods_result, "red_first", "initial_q"),
        rods_red_first_by_epsilon=shares_along(rods_result, "red_first", "epsilon"),
        rods_blue_q_none_by_epsilon=shares_along(rods_result, "blue_found", "epsilon",
                                                             initial_q=qs[0]))
    clauses["rods_toppled_first_points"] = verdict_counts(rods_result, "red_toppled_first")
    lowest = rods_result.points().sort_values("red_toppled_first", kind="stable").iloc[0]
    clauses["rods_toppled_first_weakest"] = (
        f"{weakest_point(rods_result, 'red_toppled_first')}: {lowest.red_toppled_first:.1%} "
        f"of the seeds ({lowest.red_toppled_first_low:.1%} to "
        f"{lowest.red_toppled_first_high:.1%}; {lowest.red_toppled_first_verdict})")
    # The fewest seeds at a set of points, in words: the lowest lower end of their 95%
    # intervals ("in at least 97.2% of the seeds"), the share the data vouch for at each
    # point (a sample's 100% is not "every seed").
    points = {"goal": goal.points(), "critic": critic.points(),
              "rods": rods_result.points()}
    for name, table, claim in (
            ("goal_red_first_above_in", points["goal"].query("action_weight >= @threshold"),
             "red_first"),
            ("critic_red_first_in", points["critic"], "red_first"),
            ("rods_red_toppled_first_in", points["rods"], "red_toppled_first"),
            ("rods_blue_positive_q_in", points["rods"].query("initial_q > 0"), "blue_found")):
        clauses[name] = in_seeds(float(table[claim + "_low"].min()))
    return numbers, clauses


def shares_along(result, claim, setting, **point):
    """In words, the share of seeds in which `claim` held in `result` (a
    `RobustnessResult`) at each value of `setting` (the other settings at `point`, or at
    their defaults), e.g. "51% at 1, 49% at 1.5, 97% at 3": a clause for the chapter
    (Markdown)."""
    setting = result.study.setting(setting)
    return ", ".join(f"{result.share(claim, **{**point, setting.name: v})[0]:.1%} at "
                     f"{show_value(v)}" for v in setting.values)


def weakest_point(result, claim):
    """In words, the point of a map where `claim` held in the fewest seeds, e.g.
    "action_weight = 10, presses_per_trial = 1, variant = printed_td"."""
    points = result.points()
    lowest = points.loc[points[result.study.claim(claim).name].idxmin()]
    return ", ".join(f"{s.name} = {show_value(lowest[s.name])}" for s in result.study.settings)


def verdict_counts(result, claim):
    """In words, at how many of a map's points `claim` holds, is unclear and fails, e.g.
    "it holds at 14 of the 20 points, is unclear at 6 and fails at none"."""
    verdicts = result.points()[result.study.claim(claim).name + "_verdict"]
    counts = {v: int((verdicts == v).sum()) for v in ("holds", "unclear", "fails")}
    return (f"it holds at {counts['holds']} of the {len(verdicts)} points, is unclear at "
            f"{counts['unclear'] or 'none'} and fails at {counts['fails'] or 'none'}")


def run_replication(progress=False):
    """The chapter's claims (`chapter_claims`) rechecked on its three maps run again on a
    root seed that no study, chapter or other test uses
    (`icm.experiments.seeding.REPLICATION_ROOTS["robustness"]`), with as many seeds
    at every point as the chapter's maps (`MAP_SEEDS`).

    Returns:
      {"root", "n_seeds": {study: seeds at every point}, "claims": {name: whether it
      held again}, "critic_lowest": the actor-critic's lowest share of red predicted
      well first over its map, with its interval, verdict and point (the point behind
      the chapter's bold "every point" claim of the actor-critic), "rods_toppled_first":
      {verdict: points} of "red toppled first" on the rods' map (the chapter says it
      holds at every point)}.
    """
    from icm.studies import robustness
    from icm.experiments.seeding import REPLICATION_ROOTS

    root = REPLICATION_ROOTS["robustness"]
    maps = {name: robustness.run_robustness(name, n_seeds=MAP_SEEDS[name], seed=root,
                                            progress=progress)
            for name in ("goal_oriented", "actor_critic", "rod_toppling")}
    claims = chapter_claims(maps["goal_oriented"], maps["actor_critic"],
                            maps["rod_toppling"])
    points = maps["actor_critic"].points()
    lowest = points.loc[points["red_first"].idxmin()]
    settings = [s.name for s in maps["actor_critic"].study.settings]
    toppled = maps["rod_toppling"].points()["red_toppled_first_verdict"]
    return {"root": root, "n_seeds": dict(MAP_SEEDS),
            "claims": {name: bool(held) for name, held in claims.items()},
            "critic_lowest": {"share": float(lowest["red_first"]),
                              "low": float(lowest["red_first_low"]),
                              "high": float(lowest["red_first_high"]),
                              "verdict": str(lowest["red_first_verdict"]),
                              "point": {name: show_value(lowest[name])
                                        for name in settings}},
            "rods_toppled_first": {v: int((toppled == v).sum())
                                   for v in ("holds", "unclear", "fails")}}


def replication_sentences(stored):
    """What the chapter says of its replication (`run_replication`, as
    assets/replications.json keeps it under "robustness"): {"summary": how many of the
    chapter's findings held again and which did not, "critic_everywhere": the sentence
    beside the bold claim that red is predicted well first at every point of the
    actor-critic's map, "rods_toppled": the sentence beside the bold claim that red
    toppled first holds at every point of the rods' map (how many of its points held,
    were unclear or failed where it did not replicate)}."""
    claims = stored["claims"]
    failed = [CHAPTER_CLAIMS[name] for name, held in claims.items() if not held]
    summary = (f"On a fresh root seed ({stored['root']}, with as many seeds at each point "
               f"as here), {len(claims) - len(failed)} of the chapter's {len(claims)} "
               f"findings about its maps held again")
    summary += (": all of them." if not failed else
                "; not replicated: " + "; ".join(f'"{f}"' for f in failed) + ".")
    low = stored["critic_lowest"]
    where = ", ".join(f"{name} = {value}" for name, value in low["point"].items())
    seeds = stored["n_seeds"]["actor_critic"]
    if claims["critic_red_everywhere"]:
        critic = (f"On a fresh root seed ({stored['root']}, {seeds:,} seeds at each point) "
                  f"it held again, its weakest share seen there {low['share']:.1%} (its "
                  f"interval {low['low']:.1%} to {low['high']:.1%}).")
    else:
        critic = (f"Not replicated on a fresh root seed ({stored['root']}, {seeds:,} seeds "
                  f"at each point): there, at {where}, red was predicted well first in "
                  f"{low['share']:.1%} of the seeds ({low['low']:.1%} to {low['high']:.1%}; "
                  f"verdict: {low['verdict']}, not holds). A claim about all the points of "
                  f"a map is as weak as its weakest point.")
    counts = stored["rods_toppled_first"]
    points = sum(counts.values())
    seeds = stored["n_seeds"]["rod_toppling"]
    if claims["rods_toppled_first_everywhere"]:
        rods = (f"On a fresh root seed ({stored['root']}, {seeds:,} seeds at each point) it "
                f"held again, at each of the {points} points.")
    else:
        rods = (f"Not replicated on a fresh root seed ({stored['root']}, {seeds:,} seeds at "
                f"each point): there it holds at {counts['holds']} of the {points} points, "
                f"is unclear at {counts['unclear'] or 'none'} and fails at "
                f"{counts['fails'] or 'none'}.")
    return {"summary": summary, "critic_everywhere": critic, "rods_toppled": rods}
