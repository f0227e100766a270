"""What the result depends on: the per-seed claims, the share intervals and verdicts,
the sweep of pairs, the map figure, and the README's list of dependencies checked on
the tests' own seeds."""

import itertools
import json
import math
import re

import matplotlib.patches
import numpy as np
import pytest

from conftest import ROOT
from test_bad_input import refused
from icm import chapters, stats
from icm.experiments import run_actor_critic, run_goal_oriented, run_rod_toppling, sweep
from icm.studies import readings as robustness_readings
from icm.studies import maps as maps_module
from icm.studies import robustness
from icm.figures import Figure, robustness_map

SEED = 1
"""The tests' root seed (the book uses 0)."""
OTHER_SEED = 2
"""A second root of the tests' own, on which the chapter's claims about all the points
of a map are replicated again (`test_the_claims_about_all_points_hold_on_a_second_root`)."""
N_SEEDS = 200


# --- share intervals and verdicts --------------------------------------------------

def test_wilson_interval_known_values_and_edges():
    low, high = stats.share_interval(200, 200)
    assert high == 1.0 and low == pytest.approx(0.98115, abs=1e-4)
    low, high = stats.share_interval(0, 200)
    assert low == 0.0 and high == pytest.approx(1 - 0.98115, abs=1e-4)
    # Wilson 95% for 180 of 200: 0.8506 to 0.9343 (textbook formula).
    low, high = stats.share_interval(180, 200)
    assert (low, high) == (pytest.approx(0.8506, abs=1e-3), pytest.approx(0.9343, abs=1e-3))
    # Arrays, and a wider interval for fewer seeds or a higher level.
    lows, highs = stats.share_interval(np.array([90, 180]), np.array([100, 200]))
    assert highs[0] - lows[0] > highs[1] - lows[1]
    wide = stats.share_interval(180, 200, level=0.99)
    assert wide[0] < low and wide[1] > high


def test_verdict_reads_the_whole_interval():
    assert stats.verdict(0.91, 0.99, 0.9) == "holds"
    assert stats.verdict(0.9, 0.99, 0.9) == "holds"
    assert stats.verdict(0.85, 0.93, 0.9) == "unclear"
    assert stats.verdict(0.70, 0.89, 0.9) == "fails"


@pytest.mark.parametrize("args, name, shown, kind", [
    ((5, 4), "successes", "5", "value"),
    ((-1, 4), "successes", "-1", "value"),
    ((1, 0), "n", "0", "value"),
    ((0.5, 4), "successes", "0.5", "type"),
    ((1, "4"), "n", "4", "type"),
    ((1, 2, 1.0), "level", "1.0", "value"),
])
def test_share_interval_rejects_bad_counts(args, name, shown, kind):
    refused(lambda: stats.share_interval(*args), name, shown, kind)


# --- the per-seed claims -----------------------------------------------------------

@pytest.fixture(scope="module")
def goal_run():
    return run_goal_oriented(n_seeds=30, n_trials=40, seed=SEED, progress=False)


def test_interest_centres_are_each_runs_own_centre(goal_run):
    centres = robustness.interest_centres(goal_run)
    assert centres.shape == (30, 2)
    for seed in (0, 7):
        # A one-seed result of the same run: GoalOrientedResult.interest_centre.
        single = type(goal_run)(goal_run.settings, goal_run.interest[seed:seed + 1],
                                goal_run.prediction_error[seed:seed + 1],
                                goal_run.mastery_trial[seed:seed + 1],
                                goal_run.practice[seed:seed + 1],
                                goal_run.button_share[seed:seed + 1],
                                goal_run.action_interest[seed:seed + 1])
        assert centres[seed, 0] == pytest.approx(single.interest_centre("red"))
        assert centres[seed, 1] == pytest.approx(single.interest_centre("green"))


def test_goal_oriented_claims_per_seed(goal_run):
    rows = robustness.goal_oriented_claims(goal_run)
    assert len(rows) == goal_run.n_seeds
    summaries = goal_run.seed_summaries()
    centres = robustness.interest_centres(goal_run)
    for row, summary, (red, green) in zip(rows, summaries, centres):
        assert row["red_first"] == summary["red_first"]
        assert row["green_mastered"] == (summary["green_mastery_trial"] >= 1)
        assert row["interest_later"] == bool(green > red)  # NaN compares False


def test_a_run_without_interest_in_a_task_does_not_count_as_interest_moving(goal_run):
    interest = goal_run.interest.copy()
    interest[0, :, 0] = 0.0  # no interest in red at all in run 0
    interest[0, :, 1] = 1.0
    silent = type(goal_run)(goal_run.settings, interest, goal_run.prediction_error,
                            goal_run.mastery_trial, goal_run.practice,
                            goal_run.button_share, goal_run.action_interest)
    assert np.isnan(robustness.interest_centres(silent)[0, 0])
    assert robustness.goal_oriented_claims(silent)[0]["interest_later"] is False


def test_rod_and_actor_critic_claims_per_seed():
    rods = run_rod_toppling(n_seeds=12, n_episodes=60, seed=SEED, initial_q=0.0,
                            progress=False)
    rows = robustness.rod_claims(rods)
    red, blue = rods.first_topple("red"), rods.first_topple("blue")
    assert [r["red_toppled_first"] for r in rows] == stats.comes_first(red, blue).tolist()
    assert [r["blue_found"] for r in rows] == (blue >= 1).tolist()
    assert [r["red_first"] for r in rows] == [s["red_first"] for s in rods.seed_summaries()]
    critic = run_actor_critic(n_seeds=12, n_trials=15, seed=SEED, progress=False)
    rows = robustness.actor_critic_claims(critic)
    assert [r["green_learned"] for r in rows] == (critic.zero_trial[:, 1] >= 1).tolist()
    assert [r["red_first"] for r in rows] == [s["red_first"] for s in critic.seed_summaries()]


