"""Shared fixtures and the suite's own bookkeeping: the book, built once per test
session as CI builds it; the markers that `make test-quick` leaves out; and the record
of the run's durations that `make bench` reports."""

import contextlib
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

import pytest

from icm._book import SKIP_SLOW_IMPORT

exec(SKIP_SLOW_IMPORT)  # the test processes import nbformat too (icm/_book.py says why)

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD_BOOK = ROOT / "book" / "_ext" / "build_book.py"
EXECUTE_BOOK = ROOT / "book" / "_ext" / "execute_book.py"
RECORDS = ROOT / "_build"
"""Where the last test run leaves its records (`make bench` reads them)."""
DURATIONS_RECORD = RECORDS / "icm-test-durations.json"
"""The durations per test of the last run of the whole suite (wall time without the
wait for the book's build, and CPU time), with the reference workload timed at its
end."""
BASELINE_RECORD = ROOT / "tests" / "data" / "module-seconds.json"
"""Seconds per test module in a full run, committed: the order of the modules in a
checkout that has no DURATIONS_RECORD yet (without it, a module of minutes may start
last and run alone at the end)."""
EXECUTION_RECORD = "icm-execution-record.json"
"""The book build's record of execution times (book/_ext/execute_book.py), copied into
RECORDS by the session that built the book."""


def toc_files():
    """The book's pages in table-of-contents order (paths without suffix)."""
    from icm._book import toc_pages

    return toc_pages(ROOT)


def first_objective(chapter):
    """The first learning objective a chapter's notebook states, its first four words
    (the chapter is the one source of its objectives; tests that look for them in a
    built page or a deck ask for these words, so rewording an objective breaks none)."""
    cells = json.loads((ROOT / "book" / f"{chapter}.ipynb").read_text())["cells"]
    for cell in cells:
        source = "".join(cell["source"])
        if ":class: icm-objectives" in source:
            bullet = next(line for line in source.splitlines() if line.startswith("- "))
            return " ".join(bullet[2:].split()[:4])
    raise AssertionError(f"{chapter} states no learning objectives")


@contextlib.contextmanager
def cpu_burners(count=None):
    """Keeps every core busy (one process per core spinning in a loop, at normal
    priority) while the block runs: a machine made slow on purpose, as a student's
    laptop that is doing other work, a Binder fraction of a core or a shared CI
    runner."""
    if count is None:
        count = os.cpu_count() or 1
    # Each burner spins until its parent is gone, so that a test run killed before its
    # cleanup leaves no burner behind.
    spin = "import os\nparent = os.getppid()\nwhile os.getppid() == parent:\n    pass"
    burners = [subprocess.Popen([sys.executable, "-c", spin]) for _ in range(count)]
    try:
        yield len(burners)
    finally:
        for burner in burners:
            burner.kill()
        for burner in burners:
            burner.wait()


# --- markers and order -----------------------------------------------------------------

SLOW = ("tests/test_remedies.py::test_the_study_file_is_what_the_library_computes",
        "tests/test_remedies_replication.py::test_the_kept_fresh_runs_are_what_the_library_computes",
        "tests/test_curiosity.py::test_every_clear_paired_verdict_of_the_chapter_is_replicated",
        "tests/test_robustness.py::test_the_replication_is_what_the_library_computes",
        "tests/test_robustness.py::test_the_claims_about_all_points_hold_on_a_second_root",
        "tests/test_goal_babbling.py::test_the_study_file_is_what_the_library_computes",
        "tests/test_goal_babbling.py::test_the_claims_kept_runs_are_what_the_library_computes",
        "tests/test_goal_babbling_runs.py::test_the_chapters_runs_are_what_the_library_computes",
        "tests/test_physics.py::test_thousands_of_random_actions_stay_stable",
        "tests/test_memory.py::test_memory_bound_holds_and_is_within_one_and_a_half_times_the_peak",
        "tests/test_build.py::",
        "tests/test_build_cache.py::",
        "tests/test_shared_navigation.py::",
        "tests/test_studies.py::test_every_registered_study_runs_tiny",
        "tests/test_studies.py::test_remedies_seeds_run_one_at_a_time_are_those_of_a_batched_run",
        "tests/test_studies.py::test_a_study_is_byte_identical_serially_on_joblib_and_on_a_dask_cluster",
        "tests/test_studies.py::test_a_dask_worker_killed_mid_run_costs_only_its_unit_and_the_result_is_unchanged",
        "tests/test_sweep.py::test_dask_local_cluster_gives_the_same_numbers",
        "tests/test_exact.py::test_runs_are_the_same_whichever_kernels_blas_picks")
