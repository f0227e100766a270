"""The chapter "Forming actions" (book/forming_actions.ipynb), its second half "Growing
up, and being shown": the summaries, Markdown tables, paired comparisons, verdicts and
sentences its text quotes, computed from the runs of `icm.experiments.remedies_study`
(kept in assets/remedies_study.json and assets/remedies_test_error.json).
"""

import numpy as np

from icm import _validate
from icm.envs import buttons
from icm.experiments import babbling_results, remedies_study, replication
from icm.experiments.remedies_study import (REMEDY_KEYS, TEACHING, VERDICT_ROOTS,
                                            chapter_verdicts,
                                            check_study, comparisons, load_study,
                                            load_test_error_split, pooled, seed_values,
                                            shown_buttons)
from icm.experiments.results import percent
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
    a = seed_values(study, label, measure, label, roots)
    b = seed_values(study, baseline, measure, label, roots)
    mean, low, high = bootstrap_band((a - b)[:, None], resamples=PANEL_RESAMPLES)
    return float(mean[0]), float(low[0]), float(high[0])


VERDICTS = {"better": "clearly better", "worse": "clearly worse",
            "no different": "no clear difference"}
"""The words of a verdict of `verdicts`: "clearly" when the comparison is clear in the
chapter's family (`chapter_verdicts`: Holm-corrected, on `VERDICT_ROOTS`), in the
direction of its mean (for the test error, lower is better), "no clear difference"
otherwise."""


def _bounds(label, measure):
    """The (lowest, highest) values a seed can take in `measure` for condition `label`'s
    comparison, or None for the test error (no bound reached in practice)."""
    if measure == "all_pressed":
        return 0.0, 1.0
    if measure.startswith("others"):
        return 0.0, float(buttons.N_BUTTONS - len(shown_buttons(label)))
    return None


def replication_words(replication):
    """The words of a replication beside its verdict: "replicated on 40 fresh seeds
    (power 97%)", or "not replicated on 40 fresh seeds, which detect an effect of this
    size 93% of the time", from a stored replication (`replication.replicated` with
    "n_seeds" and "power", as `remedies_study.run_replications` keeps it). A
    replication kept without its power says only its seeds."""
    n, power = replication["n_seeds"], replication.get("power")
    # A simulated power of 1 is an estimate, not a certainty.
    shown = None if power is None else ("over 99%" if power > 0.99 else percent(power))
    if replication["replicated"]:
        return (f"replicated on {n} fresh seeds"
                + ("" if power is None else f" (power {shown})"))
    return (f"not replicated on {n} fresh seeds"
            + ("" if power is None else f", which detect an effect of this size "
                                        f"{shown} of the time"))


def verdict_words(mean, clear, lower_is_better=False, bound=None, replication=None):
    """The words of one verdict: `VERDICTS`' words for a clear or unclear difference of
    mean `mean`; then, when an arm sits at a bound (`bound`, e.g. "learning progress
    at the ceiling"), that in brackets; and, for a clear verdict with a stored
    replication (`replication`: {"replicated", "n_seeds", "power"}), whether it
    replicated, on how many seeds and with what power (`replication_words`)."""
    if clear and mean != 0:
        verdict = "better" if (mean < 0) == lower_is_better else "worse"
    else:
        verdict = "no different"
    words = VERDICTS[verdict] + (f" ({bound})" if bound else "")
    if verdict != "no different" and replication is not None:
        words += ", " + replication_words(replication)
    return words


