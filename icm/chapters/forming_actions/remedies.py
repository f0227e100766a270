"""The chapter "Forming actions" (book/forming_actions.ipynb), its second half "Growing
up, and being shown": the summaries, Markdown tables, verdicts and sentences its text
quotes about the two remedies, read from the runs of `icm.studies.forming_actions.remedies`
(kept in assets/remedies_study.json and assets/remedies_test_error.json); its paired
comparisons are decided with the chapter's whole family
(`icm.chapters.forming_actions.family`).
"""

import numpy as np

from icm import _validate
from icm.chapters import replication
from icm.chapters import verdicts as paired
from icm.chapters.forming_actions.family import (REMEDY_KEYS, VERDICT_ROOTS,
                                                 chapter_verdicts, remedy_comparisons)
from icm.chapters.words import percent
from icm.envs import buttons
from icm.experiments import babbling_results
from icm.studies.forming_actions.remedies import (TEACHING, check_study, load_study,
                                            load_test_error_split, pooled, seed_values,
                                            shown_buttons)
from icm.stats import PANEL_RESAMPLES, at_bound, bootstrap_band, share_interval


def summary(study=None, roots=None):
    """Per condition, over the seeds of `roots` (default all): a dict {label: {...}}
    with "n_seeds", "all_pressed_share" (seeds with all five presses formed at the
    default budget), "buttons_pressed" (mean formed, of 5), "others_pressed" (mean
    formed among the buttons not shown, of as many), "test_error" (m), "red_first_share",
    "as_scripted", "self_pressed" [button] (share of seeds whose own rollouts pressed
    each button), "median_first_press" [button] (median rollout of the robot's first
    own press, the seeds that never pressed counted as never: None when more than
    half never did), and "maturity_full" (share of seeds whose clock reached 1)."""
    study = load_study() if study is None else check_study(study)
    out = {}
    for label in study["runs"]:
        entry = pooled(study, label, roots)
        pressed = entry["pressed"][:, -1]  # [seed, button] at the default budget
        others = [b for b in range(buttons.N_BUTTONS) if b not in shown_buttons(label)]
        first = entry["first_press"]
        median = babbling_results.median_first_press(first, study["n_rollouts"])
        out[label] = {
            "n_seeds": len(pressed),
            "all_pressed_share": float(pressed.all(axis=1).mean()),
            "buttons_pressed": float(pressed.sum(axis=1).mean()),
            "others_pressed": float(pressed[:, others].sum(axis=1).mean()) if others else None,
            "test_error": float(entry["test_error"].mean()),
            "red_first_share": float(entry["red_first"].mean()),
            "as_scripted": float(entry["as_scripted"].mean()),
            "self_pressed": (first > 0).mean(axis=0).tolist(),
            "median_first_press": [None if np.isnan(m) else float(m) for m in median],
            "maturity_full": float((entry["maturity"][:, -1] >= 1.0).mean())}
    return out


def comparison_table(study=None, roots=None):
    """A Markdown table of `summary`'s outcomes: one row per condition, with its seeds,
    the share with all five presses formed, the presses formed (of all five, and of
    the buttons its teacher did not show), the test error and the share with red
    mastered first. `first_press_table` gives the first presses: two tables, each
    narrow enough for a book page.

    Args:
      study: the study (default `load_study()`).
      roots: the root seeds pooled (default all).
    """
    lines = ["| condition | seeds | all five formed | presses formed (of 5) "
             "| of the buttons not shown | test error, cm | red mastered first |",
             "|---|---|---|---|---|---|---|"]
    for label, row in summary(study, roots).items():
        shown = shown_buttons(label)
        others = ("none left" if row["others_pressed"] is None else
                  f"{row['others_pressed']:.2f} of {buttons.N_BUTTONS - len(shown)}")
        lines.append(f"| {label} | {row['n_seeds']} | {percent(row['all_pressed_share'])} "
                     f"| {row['buttons_pressed']:.2f} | {others} "
                     f"| {100 * row['test_error']:.2f} | {percent(row['red_first_share'])} |")
    return "\n".join(lines)


def first_press_table(study=None, roots=None):
    """A Markdown table of `summary`'s first presses: one row per condition, and per
    button the median over the seeds of the rollout of the robot's own first press
    ("never" where more than half the seeds never pressed it; "shown" marks a button
    the condition's teacher showed).

    Args:
      study: the study (default `load_study()`).
      roots: the root seeds pooled (default all).
    """
    header = " | ".join(f"button {b}" for b in range(buttons.N_BUTTONS))
    lines = [f"| condition | {header} |", "|---|" + "---|" * buttons.N_BUTTONS]
    for label, row in summary(study, roots).items():
        shown = shown_buttons(label)
        firsts = " | ".join(("never" if m is None else f"{m:.0f}")
                            + (" (shown)" if b in shown else "")
                            for b, m in enumerate(row["median_first_press"]))
        lines.append(f"| {label} | {firsts} |")
    return "\n".join(lines)