# --- the sweep's per_seed hook -------------------------------------------------------

def test_sweep_keeps_the_rows_of_per_seed():
    table = sweep(run_goal_oriented, {"action_weight": [1.0, 10.0]}, n_seeds=6, n_trials=20,
                  seed=SEED, progress=False, per_seed=robustness.goal_oriented_claims)
    direct = run_goal_oriented(n_seeds=6, n_trials=20, seed=SEED, action_weight=1.0,
                               progress=False)
    rows = table[table.action_weight == 1.0].sort_values("seed_index")
    expected = robustness.goal_oriented_claims(direct)
    assert rows["interest_later"].tolist() == [r["interest_later"] for r in expected]
    assert rows["red_first"].tolist() == [r["red_first"] for r in expected]


def _rows_of_wrong_length(result):
    return [{}]


def test_sweep_rejects_a_bad_per_seed():
    refused(lambda: sweep(run_goal_oriented, {"epsilon": [0.1]}, n_seeds=3, n_trials=2,
                          progress=False, per_seed="seed_summaries"),
            "per_seed", "'seed_summaries'", "type")
    refused(lambda: sweep(run_goal_oriented, {"epsilon": [0.1]}, n_seeds=3, n_trials=2,
                          progress=False, per_seed=_rows_of_wrong_length),
            "per_seed", "[{}]", "value")


# --- the pairs' sweeps -----------------------------------------------------------------

@pytest.mark.parametrize("name", list(robustness.STUDIES))
def test_pair_grids_cover_every_pair_map_once(name):
    study = robustness.STUDIES[name]
    names = [s.name for s in study.settings]
    swept = []
    for pair, grid in robustness.pair_grids(study):
        for va in grid[pair[0]]:
            for vb in grid[pair[1]]:
                point = {**study.defaults(), pair[0]: va, pair[1]: vb}
                swept.append(tuple(point[n] for n in names))
    assert len(swept) == len(set(swept)), "a point is run twice"
    needed = set()
    for a, b in study.pairs():
        for va in study.setting(a).values:
            for vb in study.setting(b).values:
                point = {**study.defaults(), a: va, b: vb}
                needed.add(tuple(point[n] for n in names))
    assert set(swept) == needed


def _small_study():
    """The goal-oriented study on a 2 x 2 x 2 grid, short runs, plus a claim that
    always holds."""
    base = robustness.STUDIES["goal_oriented"]
    settings = (robustness.Sweep("action_weight", "weight", 10.0, (1.0, 10.0)),
                robustness.Sweep("presses_per_trial", "presses", 3, (1, 3)),
                robustness.Sweep("reading", "reading", "progress", ("progress", "literal")))
    claims = base.claims + (robustness.Claim("always", "always", 0.9, "it always does"),)
    return robustness.Study("small", "small", "small", run_goal_oriented, {"n_trials": 20},
                            settings, claims, _always_and_goal_claims)


def _always_and_goal_claims(result):
    rows = robustness.goal_oriented_claims(result)
    for row in rows:
        row["always"] = True
    return rows


@pytest.fixture(scope="module")
def small():
    return robustness.run_robustness(_small_study(), n_seeds=40, seed=SEED, progress=False)


def test_every_point_holds_what_a_direct_run_there_gives(small):
    points = small.points()
    assert len(points) == 2 * 2 + 2 + 1  # pairs of 3 settings on 2 x 2 x 2, no repeats
    assert (points.n_seeds == 40).all()
    direct = run_goal_oriented(n_seeds=40, n_trials=20, seed=SEED, action_weight=1.0,
                               reading="literal", progress=False)
    held = [r["interest_later"] for r in robustness.goal_oriented_claims(direct)]
    share, low, high = small.share("interest_later", action_weight=1.0, reading="literal")
    assert share == np.mean(held)
    assert (low, high) == stats.share_interval(int(np.sum(held)), 40)
    assert small.verdict("always") == "holds"
    table = small.pair_table("red_first", ("action_weight", "presses_per_trial"))
    assert table["share"][1, 0] == small.share("red_first", action_weight=1.0)[0]
    assert table["verdict"].shape == (2, 2)


def test_the_same_seed_gives_the_same_map(small):
    again = robustness.run_robustness(_small_study(), n_seeds=40, seed=SEED, progress=False)
    assert again.points().equals(small.points())


def test_a_claim_that_always_holds_has_no_interaction(small):
    found = small.interaction("always", ("action_weight", "reading"))
    assert np.all(found["contrast"] == 0)
    assert not small.interacts("always", ("action_weight", "reading"))


def test_interaction_is_the_contrast_of_the_shares(small):
    pair = ("action_weight", "reading")
    found = small.interaction("interest_later", pair)
    share = small.pair_table("interest_later", pair)["share"]  # [reading, weight]
    expected = share[1, 0] - share[0, 0] - share[1, 1] + share[0, 1]  # defaults: 10, progress
    assert found["contrast"][1, 0] == pytest.approx(expected)
    assert found["low"][1, 0] <= found["contrast"][1, 0] <= found["high"][1, 0]


