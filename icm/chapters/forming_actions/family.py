"""The chapter "Forming actions"'s paired comparisons, one family over both of its halves:
learning progress against random goal babbling (`strategy_comparisons`) and each
remedy, growing up or being shown, against learning progress alone
(`remedy_comparisons`), each the arm minus the baseline on the same held-out seeds
(`VERDICT_ROOTS`), decided together (`chapter_verdicts`: Holm's correction over the
whole family, `icm.chapters.verdicts.decide`), and the clear ones replicated on a
fresh root (`replicate`, `run_replications`, with their power, `replication_power`).
"""

import numpy as np

from icm import _validate
from icm.chapters import replication, verdicts
from icm.chapters.words import percent
from icm.envs import buttons
from icm.studies.forming_actions import remedies as remedies_study
from icm.studies.forming_actions import strategies as strategies_study
from icm.studies.forming_actions.arms import HELD_OUT_ROOTS
from icm.studies.forming_actions.remedies import (CONDITIONS, PAIRED_MEASURES, check_study,
                                            load_fresh_runs, load_study, run_condition,
                                            seed_values, shown_buttons)
from icm.experiments.seeding import REPLICATION_ROOTS
from icm.stats import POWER_SIMULATIONS, corrected_verdicts, paired_power

VERDICT_ROOTS = HELD_OUT_ROOTS
"""The root seeds on which the chapter's comparisons are decided: the held-out ones.
Every setting the chapter "Forming actions" compares (the learner's, the clock's, the
teacher's) was chosen on the tuning roots, which would flatter it."""
REMEDY_KEYS = {"growing up": "grow", "shown button 2": "shown1",
               "shown buttons 0 and 4": "shown2", "shown all five": "shown5"}
"""The short names of the remedies in `remedy_comparisons` (and the numbers of
`icm.chapters.forming_actions.remedies.verdicts`)."""


def remedy_comparisons(study=None, roots=VERDICT_ROOTS):
    """The remedies' paired comparisons with learning progress alone, over the seeds of
    `roots` (default `VERDICT_ROOTS`): {"{key}_{measure}": {"label", "measure", "arm",
    "baseline"}} (`REMEDY_KEYS`, `PAIRED_MEASURES`; per-seed values of the remedy and
    of learning progress alone, on the same seeds), the measures of the buttons not
    shown left out where the teacher shows all five."""
    study = load_study() if study is None else check_study(study)
    out = {}
    for label, key in REMEDY_KEYS.items():
        for measure in PAIRED_MEASURES:
            if measure.startswith("others") and len(shown_buttons(label)) == buttons.N_BUTTONS:
                continue  # no button left unshown
            out[f"{key}_{measure}"] = {
                "label": label, "measure": measure,
                "arm": seed_values(study, label, measure, label, roots),
                "baseline": seed_values(study, "learning progress", measure, label, roots)}
    return out


def strategy_comparisons(study=None):
    """The paired comparisons of learning progress with random goal babbling that the
    chapter decides, on the held-out seeds only (the learner's settings were chosen on
    the tuning seeds), from the goal-babbling study (`study`, default
    `strategies_study.load_study()`): {"lp_rg_all_pressed": per-seed differences in
    all five presses formed (1 or 0), "lp_rg_test_error": in the final test error (m)};
    learning progress minus random goal babbling (`icm.chapters.verdicts.differences`)."""
    study = strategies_study.load_study() if study is None else study
    lp, rg = (strategies_study.pool([study["runs"][label][str(r)]
                                        for r in HELD_OUT_ROOTS])
              for label in ("learning progress", "random goal babbling"))
    all_pressed = lambda entry: np.array(entry["pressed"])[:, -1].all(axis=1).astype(float)
    return {"lp_rg_all_pressed": verdicts.differences(all_pressed(lp), all_pressed(rg)),
            "lp_rg_test_error": verdicts.differences(lp["test_error"], rg["test_error"])}


def chapter_family(study=None, babbling=None):
    """Every paired comparison the chapter calls clear or not, as per-seed differences on
    the held-out root seeds: the remedies' (`remedy_comparisons` of `study`) and the
    strategies' (`strategy_comparisons` of `babbling`), {name: differences}.
    `chapter_verdicts` decides them together."""
    family = {name: verdicts.differences(c["arm"], c["baseline"])
              for name, c in remedy_comparisons(study).items()}
    family.update(strategy_comparisons(babbling))
    return family


def chapter_verdicts(study=None, babbling=None):
    """`icm.stats.corrected_verdicts` of `chapter_family`: Holm's correction at a
    family-wise 5%, on sign-flip permutation p-values ({name: {"p", "p_holm",
    "clear", "mean", "n_family"}})."""
    return corrected_verdicts(chapter_family(study, babbling))


REPLICATION_SEEDS = 40
"""Seeds of a replication (`replicate`) as assets/replications.json and `FRESH_FILE`
keep it, per condition, on the fresh root. Its power under the effect the held-out
seeds measured (`replication_power`: the one-sided sign-flip test the replication
uses, on differences drawn from the measured ones, ties kept) is about 0.97 to 1 for
the teacher's lower test errors, but only about 0.55 and 0.33 for growing up's two
verdicts (test error, buttons pressed early) and 0.04 for the early presses with the
end buttons shown: with its many tied counts, 8 seeds can almost never reject. Those
three did not replicate, which says little. `POWERED_SEEDS` is the size that reaches a
power of 0.9 for every verdict."""


