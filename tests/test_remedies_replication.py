"""The replication of the chapter "Forming actions" on a fresh root
(assets/replications.json, `remedies_study.replicate`): the library computes the stored
outcome of every verdict the chapter calls clear. Its own module, apart from
tests/test_remedies.py, so that the two take a core each (pytest-xdist runs a module on
one worker): both rerun many goal-babbling runs."""

import pytest

from icm.experiments import remedies_study, replication


@pytest.fixture(scope="module")
def study():
    return remedies_study.load_study()


@pytest.fixture(scope="module")
def fresh(study):
    """The fresh root's runs of every condition a stored replication compares, learning
    progress alone included, computed once for all of them (`remedies_study.fresh_runs`,
    as `replicate` computes them)."""
    found = remedies_study.comparisons(study)
    stored = replication.load_replications()["forming_actions"]["verdicts"]
    labels = ["learning progress"] + sorted({found[name]["label"] for name in stored})
    return remedies_study.fresh_runs(labels)


@pytest.mark.parametrize("name", sorted(
    replication.load_replications().get("forming_actions", {}).get("verdicts", {})))
def test_the_replication_is_what_the_library_computes(study, fresh, name):
    # Reruns one clear verdict on the fresh root (remedies_study.REPLICATION_SEEDS seeds;
    # its docstring gives the power) and expects the stored outcome; the chapter glues
    # "not replicated" from that file.
    stored = replication.load_replications()["forming_actions"]
    assert stored["n_seeds"] == remedies_study.REPLICATION_SEEDS
    assert fresh["roots"] == [stored["root"]]
    assert remedies_study.replicate([name], study, fresh=fresh) == {
        name: stored["verdicts"][name]}


def test_a_replication_computes_its_runs_when_not_given_them_and_refuses_too_few(
        study, fresh, monkeypatch):
    # Without `fresh`, replicate asks fresh_runs for learning progress and the verdict's
    # condition on the chapter's fresh root (here handed the shared runs back); runs
    # that lack a condition or hold other seeds are refused rather than compared.
    name = "shown5_test_error"
    label = remedies_study.comparisons(study)[name]["label"]
    asked = []
    monkeypatch.setattr(remedies_study, "fresh_runs",
                        lambda *args: asked.append(args) or fresh)
    assert remedies_study.replicate([name], study) == remedies_study.replicate(
        [name], study, fresh=fresh)
    assert asked == [(["learning progress", label], fresh["roots"][0],
                      remedies_study.REPLICATION_SEEDS)]
    with pytest.raises(ValueError, match="fresh must hold 2 seeds"):
        remedies_study.replicate([name], study, n_seeds=2, fresh=fresh)
    lacking = {**fresh, "runs": {"learning progress": fresh["runs"]["learning progress"]}}
    with pytest.raises(ValueError, match=f"lacks {label}"):
        remedies_study.replicate([name], study, fresh=lacking)
    monkeypatch.undo()
    with pytest.raises(ValueError, match="labels"):
        remedies_study.fresh_runs(["no such condition"])