def test_tables_name_every_setting_and_claim(small):
    dependencies = chapters.robustness.maps.dependency_table([small])
    for text in ("weight", "presses", "reading", "red mastered first", "always"):
        assert text in dependencies
    assert dependencies.count("\n") == 1 + 3 * 4
    interactions = chapters.robustness.maps.interaction_table([small])
    assert interactions.count("\n") == 1 + 3 * 4


def test_the_map_draws_every_pair_and_claim_with_marks_and_the_default(small):
    fig = robustness_map(small)
    assert isinstance(fig, Figure)
    maps = [ax for ax in fig.axes if ax.images and ax.get_xlabel() != ""]
    assert len(maps) == 3 * 4
    marks = {text.get_text()[-1] for ax in maps for text in ax.texts}
    assert marks <= set(robustness_map.__globals__["MARKS"].values()) and "✓" in marks
    outlined = [p for ax in maps for p in ax.patches
                if isinstance(p, matplotlib.patches.Rectangle) and not p.get_fill()]
    assert len(outlined) == len(maps)  # the default, once per map
    assert fig.png()[:4] == b"\x89PNG"


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda r: robustness.run_robustness("bandit"), "study", "'bandit'", "value"),
    (lambda r: robustness.run_robustness(3), "study", "3", "type"),
    (lambda r: robustness.run_robustness("goal_oriented", n_seeds=0), "n_seeds", "0", "value"),
    (lambda r: robustness.run_robustness("goal_oriented", progress="yes"), "progress",
     "'yes'", "type"),
    (lambda r: r.share("best"), "claim", "'best'", "value"),
    (lambda r: r.share("red_first", window=3), "setting", "'window'", "value"),
    (lambda r: r.share("red_first", action_weight=7.0), "action_weight", "7.0", "value"),
    (lambda r: r.share("red_first", action_weight=1.0, presses_per_trial=1,
                       reading="literal"), "point", "'reading': 'literal'", "value"),
    (lambda r: r.pair_table("red_first", ("reading", "action_weight")), "pair",
     "('reading', 'action_weight')", "value"),
    (lambda r: r.holding_values("red_first", "epsilon"), "setting", "'epsilon'", "value"),
    (lambda r: chapters.robustness.maps.dependency_table([]), "results", "[]", "type"),
    (lambda r: chapters.robustness.maps.interaction_table(["x"]), "results[0]", "'x'", "type"),
    (lambda r: robustness_map("x"), "result", "'x'", "type"),
    (lambda r: robustness.check_point("goal_oriented", "red_first", epsilon=0.1), "setting",
     "'epsilon'", "value"),
    (lambda r: robustness.check_point("goal_oriented", "red_first", n_seeds=0), "n_seeds",
     "0", "value"),
])
def test_bad_input_raises(small, call, name, shown, kind):
    refused(lambda: call(small), name, shown, kind)


# --- the claims, measured on the tests' own seeds -----------------------------------

DEFAULT_CLAIMS = [(study, claim.name) for study, s in robustness.STUDIES.items()
                  for claim in s.claims]


@pytest.mark.parametrize("study, claim", DEFAULT_CLAIMS)
def test_every_claim_holds_at_the_defaults(study, claim):
    result = robustness.check_point(study, claim, n_seeds=N_SEEDS, seed=SEED)
    assert result[0] == "holds", result


def _readme_paragraph():
    text = (ROOT / "README.md").read_text()
    found = re.search(r"\*\*What the result depends on\.\*\*(.*?)\n\n", text, re.S)
    assert found, "the README must open a paragraph with **What the result depends on.**"
    head = text[:found.start()]
    assert head.count("\n## ") == 0, "the paragraph must come before the README's sections"
    return " ".join(found.group(1).split())


def _check(study, claim, expected, **point):
    verdict, share, low, high = robustness.check_point(study, claim, n_seeds=N_SEEDS,
                                                       seed=SEED, **point)
    assert verdict == expected, (study, claim, point, verdict, share)
    return share


def _needs_action_weight_above_two():
    for weight in (1.0, 1.5, 2.0):
        _check("goal_oriented", "red_first", "fails", action_weight=weight)
    for weight in (3.0, 10.0):
        _check("goal_oriented", "red_first", "holds", action_weight=weight)
    # "at 1, red is mastered first in only about half of the seeds"
    share = _check("goal_oriented", "red_first", "fails", action_weight=1.0)
    assert 0.35 < share < 0.65


def _needs_progress_reading():
    _check("goal_oriented", "interest_later", "fails", reading="literal")
    _check("goal_oriented", "red_first", "holds", reading="literal")


def _needs_small_initial_q():
    for q in (0.01, 0.1):
        _check("rod_toppling", "red_first", "holds", initial_q=q)
    for q in (0.0, 0.2, 1.0):
        _check("rod_toppling", "red_first", "fails", initial_q=q)


def _does_not_need_three_presses():
    for presses in (1, 2, 5):
        _check("goal_oriented", "red_first", "holds", presses_per_trial=presses)
        _check("actor_critic", "red_first", "holds", presses_per_trial=presses)


def _does_not_need_standard_td_error():
    _check("actor_critic", "red_first", "holds", variant="printed_td")
    _check("actor_critic", "green_learned", "holds", variant="printed_td")
    # "with one press a trial or a weaker predictor, keeps [it] from learning green"
    _check("actor_critic", "green_learned", "fails", variant="printed_td",
           presses_per_trial=1)
    _check("actor_critic", "green_learned", "fails", variant="printed_td", action_weight=1.0)