def replication_power(name, study=None, n_seeds=REPLICATION_SEEDS, simulations=None):
    """The power of a replication of comparison `name` (a key of `remedy_comparisons`)
    on `n_seeds` fresh seeds, under the effect the held-out seeds measured
    (`icm.stats.paired_power`, one-sided in the direction the study found;
    `simulations` default `stats.POWER_SIMULATIONS`)."""
    study = load_study() if study is None else check_study(study)
    found = remedy_comparisons(study)
    name = _validate.one_of("name", name, tuple(found))
    differences = verdicts.differences(found[name]["arm"], found[name]["baseline"])
    direction = "less" if differences.mean() < 0 else "greater"
    return paired_power(differences, n_seeds, direction,
                        simulations=simulations or POWER_SIMULATIONS)


def fresh_runs(labels, root=None, n_seeds=REPLICATION_SEEDS):
    """The conditions `labels` run with `run_condition` on the first `n_seeds` seeds of a
    fresh root (default the chapter's of `REPLICATION_ROOTS`), as a study of that one
    root: what `replicate` compares (a test computes it once for every verdict it
    replicates)."""
    root = REPLICATION_ROOTS["forming_actions"] if root is None else root
    for label in labels:
        _validate.one_of("labels[i]", label, tuple(CONDITIONS))
    return {"n_seeds": n_seeds, "roots": [root],
            "runs": {label: {str(root): run_condition(label, root, n_seeds)}
                     for label in labels}}


def replicate(names, study=None, root=None, n_seeds=REPLICATION_SEEDS, fresh=None):
    """Reruns the comparisons `names` (keys of `remedy_comparisons`) on the first
    `n_seeds` seeds of a fresh root (default the chapter's of `REPLICATION_ROOTS`), each
    condition and learning progress alone with `run_condition`, and tests each in the
    direction the study found (`study`, default `load_study()`, over `VERDICT_ROOTS`):
    {name: `icm.chapters.replication.replicated` dict}. `fresh`: those runs when
    computed before (`fresh_runs` of at least learning progress and the names'
    conditions, on `root` with `n_seeds`); None computes them."""
    study = load_study() if study is None else check_study(study)
    root = REPLICATION_ROOTS["forming_actions"] if root is None else root
    found = remedy_comparisons(study)
    for name in names:
        _validate.one_of("names[i]", name, tuple(found))
    labels = ["learning progress"] + sorted({found[n]["label"] for n in names})
    if fresh is None:
        fresh = fresh_runs(labels, root, n_seeds)
    missing = [label for label in labels if str(root) not in fresh["runs"].get(label, {})]
    if missing or fresh["n_seeds"] != n_seeds:
        raise ValueError(f"fresh must hold {n_seeds} seeds of root {root} for "
                         f"{', '.join(labels)}; it has {fresh['n_seeds']} seeds and lacks "
                         f"{', '.join(missing) or 'nothing'}")
    fresh = {**study, "n_seeds": n_seeds, "runs": fresh["runs"]}
    out = {}
    for name in names:
        label, measure = found[name]["label"], found[name]["measure"]
        differences = verdicts.differences(
            seed_values(fresh, label, measure, label, [root]),
            seed_values(fresh, "learning progress", measure, label, [root]))
        found_differences = verdicts.differences(found[name]["arm"], found[name]["baseline"])
        direction = "less" if found_differences.mean() < 0 else "greater"
        out[name] = replication.replicated(differences, direction)
    return out


def run_replications(study=None, babbling=None, fresh=None):
    """The replications of every verdict `chapter_verdicts` calls clear among the
    remedies' comparisons (`replicate`), each with its power (`replication_power`,
    "power"), as assets/replications.json keeps them: {"root", "n_seeds", "verdicts":
    {name: ...}}, from the fresh runs `fresh` (default those
    `remedies_study.FRESH_FILE` keeps, `remedies_study.load_fresh_runs`; `python -m icm
    study remedies-replication` writes them)."""
    corrected = chapter_verdicts(study, babbling)
    clear = [name for name in remedy_comparisons(study) if corrected[name]["clear"]]
    fresh = load_fresh_runs() if fresh is None else fresh
    outcomes = replicate(clear, study, fresh=fresh)
    for name, outcome in outcomes.items():
        outcome["power"] = replication_power(name, study)
    return {"root": REPLICATION_ROOTS["forming_actions"],
            "n_seeds": REPLICATION_SEEDS, "verdicts": outcomes}


MEASURE_WORDS = {"all_pressed": "all five presses formed",
                 "others_formed": "presses formed of the buttons not shown",
                 "others_pressed_early": "buttons pressed early",
                 "test_error": "test error"}
"""The measures of `icm.studies.forming_actions.remedies.PAIRED_MEASURES` in the words of a sentence."""


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
    found = remedy_comparisons(study)
    named = [f"{found[w]['label']} ({MEASURE_WORDS[found[w]['measure']]})" for w in weak]
    named = ", ".join(named[:-1]) + " and " + named[-1] if len(named) > 1 else named[0]
    strong = [p for name, p in powers.items() if name not in weak]
    target = remedies_study.POWERED_SEEDS
    forecast = [replication_power(w, study, target, simulations)
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