def paired_difference(study, label, baseline, measure, roots=None):
    """The difference between two conditions, seed by seed (they run on the same
    seeds), in one of `PAIRED_MEASURES` (the buttons not shown: those of `label`, in
    both), with its 95% bootstrap band: (mean, low, high).

    Args:
      study: the study.
      label, baseline: two conditions of the study.
      measure: one of `PAIRED_MEASURES`.
      roots: the root seeds pooled (default all).
    """
    return paired.band(paired.differences(seed_values(study, label, measure, label, roots),
                                          seed_values(study, baseline, measure, label, roots)),
                       PANEL_RESAMPLES)


def _bounds(label, measure):
    """The (lowest, highest) values a seed can take in `measure` for condition `label`'s
    comparison, or None for the test error (no bound reached in practice)."""
    if measure == "all_pressed":
        return 0.0, 1.0
    if measure.startswith("others"):
        return 0.0, float(buttons.N_BUTTONS - len(shown_buttons(label)))
    return None


def verdicts(study=None, babbling=None, replications=None):
    """The numbers and words the chapter's comparisons of the remedies are phrased from,
    over the held-out seeds (`VERDICT_ROOTS`): for each remedy (`REMEDY_KEYS`) against
    learning progress alone, seed by seed, the difference in each of `PAIRED_MEASURES`
    with its 95% bootstrap band ("{key}_{measure}", "..._low", "..._high"), its raw
    and Holm-corrected p-values ("..._p", "..._p_holm", `chapter_verdicts`) and its
    words ("..._verdict", `icm.chapters.verdicts.phrase`: "clearly better", "clearly
    worse" or "no clear difference", clear only when Holm says so, the arm at the
    ceiling or floor named, and whether the stored replication (`replications`,
    default `replication.load_replications()`) held a clear verdict, with its seeds
    and power). Also "n_family" (the comparisons corrected together) and
    "n_verdict_seeds". A dict {name: value}."""
    study = load_study() if study is None else check_study(study)
    corrected = chapter_verdicts(study, babbling)
    if replications is None:
        replications = replication.load_replications().get("forming_actions", {})
    stored = replications.get("verdicts", {})
    out = {"n_family": len(corrected)}
    for name, c in remedy_comparisons(study).items():
        differences = paired.differences(c["arm"], c["baseline"])
        mean, low, high = paired.band(differences, PANEL_RESAMPLES)
        out[name], out[f"{name}_low"], out[f"{name}_high"] = mean, low, high
        out[f"{name}_p"], out[f"{name}_p_holm"] = (corrected[name]["p"],
                                                   corrected[name]["p_holm"])
        bounds = _bounds(c["label"], c["measure"])
        bound = None
        if bounds is not None:
            at = {who: at_bound(values, *bounds) for who, values in
                  (("learning progress", c["baseline"]), (c["label"], c["arm"]))}
            bound = "; ".join(f"{who} at the {where}" for who, where in at.items() if where)
        kept = stored.get(name)
        lower, higher = (("better", "worse") if c["measure"] == "test_error"
                         else ("worse", "better"))
        out[f"{name}_verdict"] = paired.phrase(
            mean, corrected[name]["clear"], lower, higher, bound=bound,
            replication=None if kept is None else paired.replication_words(
                {"n_seeds": replications["n_seeds"], **kept}))
        out["n_verdict_seeds"] = len(differences)
    return out


def teacher_test_error(split=None):
    """How much of the teacher's lower test error is the robot's own: for each condition
    of `TEACHING` against learning progress alone, seed by seed over the roots of
    `split` (default `load_test_error_split()`), the difference in each of "all",
    "own" and "own_grid" (`test_error_split`) with its 95% bootstrap band:
    {"{key}_{part}": (mean, low, high)} in m (keys of `REMEDY_KEYS`)."""
    split = load_test_error_split() if split is None else split
    runs = split["runs"]
    pooled = lambda label, part: np.concatenate([runs[label][r][part]
                                                 for r in runs["learning progress"]])
    out = {}
    for label in TEACHING:
        for part in ("all", "own", "own_grid"):
            differences = pooled(label, part) - pooled("learning progress", part)
            mean, low, high = bootstrap_band(differences[:, None], resamples=PANEL_RESAMPLES)
            out[f"{REMEDY_KEYS[label]}_{part}"] = (float(mean[0]), float(low[0]),
                                                   float(high[0]))
    return out