NEEDED = {"a predictor that weighs the button above the lights": _needs_action_weight_above_two,
          "the progress reading of the interest": _needs_progress_reading,
          "a small initial Q for the Q-learner": _needs_small_initial_q}
NOT_NEEDED = {"3 presses per trial": _does_not_need_three_presses,
              "the standard TD error": _does_not_need_standard_td_error}


def test_readme_lists_exactly_the_dependencies_checked_here():
    paragraph = _readme_paragraph()
    assert "(book/robustness.ipynb)" in paragraph
    needs, _, rest = paragraph.partition("It does not need")
    assert rest, "the paragraph must say what the reproduction does not need"
    needs = needs.split("the reproduction needs", 1)[1]
    assert set(re.findall(r"\*\*(.+?)\*\*", needs)) == set(NEEDED)
    assert set(re.findall(r"\*\*(.+?)\*\*", rest)) == set(NOT_NEEDED)
    assert f"needs {['no', 'one', 'two', 'three', 'four'][len(NEEDED)]}" in paragraph


@pytest.mark.parametrize("name", list(NEEDED) + list(NOT_NEEDED))
def test_readme_dependency_holds_on_our_seeds(name):
    {**NEEDED, **NOT_NEEDED}[name]()


def test_the_studies_sweep_exactly_the_settings_declared_swept():
    # A setting is one of "the unpublished choices swept in 'What the result depends
    # on'" when its Setting has swept values; each study sweeps those of its learner
    # (and the worlds' settings it names), with the Setting's values and label.
    for study in robustness.STUDIES.values():
        specs = {**robustness.WORLD_SETTINGS, **study.run_fn.settings_class.specs()}
        for sweep in study.settings:
            spec = specs[sweep.name]
            assert sweep.values == spec.swept and sweep.label == spec.label
            assert sweep.default == spec.default and not spec.published
        learner = {n for n, spec in study.run_fn.settings_class.specs().items()
                   if spec.swept is not None}
        assert learner <= {s.name for s in study.settings}


# --- the other readings of the choices the maps do not sweep ------------------------

def test_every_unpublished_choice_is_swept_read_otherwise_or_said_why():
    for name, study in robustness.STUDIES.items():
        swept = {s.name for s in study.settings}
        read = {r.name for r in robustness_readings.readings(name)}
        for setting, spec in robustness_readings.unpublished_settings(name).items():
            said = (name, setting) in robustness.NOT_MEASURED
            assert (setting in swept or setting in read) + said == 1, (name, setting)
            # A swept choice is read one at a time on the choices its grid leaves out.
            values = {r.value for r in robustness_readings.readings(name)
                      if r.name == setting}
            if setting in swept and spec.kind == "choice":
                assert values == set(spec.choices) - set(spec.swept), (name, setting)
            elif setting in swept:
                assert not values, (name, setting)
    for (name, setting), reason in robustness.NOT_MEASURED.items():
        spec = robustness_readings.unpublished_settings(name)[setting]
        assert reason and not spec.other_readings()
    # The choices the issue lists are among the readings.
    keys = {(n, r.name, r.value) for n in robustness.STUDIES
            for r in robustness_readings.readings(n)}
    for key in [("goal_oriented", "tie", "earliest"), ("goal_oriented", "short_history", "zero"),
                ("goal_oriented", "new_task_mean", "witnessed"),
                ("rod_toppling", "max_moves", None), ("rod_toppling", "off_grid", "end")]:
        assert key in keys
    for setting in ("temperature", "lr_actor", "lr_critic", "gamma"):
        assert setting in {r.name for r in robustness_readings.readings("actor_critic")}
    # The printed reward, which the maps' TD-error axis does not try (chapter 4 reads it).
    assert {("variant", "printed_reward"), ("variant", "printed")} <= {
        r.key for r in robustness_readings.readings("actor_critic")}
    assert "epsilon" in {r.name for r in robustness_readings.readings("goal_oriented")}


@pytest.fixture(scope="module")
def goal_readings():
    return robustness_readings.run_readings("goal_oriented", n_seeds=40, seed=SEED, progress=False)


def test_each_reading_is_the_run_with_that_one_setting_changed(goal_readings):
    book = run_goal_oriented(n_seeds=40, n_trials=60, seed=SEED, progress=False)
    np.testing.assert_array_equal(goal_readings.run().interest, book.interest)
    other = run_goal_oriented(n_seeds=40, n_trials=60, seed=SEED, short_history="zero",
                              progress=False)
    np.testing.assert_array_equal(goal_readings.run(("short_history", "zero")).interest,
                                  other.interest)
    held = [r["interest_later"] for r in robustness.goal_oriented_claims(other)]
    share, low, high = goal_readings.share("interest_later", ("short_history", "zero"))
    assert share == np.mean(held)
    assert (low, high) == stats.share_interval(int(np.sum(held)), 40)
    assert len(goal_readings.readings) == len(robustness_readings.readings("goal_oriented"))


def _fake_readings(changed_share):
    """A ReadingsResult of the goal-oriented study with made-up claims: the book's
    holds everything in 40 seeds; reading "zero" holds `interest_later` in
    `changed_share` of them, every other reading as the book's."""
    study = robustness.STUDIES["goal_oriented"]
    found = robustness_readings.readings(study)
    every = {c.name: np.ones(40, dtype=bool) for c in study.claims}
    held = {None: every, **{r.key: dict(every) for r in found}}
    held[("short_history", "zero")] = {**every, "interest_later":
                                       np.arange(40) < round(40 * changed_share)}
    return robustness_readings.ReadingsResult(study, {"n_seeds": 40, "seed": 0}, found, {}, held)