"""Tests (node ids, or their start) that take minutes: the reruns of the stored studies
and the chapters' claims on many seeds, the physics' thousands of random actions, the
memory bounds (a large run each, in a process of its own), the runs on a pool of
processes or a Dask cluster and under other BLAS kernels (each starts Python processes
that import icm; left out, make test-quick went from 127 s and 236 CPU-seconds to
102 s and 184, 2026-12-03, reference workload 0.019 to 0.037 s before, 0.026 to 0.019
after), the slowest chapter under
load, and the book executor's own tests (tests/test_build*.py: kernels on small
notebooks, many under CPU burners; 170 s of a make test-quick of 210 s on 2 cores,
2026-12-02). `make test` runs them; `make test-quick` leaves them out (marker `slow`).
In a make test of a fresh clone, 2026-12-03 08:09 (a slow hour: the reference workload
took 0.030 s, against 0.018 on a quiet machine), they took 420 of the 1,052 s that all
the tests took summed over both workers (273 of 634 CPU-seconds). The claims checked on
many seeds read kept runs, and only their last seeds are rerun
(tests/test_remedies_replication.py, tests/test_goal_babbling.py)."""
SLOW_FIXTURES = ("assignments", "graded", "attacked")
"""Fixtures that take tens of seconds, so that every test using them is `slow` too: the
course's assignments written by otter (tests/test_course.py, tests/test_grading.py),
and the classes graded from them, honest (tests/test_grading.py) and attacking
(tests/test_grading_attacks.py)."""


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "slow: takes minutes (conftest.SLOW); make test runs it, make "
                   "test-quick does not")
    config.addinivalue_line(
        "markers", "browser: drives headless Chromium (marked from the fixtures a test "
                   "uses: `browser`, or a test of tests/test_browser.py or tests/test_pdf.py "
                   "that reads the built book)")
    config.pluginmanager.register(_LongestFirst(), "icm-longest-first")


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Marks what a test needs from the fixtures it uses, before `-m` selects, so that
    no test can forget its marker: `book` for every test that reads the built book,
    `browser` for every test that drives Chromium. `make test-quick` leaves out both
    (and `launch`)."""
    book_ceiling = book_test_ceiling(config)
    for item in items:
        names = getattr(item, "fixturenames", ())
        module = getattr(getattr(item, "module", None), "__name__", "")
        if "built_book" in names:
            item.add_marker(pytest.mark.book)
            if book_ceiling:
                item.add_marker(pytest.mark.timeout(book_ceiling))
        if item.nodeid.startswith(SLOW) or set(SLOW_FIXTURES) & set(names):
            item.add_marker(pytest.mark.slow)
        if "browser" in names or (module in ("test_browser", "test_pdf")
                                  and "built_book" in names):
            item.add_marker(pytest.mark.browser)


def _needs_book(item):
    return "built_book" in getattr(item, "fixturenames", ())


BOOK_BUILD_SECONDS = 1800
"""How long a test that reads the built book may wait for its build, beyond the
ceiling every test has (pyproject.toml: `timeout`, pytest-timeout's, setup and teardown
included): the first such test of a worker waits in its setup (`built_book`) for the
build that started with the run. The build executes every notebook afresh (its target:
150 s on an idle machine, `make bench`), then writes the HTML (66 CPU-seconds), on
cores the unit tests share; it guards itself (a cell stalled for 60 s fails, and so does
a runaway one: book/_ext/execute_book.py). Half an hour is about eight times what it
takes on an idle machine, and a third of CI's 90 minutes (in a make test of
2026-12-05, on a machine ten times slower than a quiet one, seven of the eight
notebooks executed in 188 s of wall time, before the eighth failed on main's data)."""


def book_test_ceiling(config):
    """The time limit of a test that reads the built book: the ceiling of every test
    plus `BOOK_BUILD_SECONDS` (no limit if the run has none: `--timeout 0`, or
    `-p no:timeout`)."""
    if not config.pluginmanager.hasplugin("timeout"):
        return 0
    from pytest_timeout import get_env_settings  # the option, PYTEST_TIMEOUT or the ini

    ceiling = get_env_settings(config).timeout or 0
    return ceiling + BOOK_BUILD_SECONDS if ceiling > 0 else 0