def teacher_test_error_table(split=None):
    """A Markdown table of `teacher_test_error`: one row per condition of `TEACHING`, the
    difference in test error from learning progress alone (cm, with its 95% band) with
    the demonstrations, without them, and without them on the goals that are not press
    goals."""
    rows = teacher_test_error(split)
    cell = lambda band: f"{100 * band[0]:+.2f} ({100 * band[1]:+.2f} to {100 * band[2]:+.2f})"
    lines = ["| condition | with the demonstrations | without them "
             "| without them, goals not presses |", "|---|---|---|---|"]
    for label in TEACHING:
        key = REMEDY_KEYS[label]
        lines.append(f"| {label} | {cell(rows[key + '_all'])} | {cell(rows[key + '_own'])} "
                     f"| {cell(rows[key + '_own_grid'])} |")
    return "\n".join(lines)


def first_press_comparison(study, label, baseline="learning progress", roots=None):
    """A sentence comparing, button by button, when the robot first pressed each button
    itself in condition `label` and in `baseline` (medians over the seeds of `roots`,
    default every seed of the study, as in `summary`), e.g. "button 0 at rollout 132
    (153 with learning progress alone), ...". The buttons the teacher shows in `label`
    are left out."""
    rows = summary(study, roots)
    label = _validate.one_of("label", label, tuple(rows))
    baseline = _validate.one_of("baseline", baseline, tuple(rows))
    shown = shown_buttons(label)
    word = lambda m: "never (median)" if m is None else f"rollout {m:.0f}"
    parts = [f"button {b} at {word(rows[label]['median_first_press'][b])} "
             f"({word(rows[baseline]['median_first_press'][b])} with {baseline} alone)"
             for b in range(buttons.N_BUTTONS) if b not in shown]
    return ", ".join(parts)


def shown_first_presses(study=None, baseline="learning progress", roots=None):
    """For each button a teacher shows in a condition of the study: when the robot first
    pressed it itself (the median over the seeds of `roots`, default all, as in
    `summary`), against `baseline`. A list of dicts {"label", "button", "median",
    "baseline"} (a median None when more than half the seeds never pressed it), in
    the order of `TEACHING` and of the buttons shown."""
    rows = summary(study, roots)
    baseline = _validate.one_of("baseline", baseline, tuple(rows))
    return [{"label": label, "button": b, "median": rows[label]["median_first_press"][b],
             "baseline": rows[baseline]["median_first_press"][b]}
            for label in TEACHING if label in rows for b in shown_buttons(label)]


def seeds_words(study=None, roots=None):
    """Which seeds a number is over, in words: "all 80 seeds" (`roots` None), "the 40
    held-out seeds" (`VERDICT_ROOTS`), or "the 40 seeds of roots 100, 200"."""
    study = load_study() if study is None else check_study(study)
    label = next(iter(study["runs"]))
    n = len(pooled(study, label, roots)["test_error"])
    if roots is None:
        return f"all {n} seeds"
    if [str(r) for r in roots] == [str(r) for r in VERDICT_ROOTS]:
        return f"the {n} held-out seeds"
    return f"the {n} seeds of roots {', '.join(map(str, roots))}"


def shown_sooner_sentence(study=None, roots=None):
    """A sentence saying whether, with a teacher, the robot first pressed each shown
    button itself sooner than learning progress alone (`shown_first_presses`, medians
    over the seeds of `roots`, default all, which the sentence names): "sooner ... in
    all 8 cases", or the cases where it was not. A comparison of medians, not tested:
    the sentence says so."""
    cases = shown_first_presses(study, roots=roots)
    never = float("inf")
    late = [c for c in cases if (never if c["median"] is None else c["median"])
            >= (never if c["baseline"] is None else c["baseline"])]
    seeds = "medians over " + seeds_words(study, roots)
    if not late:
        return (f"sooner than learning progress alone in all {len(cases)} cases (each "
                f"button shown, in each condition with a teacher; {seeds}, not tested)")
    word = lambda m: "never" if m is None else f"at rollout {m:.0f}"
    return ("not sooner in " + "; ".join(
        f"{c['label']}, button {c['button']} ({word(c['median'])}, against "
        f"{word(c['baseline'])})" for c in late) + f", of {len(cases)} cases ({seeds})")


def red_first_share(study=None, label="learning progress"):
    """In how many of condition `label`'s seeds (every root of the study, default
    `load_study()`) the paper's learner, run on the presses the robot formed, mastered
    red first, with the share's 95% Wilson interval: {"k", "n", "share", "low",
    "high"}. A share of seeds is a sample: what it says of the learner is its
    interval's lower bound ("in at least 91% of seeds"), not the sample's share."""
    study = load_study() if study is None else check_study(study)
    red_first = pooled(study, label)["red_first"]
    k, n = int(red_first.sum()), len(red_first)
    low, high = share_interval(k, n)
    return {"k": k, "n": n, "share": k / n, "low": low, "high": high}