def test_a_reading_that_changes_a_verdict_is_named_and_the_others_are_not():
    changed = _fake_readings(0.2)
    assert [r.key for r in changed.changes()] == [("short_history", "zero")]
    assert changed.changed(("short_history", "zero")) == ["interest_later"]
    text = chapters.robustness.readings.describe_readings(changed)
    assert text.startswith(f"Of the {len(changed.readings)} other readings, 1 changes")
    assert "zero" in text and "interest moves to green later\" fails (20.0%" in text
    assert "witnessed" not in text and "earliest" not in text
    table = chapters.robustness.readings.readings_table(changed)
    assert table.count("\n") == 2 + len(changed.readings)
    assert table.count("**") == 2 and "**20.0% ✗**" in table
    same = _fake_readings(1.0)
    assert same.changes() == [] and chapters.robustness.readings.describe_readings(
        same).startswith("None of the")
    assert "**" not in chapters.robustness.readings.readings_table(same)


@pytest.mark.parametrize("call, name, shown, kind", [
    (lambda r: robustness_readings.run_readings("bandit"), "study", "'bandit'", "value"),
    (lambda r: robustness_readings.run_readings("rod_toppling", n_seeds=0), "n_seeds", "0",
     "value"),
    (lambda r: robustness_readings.run_readings("rod_toppling", progress=1), "progress", "1",
     "type"),
    (lambda r: r.share("red_first", ("tie", "latest")), "reading", "('tie', 'latest')",
     "value"),
    (lambda r: r.share("best"), "claim", "'best'", "value"),
    (lambda r: r.run("tie"), "reading", "'tie'", "value"),
])
def test_bad_readings_input_raises(goal_readings, call, name, shown, kind):
    refused(lambda: call(goal_readings), name, shown, kind)


def test_the_rods_measure_the_moves_off_the_grid_in_both_readings():
    stay = run_rod_toppling(n_seeds=20, n_episodes=100, seed=SEED, progress=False)
    assert 0 < stay.edge_share() < 1 and stay.edge_ended_share() == 0
    assert stay.time_limit_share() == np.mean(stay.toppled == -1)
    end = run_rod_toppling(n_seeds=20, n_episodes=100, seed=SEED, off_grid="end",
                           progress=False)
    ended = end.toppled == -1
    assert end.edge_moves.max() == 1  # the first move off the grid ends the episode
    assert end.edge_ended_share() == np.mean(ended & (end.edge_moves == 1)) > 0
    no_limit = run_rod_toppling(n_seeds=20, n_episodes=100, seed=SEED, max_moves=None,
                                progress=False)
    assert (no_limit.toppled >= 0).all() and no_limit.time_limit_share() == 0
    assert no_limit.episode_length.max() > 30


# --- the chapter's claims about its maps, on the tests' own seeds -------------------

def _maps(seed):
    """The chapter's three maps on root `seed`, each with the chapter's seeds at every
    point (`chapters.robustness.maps.MAP_SEEDS`: 1,000 for each)."""
    return {name: robustness.run_robustness(name, n_seeds=chapters.robustness.maps.MAP_SEEDS[name],
                                            seed=seed, progress=False)
            for name in robustness.STUDIES}


@pytest.fixture(scope="module")
def maps():
    return _maps(SEED)


def test_the_chapters_claims_about_its_maps_hold_on_our_seeds(maps):
    found = chapters.robustness.maps.chapter_claims(maps["goal_oriented"], maps["actor_critic"],
                                      maps["rod_toppling"])
    assert set(found) == set(chapters.robustness.maps.CHAPTER_CLAIMS) and all(found.values()), found


def _with_claim_set(result, claim, value, **where):
    """A copy of `result` whose per-seed `claim` is `value` at the points matching
    `where` ({setting: value})."""
    frames = {}
    for pair, frame in result.frames.items():
        frame = frame.copy()
        match = np.ones(len(frame), dtype=bool)
        for name, wanted in where.items():
            if name == "seed_index":  # a test of the seed's index
                match &= np.asarray(frame[name].map(wanted), dtype=bool)
                continue
            column = frame[name] if name in frame else result.study.setting(name).default
            match &= np.asarray(column == wanted)
        frame.loc[match, claim] = value
        frames[pair] = frame
    return maps_module.RobustnessResult(result.study, result.settings, frames)


def test_a_map_that_contradicts_the_chapter_fails_its_claims(maps):
    goal, critic, rods = maps["goal_oriented"], maps["actor_critic"], maps["rod_toppling"]
    broken = _with_claim_set(goal, "red_first", True, action_weight=1.0)  # red first at 1
    found = chapters.robustness.maps.chapter_claims(broken, critic, rods)
    assert not found["weight_threshold"] and found["presses_not_needed"]
    broken = _with_claim_set(rods, "blue_found", False, initial_q=1.0)
    assert not chapters.robustness.maps.chapter_claims(goal, critic, broken)["rods_blue_needs_drive"]
    # One point of the rods' map where red toppled first is unclear (half the seeds).
    broken = _with_claim_set(rods, "red_toppled_first", False, initial_q=0.0,
                             epsilon=0.0, seed_index=lambda k: k % 2 == 0)
    found = chapters.robustness.maps.chapter_claims(goal, critic, broken)
    assert not found["rods_toppled_first_everywhere"] and found["rods_small_initial_q"]
    # The interest no longer moving later at the weight where red first ties.
    broken = _with_claim_set(goal, "interest_later", False, action_weight=2.0)
    assert not chapters.robustness.maps.chapter_claims(broken, critic, rods)["interest_weight_from"]
    # Red predicted well first at the largest epsilon as often as at the smallest.
    broken = _with_claim_set(rods, "red_first", True, epsilon=0.3)
    assert not chapters.robustness.maps.chapter_claims(goal, critic, broken)["rods_epsilon"]
    refused(lambda: chapters.robustness.maps.chapter_claims(critic, goal, rods), "goal", "actor_critic",
            "value")