TAIL_SHARE = 0.1
"""The share of the recorded time that the shortest modules, run after the book's,
make up at most (`_LongestFirst`)."""


class _LongestFirst:
    """Orders the selected tests so that two workers (pytest-xdist, `make test`) finish
    together: whole modules (a worker takes a module at a time: `--dist loadscope`),
    the longest first by the last run's record of durations; then the modules that
    read the built book, each with its other tests first, so that the book builds in
    the background while everything else runs; then the shortest modules (`TAIL_SHARE`
    of the time), which fill the end. Without a record of its own (a fresh clone), by
    `BASELINE_RECORD`."""

    @pytest.hookimpl(trylast=True)
    def pytest_collection_modifyitems(self, config, items):
        recorded = {}
        try:
            for nodeid, seconds, *_ in json.loads(DURATIONS_RECORD.read_text())["durations"]:
                module = nodeid.split("::")[0]
                recorded[module] = recorded.get(module, 0.0) + seconds
        except (OSError, ValueError, KeyError, TypeError):
            pass
        modules = {}
        for item in items:
            modules.setdefault(item.nodeid.split("::")[0], []).append(item)
        if not recorded:  # a fresh clone, CI: the committed record of a full run
            try:
                recorded = json.loads(BASELINE_RECORD.read_text())["modules"]
            except (OSError, ValueError, KeyError):
                pass
        book = sorted((m for m in modules if any(map(_needs_book, modules[m]))),
                      key=lambda m: -recorded.get(m, 0.0))
        others = sorted((m for m in modules if m not in book),
                        key=lambda m: -recorded.get(m, 0.0))
        # The shortest modules go after the book's: a worker that finishes its book
        # module first takes them, so that the workers end together (with the book's
        # modules last, one worker ran Chromium's modules alone for the last 52 s of
        # a make test of 518 s, 2026-12-03, while the other had nothing left).
        tail, room = [], TAIL_SHARE * sum(recorded.get(m, 0.0) for m in modules)
        while others and recorded.get(others[-1], 0.0) <= room:
            room -= recorded.get(others[-1], 0.0)
            tail.insert(0, others.pop())
        items[:] = [item for module in others + book + tail
                    for item in sorted(modules[module], key=_needs_book)]


# --- the book ---------------------------------------------------------------------------

BUILD_IN_BACKGROUND = """
import os, signal, subprocess, sys, time
build_book, out, log, status = sys.argv[1:5]
parent, asked_to_stop, code = os.getppid(), [], 130
signal.signal(signal.SIGTERM, lambda *_: asked_to_stop.append(True))
try:
    with open(log, "w") as handle:
        build = subprocess.Popen([sys.executable, build_book, "--force", "--strict",
                                  "--path-output", out], stdout=handle,
                                 stderr=subprocess.STDOUT)
        try:
            while build.poll() is None:
                if asked_to_stop or os.getppid() != parent:  # the test run is gone
                    break
                time.sleep(0.5)
        except KeyboardInterrupt:  # Ctrl-C: the build has it too
            pass
        if build.poll() is None:
            build.send_signal(signal.SIGINT)  # build_book stops its kernels at once
            try:
                build.wait(60)
            except subprocess.TimeoutExpired:
                build.kill()
                build.wait()
        else:
            code = build.returncode
finally:
    with open(status + ".tmp", "w") as handle:
        handle.write(str(code))
    os.replace(status + ".tmp", status)
"""
"""Runs build_book.py into `out`, its log to `log`, then writes its exit status to
`status` (130 if stopped); stops the build when asked (SIGTERM) or when the test run
that started it is gone."""