def verdicts(study=None, babbling=None, replications=None):
    """The numbers and words the chapter's comparisons of the remedies are phrased from,
    over the held-out seeds (`VERDICT_ROOTS`): for each remedy (`REMEDY_KEYS`) against
    learning progress alone, seed by seed, the difference in each of `PAIRED_MEASURES`
    with its 95% bootstrap band ("{key}_{measure}", "..._low", "..._high"), its raw
    and Holm-corrected p-values ("..._p", "..._p_holm", `chapter_verdicts`) and the
    words of `verdict_words` ("..._verdict"): clear only when Holm says so, the arm at
    the ceiling or floor named, and whether the stored replication (`replications`,
    default `replication.load_replications()`) held a clear verdict, with its seeds
    and power. Also "n_family" (the comparisons corrected together) and "n_verdict_seeds".
    A dict {name: value}."""
    study = load_study() if study is None else check_study(study)
    corrected = chapter_verdicts(study, babbling)
    if replications is None:
        replications = replication.load_replications().get("forming_actions", {})
    stored = replications.get("verdicts", {})
    out = {"n_family": len(corrected)}
    for name, c in comparisons(study).items():
        differences = c["arm"] - c["baseline"]
        mean, low, high = bootstrap_band(differences[:, None], resamples=PANEL_RESAMPLES)
        out[name], out[f"{name}_low"], out[f"{name}_high"] = (float(mean[0]), float(low[0]),
                                                              float(high[0]))
        out[f"{name}_p"], out[f"{name}_p_holm"] = (corrected[name]["p"],
                                                   corrected[name]["p_holm"])
        bounds = _bounds(c["label"], c["measure"])
        bound = None
        if bounds is not None:
            at = {who: at_bound(values, *bounds) for who, values in
                  (("learning progress", c["baseline"]), (c["label"], c["arm"]))}
            bound = "; ".join(f"{who} at the {where}" for who, where in at.items() if where)
        kept = stored.get(name)
        out[f"{name}_verdict"] = verdict_words(
            float(mean[0]), corrected[name]["clear"], c["measure"] == "test_error", bound,
            None if kept is None else {"n_seeds": replications["n_seeds"], **kept})
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


MEASURE_WORDS = {"all_pressed": "all five presses formed",
                 "others_formed": "presses formed of the buttons not shown",
                 "others_pressed_early": "buttons pressed early",
                 "test_error": "test error"}
"""The measures of `remedies_study.PAIRED_MEASURES` in the words of a sentence."""


def replication_power_sentence(study=None, replications=None, simulations=500):
    """A sentence on the power of the stored replications (`replications`, default the
    chapter's entry of `replication.load_replications()`, each with its "power"): the
    lowest when every one reaches 0.9; otherwise which fall short, by how much, that
    their "not replicated" is weak evidence, and what a rerun at
    `remedies_study.POWERED_SEEDS` seeds would give (`replication_power` with
    `simulations`) and cost (`remedies_study.unit_cpu_seconds` a run)."""
    study = load_study() if study is None else check_study(study)
    if replications is None:
        replications = replication.load_replications()["forming_actions"]
    n, stored = replications["n_seeds"], replications["verdicts"]
    powers = {name: r["power"] for name, r in stored.items()}
    weak = sorted((name for name, p in powers.items() if p < 0.9), key=powers.get)
    if not weak:
        return (f"with {n} seeds, the lowest power of these replications is "
                f"{percent(min(powers.values()))}")
    found = comparisons(study)
    named = [f"{found[w]['label']} ({MEASURE_WORDS[found[w]['measure']]})" for w in weak]
    named = ", ".join(named[:-1]) + " and " + named[-1] if len(named) > 1 else named[0]
    strong = [p for name, p in powers.items() if name not in weak]
    target = remedies_study.POWERED_SEEDS
    forecast = [remedies_study.replication_power(w, study, target, simulations)
                for w in weak]
    runs = target * len(remedies_study.CLAIMED)
    cpu = runs * remedies_study.unit_cpu_seconds()
    return ((f"with {n} seeds, the other verdicts have a power of at least "
             f"{percent(min(strong))}, but " if strong else f"with {n} seeds, ")
            + f"{named} only {percent(powers[weak[0]])} to {percent(powers[weak[-1]])}: "
            f"their \"not replicated\" is weak evidence against them, not evidence that "
            f"they are absent. {target} seeds of each condition would give them a power of "
            f"{percent(min(forecast))} or more, for about {cpu:,.0f} CPU-seconds ({runs} "
            f"runs of one seed; `python -m icm study remedies-replication --seeds "
            f"{target}`); that rerun is not in this edition of the book")


STRONG_WORDS = {
    "we call a difference clear only when it survives Holm's correction":
        ("clear_is_holm", "corrected"),
    "Each clear verdict was rerun on a root seed no study uses":
        ("clear_is_holm", "corrected"),
    "cm), and not only because the": ("shown1_lower_without_demonstrations", "causal"),
    "{glue:text}`rem_shown_sooner`":
        ("shown_sooner_held_out", "all", "cases: each shown button in each condition "
                                          "with a teacher, medians of the held-out seeds"),
}
"""The chapter's sentences with a word of strength beside a result, and the checks that
carry them (book/_ext/claim_words.py): {a fragment of the sentence: (claim name the
chapter checks when built, kind[, the set an "all" claim is over])}. The shown buttons'
"in all 8 cases" (a glued phrase) is over the 8 cases, each a comparison of medians of
the held-out seeds, which the sentence says."""