def test_holds_from_and_shares_along(maps):
    goal = maps["goal_oriented"]
    assert goal.holding_values("red_first", "action_weight") == [3.0, 10.0]
    assert goal.holds_from("red_first", "action_weight") == 3.0
    rods = maps["rod_toppling"]
    held = rods.holding_values("red_first", "initial_q")
    assert held and held[0] > 0 and rods.holds_from("red_first", "initial_q") is None
    text = chapters.robustness.maps.shares_along(goal, "red_first", "action_weight",
                                           presses_per_trial=1)
    parts = text.split(", ")
    assert len(parts) == len(goal.study.setting("action_weight").values)
    assert parts[-1] == f"{goal.share('red_first', presses_per_trial=1)[0]:.1%} at 10"


def test_the_studies_table_defines_every_claim_for_one_run():
    # The chapter's first table: one row per claim, each with when it holds in one run
    # and the share of seeds it needs, the learner (and the paper's figure) named once.
    table = chapters.robustness.maps.studies_table()
    claims = [c for study in robustness.STUDIES.values() for c in study.claims]
    assert table.count("\n") == 1 + len(claims)
    for study in robustness.STUDIES.values():
        assert table.count(study.title) == 1 and "the paper's Figure" in study.title
        for claim in study.claims:
            assert f"| {claim.text} | {claim.meaning} | ≥ {claim.threshold:.0%} |" in table


def test_the_readings_summary_names_what_changes_a_verdict():
    changed, same = _fake_readings(0.2), _fake_readings(1.0)
    total = 2 * len(changed.readings)
    text = chapters.robustness.readings.readings_summary([changed, same])
    assert text.startswith(f"1 of the {total} other readings changes a claim's verdict")
    assert "fewer than k times: zero (goal-oriented learner: interest moves to green " \
           "later fails, 20.0%)" in text and text.endswith(f"the other {total - 1} change none")
    assert chapters.robustness.readings.changed_readings([changed, same], shares=False) == (
        "interest of a task seen fewer than k times: zero (goal-oriented learner)")
    assert chapters.robustness.readings.changed_readings([same]) == "none"
    assert chapters.robustness.readings.readings_summary([same]).startswith("none of the")
    refused(lambda: chapters.robustness.readings.readings_summary([]), "results", "[]", "type")


def test_the_chapters_numbers_come_from_its_maps(maps):
    goal, critic, rods = maps["goal_oriented"], maps["actor_critic"], maps["rod_toppling"]
    numbers, clauses = chapters.robustness.maps.chapter_numbers(goal, critic, rods)
    assert numbers["goal_lowest_weight"] == goal.holds_from("red_first", "action_weight")
    assert numbers["goal_highest_failing_weight"] < numbers["goal_lowest_weight"]
    assert numbers["goal_red_first"] == goal.summary()["red_first"]
    assert numbers["critic_green_printed_fewest"] == critic.share(
        "green_learned", variant="printed_td", presses_per_trial=1)[0]
    assert numbers["rods_q_lowest"] <= numbers["rods_q_highest"]
    assert clauses["rods_red_first_by_q"] == chapters.robustness.maps.shares_along(
        rods, "red_first", "initial_q")
    # "In at least X% of the seeds" quotes the lowest lower end of the points'
    # intervals (the share the seeds vouch for), never the sample's 100%.
    lowest = float(rods.points().query("initial_q > 0").blue_found_low.min())
    assert lowest < 1 and clauses["rods_blue_positive_q_in"] == \
        f"in at least {math.floor(1000 * lowest + 1e-9) / 10:.1f}% of the seeds"
    assert "every" not in clauses["rods_toppled_first_points"]
    counts = rods.summary()
    assert clauses["rods_toppled_first_points"].startswith(
        f"it holds at {counts['red_toppled_first_holds']} of the {counts['n_points']} points")
    points = critic.points()
    weakest = points.loc[points.red_first.idxmin()]
    assert numbers["critic_red_first_min"] == weakest.red_first
    assert clauses["critic_red_first_weakest"] == ", ".join(
        f"{name} = {robustness.show_value(weakest[name])}"
        for name in ("action_weight", "presses_per_trial", "variant"))
    refused(lambda: chapters.robustness.maps.chapter_numbers(goal, goal, rods), "critic",
            "goal_oriented", "value")


def test_the_readings_numbers_come_from_the_runs():
    found = {name: robustness_readings.run_readings(name, n_seeds=10, seed=SEED, progress=False)
             for name in robustness.STUDIES}
    numbers, clauses = chapters.robustness.readings.readings_numbers(found)
    book = found["rod_toppling"].run()
    assert numbers["edge_share"] == book.edge_share() > 0
    assert numbers["time_limit_share"] == book.time_limit_share()
    assert numbers["no_limit_longest"] >= numbers["book_longest"]
    assert numbers["edge_ended_share"] > 0
    assert clauses["readings_actor_critic"] == \
        chapters.robustness.readings.describe_readings(found["actor_critic"])
    refused(lambda: chapters.robustness.readings.readings_numbers(
        {"goal_oriented": found["goal_oriented"]}), "found", "goal_oriented", "type")