class BookBuild:
    """The one build of the book in a test run, in `folder`: started in the background
    as soon as the run has a test that needs it, so that it runs while the unit tests
    do; with pytest-xdist, the workers share it through `folder` (the first to ask
    starts it, a lock keeps it to one)."""

    def __init__(self, folder):
        self.folder = pathlib.Path(folder)
        self.out = self.folder / "book"
        self.log = self.folder / "book-build.log"
        self.status = self.folder / "book-build.status"
        self.process = None

    def start(self):
        """Starts the build unless it was started before (here or by another worker);
        returns whether this call started it."""
        import fcntl

        self.folder.mkdir(parents=True, exist_ok=True)
        with open(self.folder / "book-build.lock", "a") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if self.log.exists():
                return False
            self.log.touch()
            self.process = subprocess.Popen(
                [sys.executable, "-c", BUILD_IN_BACKGROUND, str(BUILD_BOOK), str(self.out),
                 str(self.log), str(self.status)], cwd=ROOT)
            return True

    def wait(self):
        """The build's exit status, once it has ended (however long a slow machine
        takes: the build itself fails a cell that stalls or runs away)."""
        while not self.status.exists():
            if self.process is not None and self.process.poll() is not None \
                    and not self.status.exists():
                return self.process.returncode or 1  # its runner ended without a word
            time.sleep(1)
        return int(self.status.read_text())

    def stop(self):
        """Stops a build this process started, if it still runs."""
        if self.process is not None and self.process.poll() is None:
            self.process.terminate()
            self.process.wait()


def _shared_folder(tmp_path_factory):
    """A folder all the run's pytest-xdist workers share (the run's own otherwise)."""
    base = tmp_path_factory.getbasetemp()
    return base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base


def _needs_the_book(session):
    return not os.environ.get("ICM_BUILT_BOOK") and any(
        "built_book" in getattr(item, "fixturenames", ()) for item in session.items)


@pytest.fixture(scope="session", autouse=True)
def _book_built_in_the_background(request, tmp_path_factory):
    """Starts the book's build as the run starts, if any of its tests needs the book."""
    if not _needs_the_book(request.session):
        yield None
        return
    build = BookBuild(_shared_folder(tmp_path_factory))
    build.start()
    yield build
    if request.session.shouldfail or request.session.shouldstop:
        build.stop()  # the run stops early (-x, Ctrl-C): no need for the book
    elif build.process is not None:
        # Other workers may still need it: this process waits for it to end, after its
        # last test (pytest_sessionfinish), not in that test's teardown, where the wait
        # would count against the test's time limit.
        _BUILDS_TO_AWAIT.append(build)


_BUILDS_TO_AWAIT = []
"""The book's build, if this process started it and the run needs it to finish."""


@pytest.fixture(scope="session")
def built_book(_book_built_in_the_background, request):
    """The whole book, built once per run as CI builds it, with `book/_ext/build_book.py
    --force --strict`: every notebook executed afresh into this build's own cache, then
    jupyter-book build with -W (warnings fatal), which must take every notebook from
    that cache; returns the folder of the HTML.

    Built at the machine's own speed, in the background while the unit tests run:
    that the build holds on a machine made slow on purpose is tested on the slowest
    chapter (tests/test_build.py). The build's record of execution times
    is copied to `_build/` for `make bench`.

    While working on the browser checks, ICM_BUILT_BOOK=<folder of the HTML> reuses a
    book built before (CI never sets it)."""
    reuse = os.environ.get("ICM_BUILT_BOOK")
    if reuse:
        return pathlib.Path(reuse)
    build = _book_built_in_the_background
    started = time.time()
    status = build.wait()
    _BOOK_WAIT.append(time.time() - started)
    log = build.log.read_text()
    assert status == 0, "book build failed:\n" + log[-8000:]
    assert "book execution:" in log, log[-8000:]
    reporter = request.config.pluginmanager.get_plugin("terminalreporter")
    for line in log.splitlines():
        if reporter is not None and line.startswith(("executed", "book execution")):
            reporter.write_line(line)
    record = build.out / "_build" / EXECUTION_RECORD
    if record.exists():
        RECORDS.mkdir(exist_ok=True)
        shutil.copyfile(record, RECORDS / EXECUTION_RECORD)
    return build.out / "_build" / "html"


# --- notes and the record of durations ------------------------------------------------

@pytest.fixture
def note(request):
    """`note(text)`: a line for the run's summary (what a test measured, for the
    record), shown at the end of the run, also from pytest-xdist's workers."""
    return lambda text: request.node.user_properties.append(("icm-note", str(text)))


_CPU_MARK = pytest.StashKey[float]()
_BOOK_WAIT = []
"""The seconds this process's first test that needed the book waited for its build
(`built_book`), until that test's setup is reported."""
_DURATIONS = {}
_CPU = {}
_NOTES = []
_STARTED = time.time()


