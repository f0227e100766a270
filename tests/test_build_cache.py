"""The book's build stops and repairs itself: the first failure and Ctrl-C stop every
notebook at once, a damaged cache repairs itself, two builds in one folder take turns,
bad arguments are refused in one line. Each test runs `book/_ext/execute_book.py` (or
`build_book.py`'s lock) on small notebooks of its own, with the helpers of
tests/test_build.py (its own module so that pytest-xdist runs the two on both cores)."""

import json
import signal
import subprocess
import sys
import time

import nbformat
import psutil
import pytest

from conftest import BUILD_BOOK, EXECUTE_BOOK, ROOT
from test_build import BUSY, build_book, execute_book, kernels_of, notebook, run


# Fail fast, stop at once --------------------------------------------------------------

def test_the_first_failure_stops_the_other_notebooks_at_once(tmp_path):
    long = notebook(tmp_path / "long.ipynb", BUSY.format(300))
    fails = notebook(tmp_path / "fails.ipynb", "import time\ntime.sleep(2)",
                     "raise ValueError('a cell that raises')")
    status, _, stderr, seconds = run(tmp_path / "out", long, fails)
    assert status == 1
    assert "fails.ipynb: cell 1 failed" in stderr and "a cell that raises" in stderr
    assert "stopping the other notebooks" in stderr
    assert seconds < 300  # not the 300 CPU-seconds of the long notebook
    assert "long.ipynb" not in stderr.split("stopping the other notebooks")[1]  # not reported


def test_keep_going_runs_the_others_after_a_failure(tmp_path):
    fails = notebook(tmp_path / "fails.ipynb", "raise ValueError('boom')")
    passes = notebook(tmp_path / "passes.ipynb", "import time\ntime.sleep(3)\nprint(1)")
    status, stdout, stderr, _ = run(tmp_path / "out", "--keep-going", "--jobs", 1, fails, passes)
    assert status == 1 and "fails.ipynb: cell 0 failed" in stderr
    assert "executed" in stdout and "passes.ipynb" in stdout