# --- the chapter's claims replicated on a fresh root (issue 28) ----------------------------

def test_the_replication_is_what_the_library_computes():
    # assets/replications.json's "robustness" entry is the chapter's three maps run again
    # on the fresh root, every claim rechecked there (python -m icm.chapters.robustness).
    from icm.chapters import replication
    from icm.experiments.seeding import REPLICATION_ROOTS
    stored = replication.load_replications()["robustness"]
    assert stored["root"] == REPLICATION_ROOTS["robustness"]
    assert stored["root"] not in (0, SEED, OTHER_SEED)
    assert stored["n_seeds"] == chapters.robustness.maps.MAP_SEEDS
    assert chapters.robustness.maps.run_replication() == stored
    assert set(stored["claims"]) == set(chapters.robustness.maps.CHAPTER_CLAIMS)


def test_a_claim_that_did_not_replicate_is_said_so_beside_it():
    from icm.chapters import replication
    stored = replication.load_replications()["robustness"]
    sentences = chapters.robustness.maps.replication_sentences(stored)
    failed = [name for name, held in stored["claims"].items() if not held]
    for name in failed:
        assert chapters.robustness.maps.CHAPTER_CLAIMS[name] in sentences["summary"]
    assert ("Not replicated" in sentences["critic_everywhere"]) == (
        "critic_red_everywhere" in failed)
    # A bold claim of the chapter that did not replicate has the sentence beside it.
    cells = [c["source"] for c in json.loads(
        (ROOT / "book" / "robustness.ipynb").read_text())["cells"]]
    for bold, (claim, _) in chapters.robustness.BOLD_CLAIMS.items():
        if claim in failed:
            text = next("".join(c) for c in cells
                        if bold[:40] in " ".join("".join(c).split()))
            assert "replication_" in text, bold
    # Made up: every claim held, or the actor-critic's did not.
    held = {**stored, "claims": dict.fromkeys(stored["claims"], True)}
    assert "all of them" in chapters.robustness.maps.replication_sentences(held)["summary"]
    assert "held again" in chapters.robustness.maps.replication_sentences(held)["critic_everywhere"]
    lost = {**held, "claims": {**held["claims"], "critic_red_everywhere": False}}
    assert "Not replicated" in chapters.robustness.maps.replication_sentences(lost)[
        "critic_everywhere"]
    # The rods' counts are said as they are, with "none" for a count of zero.
    counts = stored["rods_toppled_first"]
    assert sum(counts.values()) == robustness.STUDIES["rod_toppling"].setting(
        "initial_q").values.__len__() * len(robustness.STUDIES["rod_toppling"].setting(
            "epsilon").values)
    assert ("Not replicated" in sentences["rods_toppled"]) == (
        "rods_toppled_first_everywhere" in failed)
    rods = chapters.robustness.maps.replication_sentences(
        {**stored, "claims": {**stored["claims"], "rods_toppled_first_everywhere": False},
         "rods_toppled_first": {"holds": 14, "unclear": 6, "fails": 0}})["rods_toppled"]
    assert rods.startswith("Not replicated") and rods.endswith(
        "it holds at 14 of the 20 points, is unclear at 6 and fails at none.")


# --- how many seeds a claim needs, and the rods' first episode (issues 43 and 44) -------

def test_seeds_needed_is_the_fewest_whose_interval_clears_the_threshold():
    for n in (50, 200, 1000):
        needed = chapters.robustness.maps.seeds_needed(n)
        assert stats.share_interval(needed, n)[0] >= robustness.CLAIM_SHARE
        assert stats.share_interval(needed - 1, n)[0] < robustness.CLAIM_SHARE
    assert chapters.robustness.maps.seeds_needed(200) == 189  # the chapter's question 6.2
    assert chapters.robustness.maps.seeds_needed(10) is None  # 10 of 10: 72% to 100%


def test_the_chance_to_hold_grows_with_the_seeds_and_the_share():
    chance = chapters.robustness.maps.chance_to_hold
    assert chance(0.95, 200) < chance(0.95, 1000) < 1
    assert chance(0.93, 200) < chance(0.95, 200) < chance(0.97, 200)
    assert chance(0.9, 1000) < 0.05  # a share at the threshold seldom clears it
    assert chance(1.0, 200) == 1.0 and chance(0.0, 200) == 0.0
    # Counted by simulation: 20,000 sets of 200 seeds with a true share of 95%.
    held = np.random.default_rng(SEED).binomial(200, 0.95, size=20_000)
    assert np.mean(held >= 189) == pytest.approx(chance(0.95, 200), abs=0.01)
    refused(lambda: chance(1.5, 200), "share", "1.5", "value")
    refused(lambda: chapters.robustness.maps.seeds_needed(0), "n_seeds", "0", "value")


def test_the_first_episode_a_quiet_move_loses_a_little_unless_untried_moves_are_worth_nothing():
    from icm.studies import readings as robustness_readings
    from icm.learners.q_learning import QLearnerSettings
    book = QLearnerSettings()
    for q in (0.0, 0.1, 1.0):
        after = robustness_readings.value_after_a_quiet_move(q)
        # Equation 3 with no reward and untried moves ahead: q + alpha (gamma q - q).
        assert after == pytest.approx(q + book.alpha * (book.gamma * q - q))
        assert (after < q) if q > 0 else (after == 0)
    checks, numbers = chapters.robustness.readings.first_episode([0.0, 0.1])
    assert checks == {"quiet_move_loses": True, "red_nearer": True}
    assert numbers["quiet_move_after"] == robustness_readings.value_after_a_quiet_move(
        book.initial_q) < numbers["quiet_move_before"] == book.initial_q
    refused(lambda: chapters.robustness.readings.first_episode([]), "initial_q_values", "[]", "type")


