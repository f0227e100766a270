"""The chapter "Forming actions" (book/forming_actions.ipynb), its first half: the three
strategies and the variants of the goal-babbling learner, read from the longer runs of
`icm.studies.forming_actions.strategies` (assets/goal_babbling_study.json): its table of
variants (`study_table`), what became of the presses a variant formed
(`failures_table`), its targets (`TARGETS`) and the numbers and words its comparisons
are phrased from (`verdicts`; the comparisons themselves are decided with the
chapter's whole family, `icm.chapters.forming_actions.family`).
"""

import numpy as np

from icm import _validate
from icm.chapters import verdicts as paired
from icm.chapters.forming_actions import family
from icm.chapters.words import percent
from icm.experiments import formed_actions
from icm.experiments.babbling_results import GoalBabblingResult
from icm.experiments.results import check_results
from icm.studies.forming_actions.arms import HELD_OUT_ROOTS, TUNING_ROOTS
from icm.studies.forming_actions.strategies import load_study, pool, summary, tuning
from icm.stats import PANEL_RESAMPLES


def study_table(study=None):
    """A Markdown table of `summary`: one row per variant on the tuning root seeds,
    then the held-out rows.

    Args:
      study: the study (default `load_study()`).
    """
    rows = summary(study)
    lines = ["| variant | root seeds | seeds | all five presses formed | presses formed (of 5) "
             "| test error, cm (in its outcome space) | red mastered first "
             "| presses with the scripted effect |",
             "|---|---|---|---|---|---|---|---|"]
    for group, roots in (("tuning", TUNING_ROOTS), ("held_out", HELD_OUT_ROOTS)):
        for label, by_group in rows.items():
            if group not in by_group:
                continue
            row = by_group[group]
            loop = (f"{percent(row['red_first_share'])} | {percent(row['as_scripted'], 1)}"
                    if "red_first_share" in row else "not run | not run")
            lines.append(f"| {label} | {', '.join(map(str, roots))} | {row['n_seeds']} "
                         f"| {percent(row['all_pressed_share'])} | {row['buttons_pressed']:.2f} "
                         f"| {100 * row['test_error']:.2f} | {loop} |")
    return "\n".join(lines)


def failures_table(study, label):
    """A Markdown table of what became of the press formed for each button (rows:
    `formed_actions.PRESS_FAILURES`, columns: buttons), over the tuning seeds of
    variant `label`."""
    label = _validate.one_of("label", label, tuple(study["runs"]))
    codes = np.array(tuning(study, label)["failures"])  # [seed, button]
    n_buttons = codes.shape[1]
    lines = ["| the press formed for the button | " + " | ".join(
        f"button {b}" for b in range(n_buttons)) + " | all |",
             "|---|" + "---|" * (n_buttons + 1)]
    for i, name in enumerate(formed_actions.PRESS_FAILURES):
        counts = (codes == i).sum(axis=0)
        lines.append(f"| {name} | " + " | ".join(str(c) for c in counts)
                     + f" | {counts.sum()} |")
    return "\n".join(lines)


TARGETS = {"all_pressed_share": 0.9, "red_first_share": 0.9, "as_scripted": 0.95}
"""The chapter's targets: all five presses formed in at least 90% of the seeds, red
mastered first in at least 90% with the formed presses, and at least 95% of their
presses with the scripted press's effect."""


OPTIONS = ("LWLR inverse model", "competence progress", "splitting regions")
"""The options from the field that the study compares with the default learner."""


def _join(labels):
    return labels[0] if len(labels) == 1 else ", ".join(labels[:-1]) + " and " + labels[-1]