def _cpu_seconds():
    """CPU time used so far by this process and by the processes it has waited for."""
    import resource

    return sum(resource.getrusage(who).ru_utime + resource.getrusage(who).ru_stime
               for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    item.stash[_CPU_MARK] = _cpu_seconds()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Each phase's report carries the CPU time it used (a time that, unlike wall
    time, barely grows when the machine is busy: what the record orders by)."""
    report = (yield).get_result()
    now = _cpu_seconds()
    report.user_properties = list(report.user_properties) + [  # the item's list kept
        ("icm-cpu", now - item.stash.get(_CPU_MARK, now))]
    if _BOOK_WAIT:  # the setup in which built_book waited for the build
        report.user_properties.append(("icm-book-wait", _BOOK_WAIT.pop()))
    item.stash[_CPU_MARK] = now


def pytest_runtest_logreport(report):
    """Adds up each test's setup, call and teardown (wall and CPU time), and keeps its
    notes (on the controller, the workers' reports too). A test's wall time leaves
    out its wait for the book's build: the record orders the modules by their own
    work, and which module happened to ask for the book first is not its work."""
    waited = sum(value for key, value in report.user_properties if key == "icm-book-wait")
    _DURATIONS[report.nodeid] = _DURATIONS.get(report.nodeid, 0.0) + report.duration - waited
    _CPU[report.nodeid] = _CPU.get(report.nodeid, 0.0) + sum(
        value for key, value in report.user_properties if key == "icm-cpu")
    if report.when == "call":
        _NOTES.extend(f"{report.nodeid.split('::')[-1]}: {text}"
                      for key, text in report.user_properties if key == "icm-note")


def pytest_terminal_summary(terminalreporter):
    if _NOTES:
        terminalreporter.section("measured along the way")
        for line in _NOTES:
            terminalreporter.write_line(line)


def _whole_suite(config):
    """Whether the run is of every test (`make test`): no paths, -m or -k given."""
    return (config.args_source == pytest.Config.ArgsSource.TESTPATHS
            and not config.getoption("markexpr") and not config.getoption("keyword"))


def pytest_sessionfinish(session, exitstatus):
    """Waits for the book's build if this process started it (`_BUILDS_TO_AWAIT`), then
    writes the run's durations, slowest first, with the reference workload timed
    now (`make bench` prints the ten slowest): `_build/icm-test-durations.json`. Only
    a run of the whole suite that ran at least 100 tests writes it: a part (`make
    test-quick`, a file, --collect-only) would replace the record of the whole, which
    orders the next run's modules."""
    while _BUILDS_TO_AWAIT:
        _BUILDS_TO_AWAIT.pop().wait()
    if hasattr(session.config, "workerinput") or not _whole_suite(session.config) \
            or len(_DURATIONS) < 100:
        return
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        from reference import reference_seconds
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    durations = sorted(_DURATIONS.items(), key=lambda item: -item[1])
    record = {"finished": time.strftime("%Y-%m-%d %H:%M:%S"),
              "command": " ".join(["pytest"] + list(session.config.invocation_params.args)),
              "wall_seconds": round(time.time() - _STARTED, 1),
              "tests": len(durations), "exit_status": int(exitstatus),
              "reference_seconds": round(reference_seconds(5), 4),
              "durations": [[nodeid, round(seconds, 2), round(_CPU.get(nodeid, 0.0), 2)]
                            for nodeid, seconds in durations]}
    RECORDS.mkdir(exist_ok=True)
    temporary = DURATIONS_RECORD.with_suffix(".tmp")
    temporary.write_text(json.dumps(record, indent=0))
    os.replace(temporary, DURATIONS_RECORD)


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
"""Debian's Chromium, which the tests in a browser drive (None where it is missing)."""
CHROMIUM_FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update",
                  "--disable-sync"]
"""How they start it: offline, without its sandbox (root in CI) or a GPU."""


@contextlib.contextmanager
def chromium(extra_flags=()):
    """Headless Chromium through Playwright, for a module's `browser` fixture; skips the
    test where Playwright or Chromium is missing, saying which."""
    import pytest

    playwright_api = pytest.importorskip("playwright.sync_api",
                                         reason="Playwright is not installed (pip)")
    if CHROMIUM is None:
        pytest.skip("Chromium is not installed (Debian: apt-get install chromium)")
    with playwright_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM,
                                             args=CHROMIUM_FLAGS + list(extra_flags))
        yield browser
        browser.close()