def test_with_untried_moves_worth_nothing_red_passes_chapter_5s_reading_not_the_strict_one():
    # Why the rods' map reads "predicted well" strictly, on the tests' own seeds.
    zero = run_rod_toppling(n_seeds=200, n_episodes=300, seed=SEED, initial_q=0.0,
                            progress=False)
    checks, numbers = chapters.robustness.readings.strict_reading(zero)
    assert checks == dict.fromkeys(chapters.robustness.readings.STRICT_READING_CLAIMS, True), numbers
    well = zero.well_predicted("toppled")
    assert numbers["zero_red_first_toppled"] == np.mean(stats.comes_first(well[:, 0],
                                                                           well[:, 1]))
    assert numbers["zero_seeds"] == 200
    book = run_rod_toppling(n_seeds=5, n_episodes=20, seed=SEED, progress=False)
    refused(lambda: chapters.robustness.readings.strict_reading(book), "zero_run", "0.1", "value")
    refused(lambda: chapters.robustness.readings.strict_reading("run"), "zero_run", "'run'", "type")


@pytest.mark.parametrize("rod", ["red", "blue"])
def test_the_fewest_moves_to_topple_a_rod_are_those_of_the_table(rod):
    # Every sequence of moves from the start, played on the tabular twin: the shortest
    # that topples `rod` is as long as the breadth-first search says.
    from icm.envs import load, rods
    from icm.studies import readings as robustness_readings
    fewest = robustness_readings.fewest_moves_to_topple(rod)
    env = load("rods")
    index = rods.ROD_NAMES.index(rod)

    def topples(moves):
        env.reset()
        for move in moves:
            step = env.step(move)
            if step.last():
                return bool(step.observation["rods"][index])
        return False

    for length in range(1, fewest + 1):
        found = any(topples(m) for m in itertools.product(range(4), repeat=length))
        assert found == (length == fewest), (rod, length)
    refused(lambda: robustness_readings.fewest_moves_to_topple("green"), "rod", "'green'",
            "value")


def test_the_claims_about_all_points_hold_on_a_second_root():
    # Every claim of the chapter about its maps (not only those about all the points of
    # a map, as the name says: conftest.SLOW lists it by name), replicated on a second
    # root of the tests' own, each map with the chapter's 1,000 seeds at every point:
    # the claims about all the points of a map (red predicted well first at every point
    # of the actor-critic's map, red toppled first at every point of the rods' map,
    # ...), and those about single points, worded at the strength 1,000 seeds give (a
    # point whose share lies near its threshold is quoted with its verdict, not
    # claimed: MAP_SEEDS).
    found = _maps(OTHER_SEED)
    claims = chapters.robustness.maps.chapter_claims(found["goal_oriented"],
                                                found["actor_critic"], found["rod_toppling"])
    assert claims == dict.fromkeys(chapters.robustness.maps.CHAPTER_CLAIMS, True)


def test_a_map_cell_reads_100_only_when_every_seed_held(small):
    # One decimal in every cell (a share of 200 or 1,000 seeds shows exactly), more
    # where one would read 100.0 or 0.0 for a share that is neither.
    from icm.figures.robustness import cell_percent
    assert [cell_percent(s) for s in (1.0, 0.999, 0.995, 0.485, 0.97, 0.004, 0.0,
                                      0.9996)] == [
        "100.0", "99.9", "99.5", "48.5", "97.0", "0.4", "0.0", "99.96"]
    # The map writes each point's share so, and "100.0" only where every seed held.
    fig = robustness_map(small)
    texts = [t.get_text().split("\n")[0] for ax in fig.axes for t in ax.texts]
    table = small.pair_table("red_first", ("action_weight", "presses_per_trial"))
    for share in table["share"].ravel():
        assert cell_percent(share) in texts
        assert (cell_percent(share) == "100.0") == (share == 1)


def test_the_maps_colour_bars_are_in_percent_as_the_cells_are(small):
    import dataclasses

    from icm.figures.robustness import KEY, KEY_MORE_SETTINGS
    fig = robustness_map(small)
    bars = [ax for ax in fig.axes if "share of seeds" in ax.get_xlabel()]
    assert len(bars) == len(small.study.claims)
    for bar, claim in zip(bars, small.study.claims):
        labels = [t.get_text() for t in bar.get_xticklabels()]
        assert labels == ["0", f"{100 * claim.threshold:g}", "100"]
        assert "%" in bar.get_xlabel()
    keys = lambda fig: [" ".join(t.get_text().split()) for t in fig.texts
                        if t is not fig._suptitle]
    assert keys(fig) == []  # four claims in two columns: no place free for the key
    # Three claims in two columns: the key fills the free place beside the third.
    three = maps_module.RobustnessResult(
        dataclasses.replace(small.study, claims=small.study.claims[:3]), small.settings,
        small.frames)
    assert keys(robustness_map(three)) == [f"{KEY} {KEY_MORE_SETTINGS}"]
    # With two settings (one map per claim), the key does not speak of other settings.
    rods = robustness.run_robustness("rod_toppling", n_seeds=10, seed=SEED, progress=False)
    assert keys(robustness_map(rods)) == [KEY]