def verdicts(study=None, corrected=None):
    """The numbers and words the chapter's comparisons are phrased from, a dict: for
    learning progress ("lp") and random goal babbling ("rg") on the held-out seeds,
    the share with all five presses formed, their paired difference with its 95%
    bootstrap band, a sentence saying whether the margin is clear in the chapter's
    family (`corrected`: `family.chapter_verdicts()`, computed when None), the same for
    their test errors (`icm.chapters.verdicts.phrase`), the closing-the-loop shares,
    sentences saying whether the `OPTIONS` and the simulated return home did better
    than the default learner and whether, on the held-out seeds, its share was still
    rising between the last two budgets, and "met" or "not met" for each of
    `TARGETS`."""
    study = load_study() if study is None else study
    if corrected is None:
        corrected = family.chapter_verdicts(babbling=study)
    lp, rg = (pool(list(study["runs"][label].values()))
              for label in ("learning progress", "random goal babbling"))
    held_lp, held_rg = (pool([study["runs"][label][str(r)] for r in HELD_OUT_ROOTS])
                        for label in ("learning progress", "random goal babbling"))
    differences = family.strategy_comparisons(study)
    mean, low, high = paired.band(differences["lp_rg_all_pressed"], PANEL_RESAMPLES)
    n_family = corrected["lp_rg_all_pressed"]["n_family"]
    margin = paired.phrase(
        mean, corrected["lp_rg_all_pressed"]["clear"],
        lower="random goal babbling does clearly better than learning progress",
        higher="the margin of learning progress over random goal babbling is clear",
        unclear="no clear difference between the two strategies", clearly=False)
    error = differences["lp_rg_test_error"]
    error_verdict = paired.phrase(error.mean(), corrected["lp_rg_test_error"]["clear"],
                                  "lower with learning progress",
                                  "lower with random goal babbling")
    rows = summary(study)["learning progress"]
    red_first = float(np.mean(lp["red_first"]))
    as_scripted = float(np.mean(lp["as_scripted"]))
    word = lambda value, target: "met" if value >= target else "not met"
    rows_all = summary(study)
    share = lambda label: rows_all[label]["tuning"]["all_pressed_share"]
    better = [label for label in OPTIONS
              if label in rows_all and share(label) > share("learning progress")]
    options = ("none of them formed all five presses in more of these seeds than the "
               "learner without them" if not better else
               f"{_join(better)} formed all five presses in more of these seeds than the "
               f"learner without {'it' if len(better) == 1 else 'them'}")
    compare = lambda label: ("better than" if share(label) > share("learning progress")
                             else "no better than")
    retract = (f"{compare('return home simulated')} without the return"
               if "return home simulated" in rows_all else None)
    by_budget = np.array(held_lp["pressed"]).all(axis=2).mean(axis=0)  # [budget]
    trend = ("still rising at the default budget" if by_budget[-1] > by_budget[-2]
             else "no longer rising at the default budget")
    error_mean, error_low, error_high = paired.band(error, PANEL_RESAMPLES)
    return {"n_held_seeds": len(differences["lp_rg_all_pressed"]),
            "held_difference": mean, "held_difference_low": low,
            "held_difference_high": high, "margin_verdict": margin,
            "margin_p_holm": corrected["lp_rg_all_pressed"]["p_holm"],
            "n_family": n_family,
            "held_lp_error_cm": 100 * float(np.mean(held_lp["test_error"])),
            "held_rg_error_cm": 100 * float(np.mean(held_rg["test_error"])),
            "held_error_difference_cm": 100 * error_mean,
            "held_error_difference_low_cm": 100 * error_low,
            "held_error_difference_high_cm": 100 * error_high,
            "error_verdict": error_verdict,
            "n_loop_seeds": len(lp["red_first"]), "loop_red_first": red_first,
            "loop_as_scripted": as_scripted,
            "options_verdict": options, "retract_verdict": retract,
            "held_out_trend": trend,
            "target_presses_tuning": word(rows["tuning"]["all_pressed_share"],
                                          TARGETS["all_pressed_share"]),
            "target_presses_held_out": word(rows["held_out"]["all_pressed_share"],
                                            TARGETS["all_pressed_share"]),
            "target_red_first": word(red_first, TARGETS["red_first_share"]),
            "target_as_scripted": word(as_scripted, TARGETS["as_scripted"])}


def strategy_table(results):
    """A Markdown table of the three strategies' numbers, one row per run.

    Args:
      results: a dict {row label: GoalBabblingResult}.
    """
    check_results("results", results, GoalBabblingResult)
    lines = ["| strategy | seeds | rollouts | test error at the end, cm (95% band) "
             "| buttons pressed (of 5) | seeds pressing all 5 | rollouts that pressed a button |",
             "|---|---|---|---|---|---|---|"]
    for label, result in results.items():
        s = result.summary()
        lines.append(f"| {label} | {result.n_seeds} | {result.n_rollouts} "
                     f"| {100 * s['test_error']:.1f} ({100 * s['test_error_low']:.1f} to "
                     f"{100 * s['test_error_high']:.1f}) | {s['buttons_pressed']:.1f} "
                     f"| {percent(s['all_pressed_share'])} | {percent(s['press_share'], 1)} |")
    return "\n".join(lines)