def test_ctrl_c_stops_at_once_and_the_next_run_keeps_what_was_executed(tmp_path):
    quick = notebook(tmp_path / "quick.ipynb", "print('quick')")
    long = notebook(tmp_path / "long.ipynb", BUSY.format(300))
    out = tmp_path / "out"
    # Started with SIGINT ignored, as a background job of a shell without job control
    # starts it (a CI script's `make test &`): Ctrl-C must stop it all the same.
    process = subprocess.Popen(
        [sys.executable, str(EXECUTE_BOOK), "--path-output", str(out), str(long), str(quick)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    deadline = time.monotonic() + 600
    lines = []
    while time.monotonic() < deadline:  # wait until the quick one is cached
        line = process.stdout.readline()
        lines.append(line)
        if "executed" in line and "quick.ipynb" in line:
            break
    else:
        process.kill()
        pytest.fail("the quick notebook never finished:\n" + "".join(lines))
    assert kernels_of(process.pid), "the long notebook's kernel should be running"
    process.send_signal(signal.SIGINT)
    start = time.monotonic()
    _, stderr = process.communicate(timeout=600)
    assert process.returncode == 130
    # At once: not after the long notebook's remaining CPU-seconds (most of its 300).
    assert time.monotonic() - start < 120, "Ctrl-C did not stop the build at once"
    assert "interrupted: 1 notebooks executed and kept in the cache" in stderr
    assert not psutil.pid_exists(process.pid) or not kernels_of(process.pid)
    status, stdout, stderr, _ = run(out, quick)
    assert status == 0 and "cached   " in stdout and "quick.ipynb" in stdout, stdout + stderr


# A cache that repairs itself ----------------------------------------------------------

def _first_build(tmp_path):
    path = notebook(tmp_path / "small.ipynb", "print(6 * 7)")
    out = tmp_path / "out"
    status, _, stderr, _ = run(out, path)
    assert status == 0, stderr
    return path, out, out / "_build" / ".jupyter_cache"


def test_a_damaged_cache_database_is_emptied_and_the_build_goes_on(tmp_path):
    path, out, cache = _first_build(tmp_path)
    database = cache / "global.db"
    database.write_bytes(database.read_bytes()[:100])  # truncated
    status, stdout, stderr, _ = run(out, path)
    assert status == 0, stderr
    assert "repair   the execution cache's database was damaged" in stderr
    assert "executed" in stdout
    status, stdout, _, _ = run(out, path)  # and the repaired cache works
    assert status == 0 and "cached" in stdout


def test_a_damaged_cached_notebook_is_executed_again(tmp_path):
    path, out, cache = _first_build(tmp_path)
    (cached,) = cache.glob("executed/*/base.ipynb")
    cached.write_text(cached.read_text()[:50])  # truncated: no longer JSON
    status, stdout, stderr, _ = run(out, path)
    assert status == 0, stderr
    assert "repair   the cached copy of" in stderr and "executed" in stdout
    from jupyter_cache import get_cache

    record = get_cache(str(cache)).match_cache_notebook(nbformat.read(path, as_version=4))
    assert get_cache(str(cache)).get_cache_bundle(record.pk).nb.cells[0].outputs


def test_a_damaged_record_of_times_is_forgotten(tmp_path):
    path, out, cache = _first_build(tmp_path)
    times = cache.parent / execute_book.TIMES_FILE
    times.write_text('{"book/x.ipynb": 1')  # truncated JSON
    status, _, stderr, _ = run(out, "--force", path)
    assert status == 0, stderr
    assert f"repair   {execute_book.TIMES_FILE} was damaged" in stderr
    assert json.loads(times.read_text())  # written afresh


def test_the_library_fingerprint_is_kept_when_a_run_fails(tmp_path):
    # Written before anything runs: an interrupted or failed run keeps its cache.
    good = notebook(tmp_path / "good.ipynb", "print(1)")
    bad = notebook(tmp_path / "bad.ipynb", "raise ValueError('x')")
    out = tmp_path / "out"
    status, _, _, _ = run(out, "--keep-going", "--jobs", 1, good, bad)
    assert status == 1
    status, stdout, _, _ = run(out, good)
    assert status == 0 and "cached" in stdout


# Two builds in one folder -------------------------------------------------------------

TWO_BUILDS = """
import sys, pathlib
sys.path.insert(0, {folder!r})
import build_book, execute_book
out = pathlib.Path(sys.argv[1])
with build_book.build_lock(out / "_build"):
    sys.exit(execute_book.main(["--force", "--path-output", str(out)] + sys.argv[2:]))
"""


def test_two_builds_in_one_folder_take_turns_and_both_succeed(tmp_path):
    # Each build empties the cache (--force) and executes into it: without the lock,
    # one deletes the database the other has open.
    paths = [notebook(tmp_path / f"n{i}.ipynb", "import time\ntime.sleep(2)\nprint(1)")
             for i in range(2)]
    script = tmp_path / "one_build.py"
    script.write_text(TWO_BUILDS.format(folder=str(BUILD_BOOK.parent)))
    out = tmp_path / "out"
    command = [sys.executable, str(script), str(out)] + [str(p) for p in paths]
    first = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    second = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    results = [p.communicate(timeout=900) for p in (first, second)]
    assert first.returncode == 0 and second.returncode == 0, results
    assert "waiting: another build of the book is running in" in results[1][1]
    assert all("2 of 2 notebooks executed" in r[0] for r in results)


def test_the_lock_is_released_when_its_holder_dies(tmp_path):
    holder = subprocess.Popen([sys.executable, "-c", TWO_BUILDS.format(
        folder=str(BUILD_BOOK.parent)).replace(
        'sys.exit(execute_book.main(["--force", "--path-output", str(out)] + sys.argv[2:]))',
        'print("locked", flush=True); import time; time.sleep(600)'), str(tmp_path)],
        stdout=subprocess.PIPE, text=True)
    assert holder.stdout.readline().strip() == "locked"
    holder.kill()
    holder.wait()
    start = time.monotonic()
    with build_book.build_lock(tmp_path / "_build"):
        pass
    assert time.monotonic() - start < 5


@pytest.mark.parametrize("argument", ["--jobs=0", "--stall=0", "--cpu-limit=-1"])
def test_bad_arguments_are_refused_in_one_line(tmp_path, argument):
    status, _, stderr, _ = run(tmp_path, argument)
    assert status == 2 and "must be" in stderr
