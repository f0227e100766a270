"""The suite's time limits (pytest-timeout): a test that hangs fails with its name, and
the run goes on; the tests that wait for the book's build may wait longer."""

import os
import subprocess
import sys
import textwrap
import time
import tomllib

from conftest import BOOK_BUILD_SECONDS, ROOT

SLEEPY = textwrap.dedent("""
    import time


    def test_sleeps_past_the_ceiling():
        time.sleep(60)


    def test_ends_at_once():
        pass
""")
"""Two tests: one that outsleeps a ceiling of 2 s, one that passes."""

SHOW_CEILINGS = textwrap.dedent("""
    import pytest


    @pytest.hookimpl(trylast=True)
    def pytest_collection_modifyitems(items):
        for item in items:
            marker = item.get_closest_marker("timeout")
            book = "built_book" in getattr(item, "fixturenames", ())
            print("ceiling", item.nodeid, book, marker.args[0] if marker else "default")
""")
"""A plugin that prints, for each collected test, whether it reads the built book and
its own time limit ("default": the ini's)."""


def _pytest(*args, cwd, extra_path=None):
    """Runs pytest in a new process with the project's configuration (pyproject.toml):
    its CompletedProcess, stdout and stderr together."""
    env = dict(os.environ)
    env.pop("PYTEST_TIMEOUT", None)
    env.pop("PYTEST_ADDOPTS", None)
    if extra_path is not None:
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(extra_path),
                                                          env.get("PYTHONPATH")]))
    return subprocess.run([sys.executable, "-m", "pytest", "-c", str(ROOT / "pyproject.toml"),
                           "-p", "no:cacheprovider", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


def test_every_test_has_a_ceiling_that_fails_it_without_ending_the_run():
    options = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pytest"][
        "ini_options"]
    assert float(options["timeout"]) >= 300 and options["timeout_method"] == "signal"


def test_a_test_that_sleeps_past_the_ceiling_fails_with_its_name(tmp_path):
    # The project's configuration, its ceiling lowered to 2 s so that this test is
    # quick, on two workers as `make test` runs: the sleeper fails, named, long before
    # its 60 s are up, and the other test still passes.
    (tmp_path / "test_sleepy.py").write_text(SLEEPY)
    started = time.perf_counter()
    run = _pytest("--rootdir", str(tmp_path), "-o", "timeout=2", "-n", "2",
                  "--dist", "loadscope", "test_sleepy.py", cwd=tmp_path)
    seconds = time.perf_counter() - started
    output = run.stdout + run.stderr
    assert run.returncode == 1, output
    assert "FAILED test_sleepy.py::test_sleeps_past_the_ceiling" in output, output
    assert "Timeout (>2.0s) from pytest-timeout" in output, output
    assert "1 failed, 1 passed" in output, output
    assert seconds < 50, f"the run took {seconds:.0f} s: the sleeper was not stopped"


def test_the_tests_that_read_the_book_wait_for_its_build_and_no_others(tmp_path):
    # The ceilings the suite's own conftest gives, read at collection (the book is not
    # built: nothing runs).
    (tmp_path / "show_ceilings.py").write_text(SHOW_CEILINGS)
    run = _pytest("--collect-only", "-q", "-p", "show_ceilings", "-s",
                  "tests/test_book.py", "tests/test_timeout.py", cwd=ROOT,
                  extra_path=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    book, others = {}, {}
    for line in run.stdout.splitlines():
        if line.startswith("ceiling "):
            _, nodeid, reads_book, value = line.split(" ")
            (book if reads_book == "True" else others)[nodeid] = value
    ini = float(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pytest"][
        "ini_options"]["timeout"])
    assert book and others, run.stdout
    assert set(book.values()) == {str(ini + BOOK_BUILD_SECONDS)}, book
    assert set(others.values()) == {"default"}, others
