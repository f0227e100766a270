"""Executes the book's notebooks into the execution cache that Jupyter Book reads.

    python book/_ext/execute_book.py [--path-output DIR] [--jobs N] [--stall S]
                                     [--cpu-limit S] [--force] [--keep-going] [NOTEBOOK ...]

`book/_ext/build_book.py` (which `make book` and the tests call) runs this before
`jupyter-book build`, whose configuration (`execute_notebooks: cache`) then takes every
notebook's outputs from the cache instead of executing it again. Doing the execution
here, not inside Sphinx, gives:

- **Slow is not hung.** No wall-clock limit ever fails a cell: a 2-core laptop that is
  also doing other work, a Binder fraction of a core or a shared CI runner may take
  many times longer than a quiet machine, and that is not an error. A cell fails only
  on evidence that it will never finish:

  * *stalled*: for `--stall` seconds (default 60) the kernel sent no output and its
    processes (the kernel and every process it started) used less than
    `PROGRESS_CPU_SECONDS` (0.5 s) of CPU time together. A kernel that computes, even
    on 1% of a core, uses more; a kernel that waits for something that never comes
    (a sleep, a lock, a reply that was lost) uses almost none (measured: about 0.01 s
    a minute for an idle kernel);
  * *runaway*: the cell has used more than `--cpu-limit` CPU-seconds (default 1800,
    50 times the slowest cell of the book): CPU time, unlike wall time, does not grow
    when the machine is busy.

  Either failure names the notebook and the cell and shows the cell's code. The
  evidence is read once a second (`CHECK_SECONDS`) with psutil.
- **No silent stalls in the client.** nbclient waits for a cell's reply with one
  `get_msg` of the whole cell timeout; a wakeup lost in zmq.asyncio's edge-triggered
  polling would leave it waiting for that whole timeout. Here every wait on the
  kernel's shell and iopub channels is cut into one-second polls, each of which ends
  with a non-blocking poll, so a lost wakeup costs at most a second.
- **No output lost.** After a cell's reply, nbclient waits only 4 s (`iopub_timeout`)
  for the cell's remaining outputs, then drops them with a warning nobody sees: on a
  busy machine a cell that glues many numbers lost its last ones, and the strict
  build failed on the missing keys (seen here at a load of 15 on 2 cores). Here the
  client waits for every output, however slow; the stall rule still fails a kernel
  that sends nothing and computes nothing.
- **Fail fast, stop at once.** The first notebook that fails stops the others (their
  kernels are shut down within about a second) unless `--keep-going` is given; so does
  Ctrl-C. Notebooks that finished before are kept in the cache: the next run executes
  only the rest.
- **A cache that repairs itself.** The cache is emptied whenever a file of `icm/`,
  `assets/`, `requirements.txt` or `pyproject.toml` changes (a fingerprint of them is
  kept in the cache folder, written before anything is executed, so that an
  interrupted run keeps what it cached). A damaged cache database, a damaged cached
  notebook or a damaged record of times is reported in one line and repaired (the
  cache emptied, the notebook executed again, the times forgotten). `--force` (the
  tests, CI) executes everything.
- **The execution time, printed and recorded**: per notebook and in total; the times
  of the last run order the next one, longest first (with two at a time, a long
  notebook started last would finish alone). Each run that executes notebooks also
  writes `_build/icm-execution-record.json`: per notebook its wall and CPU seconds
  and those of each cell (the kernel with its children), and the reference workload
  of `benchmarks/reference.py` timed before and after, which `make bench` reports.
- **The book's versions of the panels**: the kernels run with `ICM_STATIC_PANELS=1`,
  so `icm.widgets` panels are drawn as their static, precomputed versions, which move
  in the HTML without a kernel (in Jupyter they are the live ipywidgets panels).
- **Progress on the terminal, not in the page**: the kernels run with
  `ICM_BOOK_BUILD=1`, so the library's progress bars (`icm/experiments/progress.py`)
  write to the kernel's original standard error, `sys.__stderr__`; and they are
  started with ipykernel's `capture_fd_output` off, so that this standard error is the
  terminal of whoever builds (by default ipykernel redirects it into the cell's
  outputs). The outputs of the book's cells hold what the cells show, never progress.
- **One BLAS thread per kernel**: two notebooks run at once on the two cores, and the
  library's matrices are small; a multithreaded BLAS then spends more time waiting for
  its threads than computing (measured: 0.2 ms against 1.5-8 ms for a band's matrix
  product).
- **Kernels on local sockets.** The kernels talk to this process over IPC sockets in a
  private temporary folder, not over TCP on localhost (ipykernel warns about
  unencrypted TCP, rightly: any local user could connect to a TCP port).
- **Launch cells skipped**: a cell tagged `skip-execution` (each notebook's first cell,
  which installs icm on Binder or Colab) is not run, as when Jupyter Book executes a
  notebook itself; its tag `remove-cell` keeps it out of the HTML.

Exit status: 0 when every notebook executed (or came from the cache), 1 when one
failed, 130 when interrupted.
"""

import argparse
import asyncio
import concurrent.futures
import hashlib
import json
import os
import pathlib
import shutil
import sqlite3
import signal
import sys
import tempfile
import threading
import time
from queue import Empty

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _shared_with_the_library():
    """icm/_book.py (`STATIC_ENV`, `toc_pages`, `SKIP_SLOW_IMPORT`), loaded from its
    file rather than imported: this executor also runs where icm is not installed yet
    (a fresh launch installs it from the notebook's first cell), and that module needs
    nothing of icm."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("icm_book_shared",
                                                  ROOT / "icm" / "_book.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_shared = _shared_with_the_library()
STATIC_ENV, toc_pages = _shared.STATIC_ENV, _shared.toc_pages
exec(_shared.SKIP_SLOW_IMPORT)  # before nbformat imports jsonschema

import nbformat  # noqa: E402
import psutil  # noqa: E402
from jupyter_client.channels import AsyncZMQSocketChannel  # noqa: E402
from jupyter_client.manager import AsyncKernelManager  # noqa: E402
from nbclient import NotebookClient  # noqa: E402
from nbclient.exceptions import CellExecutionError, DeadKernelError  # noqa: E402

POLL_SECONDS = 1.0
"""The longest single wait on a kernel channel: a lost wakeup costs at most this."""
CHECK_SECONDS = 1.0
"""How often the kernel's progress is read."""
DEFAULT_STALL_SECONDS = 60
"""Seconds without output and without CPU progress after which a cell has stalled."""
PROGRESS_CPU_SECONDS = 0.5
"""CPU time (s) the kernel's processes must use, within a stall period, to count as
computing."""
DEFAULT_CPU_LIMIT = 1800
"""CPU-seconds a single cell may use (the slowest cell of the book uses about 40)."""
LIBRARY = ("icm", "assets", "requirements.txt", "pyproject.toml")
KERNEL_ENVIRONMENT = {STATIC_ENV: "1", "ICM_BOOK_BUILD": "1",
                      "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1",
                      "MKL_NUM_THREADS": "1"}
"""Set for the kernels (which inherit this process's environment): see above."""
IOPUB_WAIT_SECONDS = 10 ** 9
"""How long to wait for a cell's outputs after its reply: in effect for ever (see "No
output lost"); the stall rule ends a wait for a kernel that is gone."""
KERNEL_ARGUMENTS = ["--IPKernelApp.capture_fd_output=False",
                    f"--IPKernelApp.exec_lines={_shared.SKIP_SLOW_IMPORT}"]
"""The kernels' standard error stays this process's (see "Progress on the terminal"),
and each runs `icm._book.SKIP_SLOW_IMPORT` as it starts (IPython's exec_lines: not a
cell, not in the executed notebook)."""
SKIP_TAG = "skip-execution"
"""Cells with this tag are not executed (nbclient's and so Jupyter Book's convention)."""
FINGERPRINT_FILE = "icm-library-fingerprint"
EXECUTED = []
"""The notebooks `main` executed (not taken from the cache) in this process: their
pages must be read again by Sphinx (build_book.py), whose own record of what changed
knows only the notebooks' sources."""
TIMES_FILE = "icm-notebook-seconds.json"
RECORD_FILE = "icm-execution-record.json"
"""Beside TIMES_FILE: the last run's times per notebook and per cell (`main`)."""
CELL_TIMES = {}
"""{notebook path: [(cell index, wall seconds, CPU seconds), ...]}, per executed cell,
filled by `execute` in this process."""


def notebooks():
    """The book's notebooks, in table-of-contents order."""
    files = toc_pages(ROOT)
    return [ROOT / f"{name}.ipynb" for name in files if (ROOT / f"{name}.ipynb").exists()]


def library_fingerprint():
    """A hash of every file the notebooks' results depend on, besides the notebooks."""
    digest = hashlib.sha256()
    for entry in LIBRARY:
        path = ROOT / entry
        files = sorted(p for p in path.rglob("*") if p.is_file() and "__pycache__" not in p.parts) \
            if path.is_dir() else [path]
        for file in files:
            digest.update(str(file.relative_to(ROOT)).encode())
            digest.update(file.read_bytes())
    return digest.hexdigest()


def sliced(get_msg):
    """Wraps a channel's `get_msg(timeout)` so that it waits in polls of at most
    `POLL_SECONDS`: pyzmq ends each timed-out poll with a non-blocking one, which finds
    a message whose wakeup was lost. The overall timeout is kept."""
    async def get_msg_sliced(timeout=None):
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            remaining = None if deadline is None else max(0.0, deadline - time.monotonic())
            try:
                return await get_msg(timeout=POLL_SECONDS if remaining is None
                                     else min(POLL_SECONDS, remaining))
            except (Empty, asyncio.TimeoutError):  # nothing within this poll
                if remaining is not None and remaining <= POLL_SECONDS:
                    raise Empty from None
    return get_msg_sliced


def cpu_seconds(process):
    """CPU time (user + system, s) used so far by `process` (a psutil.Process) and by
    every process it started that is still running; 0 once it is gone."""
    total = 0.0
    try:
        family = [process] + process.children(recursive=True)
    except psutil.Error:
        return total
    for member in family:
        try:
            times = member.cpu_times()
        except psutil.Error:  # ended in between
            continue
        total += times.user + times.system
    return total


class CellStalled(Exception):
    """A cell made no progress (see the module docstring); the message says why."""


class Stopped(Exception):
    """The run was stopped (Ctrl-C, or another notebook failed) while this one ran."""


class BookClient(NotebookClient):
    """nbclient's NotebookClient, with every wait on the kernel cut into short polls, a
    watchdog that fails a cell only on evidence that it will never finish, and a stop
    signal shared with the other notebooks of the run."""

    def __init__(self, nb, path, stop, stall_seconds, cpu_limit, socket_folder, **kwargs):
        km = AsyncKernelManager(kernel_name=nb.metadata.get("kernelspec", {}).get(
            "name", "python3"), transport="ipc", ip=str(socket_folder / "kernel"))
        # Every kernel is killed at the end, never asked to shut down: a finished
        # notebook's kernel has nothing left to do, and one asked to shut down
        # (ipykernel 7.4) may still run a handler that sends on a socket it has just
        # closed, which tornado then logs as "Uncaught exception in ZMQStream
        # callback ... ZMQError: Socket operation on non-socket" (seen here once in
        # about a hundred builds of a one-cell notebook, which still succeeded). A
        # kernel that stalls or runs away is killed too (async_execute_cell).
        super().__init__(nb, km=km, on_notebook_start=self._slice_channels,
                         on_cell_execute=self._note_cell, shutdown_kernel="immediate",
                         **kwargs)
        self.path = path
        self.cell_index = None
        self.stop = stop
        self.stall_seconds = stall_seconds
        self.cpu_limit = cpu_limit
        self._last_output = time.monotonic()
        self.cell_times = []  # (cell index, wall seconds, CPU seconds) per executed cell

    def _slice_channels(self, notebook, **_):
        for channel in (self.kc.shell_channel, self.kc.iopub_channel):
            assert isinstance(channel, AsyncZMQSocketChannel)
            channel.get_msg = sliced(channel.get_msg)

    def _note_cell(self, cell, cell_index, **_):
        self.cell_index = cell_index

    def process_message(self, msg, cell, cell_index):
        self._last_output = time.monotonic()  # any message of the cell is activity
        return super().process_message(msg, cell, cell_index)

    def _kernel_process(self):
        provisioner = getattr(self.km, "provisioner", None)
        pid = getattr(getattr(provisioner, "process", None), "pid", None)
        try:
            return psutil.Process(pid) if pid else None
        except psutil.Error:
            return None

    async def async_execute_cell(self, cell, cell_index, execution_count=None,
                                 store_history=True):
        if self.stop.is_set():
            raise Stopped()
        process = self._kernel_process()
        task = asyncio.ensure_future(super().async_execute_cell(
            cell, cell_index, execution_count=execution_count, store_history=store_history))
        start_cpu = mark_cpu = cpu_seconds(process) if process else 0.0
        start_time = mark_time = self._last_output = time.monotonic()
        while True:
            done, _ = await asyncio.wait({task}, timeout=CHECK_SECONDS)
            if task in done:
                self.cell_times.append((cell_index, time.monotonic() - start_time,
                                        (cpu_seconds(process) if process else 0.0) - start_cpu))
                return task.result()
            problem = None
            now, used = time.monotonic(), cpu_seconds(process) if process else 0.0
            if self.stop.is_set():
                problem = Stopped()
            elif used - start_cpu > self.cpu_limit:
                problem = CellStalled(f"ran away (more than {self.cpu_limit:g} CPU-seconds)")
            else:
                if used - mark_cpu >= PROGRESS_CPU_SECONDS or self._last_output > mark_time:
                    mark_cpu, mark_time = used, now  # progress: the kernel computes or talks
                elif now - mark_time > self.stall_seconds:
                    problem = CellStalled(
                        f"stalled (no output and {used - mark_cpu:.2f} s of CPU in the last "
                        f"{now - mark_time:.0f} s: the kernel is waiting, not computing)")
            if problem is not None:
                # Killed (shutdown_kernel is "immediate"), not asked to shut down: a
                # kernel asked while it computes closes its sockets under the running
                # cell, which then fails to send its reply (ZMQError: Socket operation
                # on non-socket, in the log).
                # The cell's task and nbclient's pollers of this notebook's loop.
                for other in asyncio.all_tasks():
                    if other is not asyncio.current_task():
                        other.cancel()
                try:
                    await task
                except BaseException:  # the cancellation, or the cell's own end
                    pass
                raise problem


def _name(path):
    """`path` relative to the project, if it is inside it."""
    return path.relative_to(ROOT) if ROOT in path.parents else path


class NotebookFailed(Exception):
    """A notebook's cell failed or stalled; the message names the notebook and the cell."""


def _code_of(nb, index):
    if index is None or index >= len(nb.cells):
        return ""
    lines = nb.cells[index].source.splitlines()
    shown = "\n".join(f"    {line}" for line in lines[:12])
    return shown + ("\n    ..." if len(lines) > 12 else "")


def execute(path, stop, stall_seconds=DEFAULT_STALL_SECONDS, cpu_limit=DEFAULT_CPU_LIMIT):
    """Executes the notebook at `path` in its folder; returns (notebook, seconds).

    Raises:
      NotebookFailed: a cell raised, stalled or ran away (the message names the
        notebook and the cell, and shows the cell's code).
      Stopped: `stop` (a threading.Event) was set while the notebook ran.
    """
    nb = nbformat.read(path, as_version=4)
    with tempfile.TemporaryDirectory(prefix="icm-kernel-") as sockets:
        client = BookClient(nb, path, stop, stall_seconds, cpu_limit, pathlib.Path(sockets),
                            timeout=None, allow_errors=False, record_timing=False,
                            iopub_timeout=IOPUB_WAIT_SECONDS, raise_on_iopub_timeout=True,
                            skip_cells_with_tag=SKIP_TAG, extra_arguments=KERNEL_ARGUMENTS,
                            resources={"metadata": {"path": str(path.parent)}})
        start = time.perf_counter()
        try:
            client.execute(cleanup_kc=True)  # the kernel manager is ours: shut it down
        except Stopped:
            raise
        except (CellExecutionError, CellStalled, DeadKernelError) as error:
            if stop.is_set():
                raise Stopped() from None
            where = f"{_name(path)}: cell {client.cell_index}"
            if isinstance(error, CellExecutionError):  # its message shows the cell
                raise NotebookFailed(f"{where} failed:\n{error}") from None
            what = "lost its kernel" if isinstance(error, DeadKernelError) else str(error)
            raise NotebookFailed(f"{where} {what}:\n{_code_of(nb, client.cell_index)}") from None
        finally:
            CELL_TIMES[path] = client.cell_times
    return nb, time.perf_counter() - start


class ExecutionCache:
    """The jupyter-cache folder, opened so that damage is repaired, not repeated:
    a database that cannot be read is emptied, a cached notebook that cannot be read
    is dropped (and executed again), and the record of times is forgotten if damaged."""

    def __init__(self, folder, fingerprint, force):
        self.folder = folder
        self.fingerprint = fingerprint
        stamp = folder / FINGERPRINT_FILE
        try:
            same = stamp.read_text() == fingerprint
        except OSError:
            same = False
        if force or not same:
            shutil.rmtree(folder, ignore_errors=True)
        self.cache = self._open()

    def _open(self):
        from jupyter_cache import get_cache

        self.folder.mkdir(parents=True, exist_ok=True)
        cache = get_cache(str(self.folder))
        try:
            cache.list_cache_records()  # reads the database: fails here if damaged
        except _DATABASE_ERRORS as error:
            print(f"repair   the execution cache's database was damaged "
                  f"({_first_line(error)}); emptied it, every notebook runs again",
                  file=sys.stderr)
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder.mkdir(parents=True)
            cache = get_cache(str(self.folder))
        # Written before anything runs: what this run caches belongs to this library.
        _write_atomic(self.folder / FINGERPRINT_FILE, self.fingerprint)
        return cache

    def is_cached(self, path):
        """True if the cache holds a readable executed copy of the notebook at `path`
        (a damaged copy is removed, with a note)."""
        nb = nbformat.read(path, as_version=4)
        try:
            record = self.cache.match_cache_notebook(nb)
        except KeyError:
            return False
        try:
            self.cache.get_cache_bundle(record.pk)
            return True
        except (KeyError, ValueError, OSError) as error:  # NotJSONError is a ValueError
            print(f"repair   the cached copy of {_name(path)} was damaged "
                  f"({_first_line(error)}); it runs again", file=sys.stderr)
            try:
                self.cache.remove_cache(record.pk)
            except (KeyError, OSError):
                from jupyter_cache.cache.db import NbCacheRecord

                NbCacheRecord.remove_records([record.pk], self.cache.db)
            return False

    def store(self, path, nb, seconds):
        from jupyter_cache.base import CacheBundleIn

        self.cache.cache_notebook_bundle(
            CacheBundleIn(nb, str(path), data={"execution_seconds": seconds}),
            check_validity=False, overwrite=True)


def _database_errors():
    from sqlalchemy.exc import SQLAlchemyError

    return (SQLAlchemyError, sqlite3.DatabaseError)


_DATABASE_ERRORS = _database_errors()


def _first_line(error):
    text = str(error).strip().splitlines()
    return f"{type(error).__name__}: {text[0] if text else ''}"[:160]


def _write_atomic(path, text):
    temporary = path.with_name(path.name + f".{os.getpid()}.tmp")
    temporary.write_text(text)
    os.replace(temporary, path)


def read_times(path):
    """The execution times of the last run ({notebook: seconds}); {} if there are
    none or the file is damaged (with a note)."""
    try:
        times = json.loads(path.read_text())
        if not isinstance(times, dict):
            raise ValueError("not a JSON object")
        return {str(k): float(v) for k, v in times.items()}
    except FileNotFoundError:
        return {}
    except (ValueError, TypeError, OSError) as error:
        print(f"repair   {path.name} was damaged ({_first_line(error)}); the notebooks "
              f"run in table-of-contents order this time", file=sys.stderr)
        return {}


def _reference_seconds():
    """The reference workload of benchmarks/reference.py, best of 5 (s), or None where
    the benchmarks are not beside the book."""
    import importlib.util

    path = ROOT / "benchmarks" / "reference.py"
    if not path.exists():
        return None
    spec = importlib.util.spec_from_file_location("icm_reference", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return round(module.reference_seconds(5), 4)


def _record(executed, times, jobs, wall, references):
    """The record of a run's times (RECORD_FILE): when, the reference workload before
    and after, and per notebook executed its seconds, CPU seconds and cells (index,
    seconds, CPU seconds, the first line of its code), in table-of-contents order."""
    notebooks = {}
    for path in executed:
        nb = nbformat.read(path, as_version=4)
        cells = CELL_TIMES.get(path, [])
        notebooks[str(_name(path))] = {
            "seconds": times[str(_name(path))],
            "cpu_seconds": round(sum(cpu for _, _, cpu in cells), 1),
            "cells": [[index, round(seconds, 2), round(cpu, 2),
                       (nb.cells[index].source.strip().splitlines() or [""])[0][:80]]
                      for index, seconds, cpu in cells]}
    return {"finished": time.strftime("%Y-%m-%d %H:%M:%S"), "jobs": jobs,
            "wall_seconds": round(wall, 1),
            "reference_seconds": {"before": references[0], "after": references[1]},
            "notebooks": notebooks}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--path-output", type=pathlib.Path, default=ROOT,
                        help="as jupyter-book build --path-output: the cache is "
                             "<path-output>/_build/.jupyter_cache (default: the project)")
    parser.add_argument("--jobs", type=int, default=2, help="notebooks at once (default 2)")
    parser.add_argument("--stall", type=float, default=DEFAULT_STALL_SECONDS,
                        help="seconds without output or CPU progress after which a cell "
                             f"has stalled (default {DEFAULT_STALL_SECONDS})")
    parser.add_argument("--cpu-limit", type=float, default=DEFAULT_CPU_LIMIT,
                        help=f"CPU-seconds a cell may use (default {DEFAULT_CPU_LIMIT})")
    parser.add_argument("--force", action="store_true",
                        help="execute every notebook, whatever the cache holds")
    parser.add_argument("--keep-going", action="store_true",
                        help="after a notebook fails, execute the others anyway")
    parser.add_argument("notebooks", nargs="*", type=pathlib.Path,
                        help="notebooks to execute (default: every one of the book)")
    args = parser.parse_args(argv)
    if args.jobs < 1 or args.stall <= 0 or args.cpu_limit <= 0:
        parser.error("--jobs must be >= 1, --stall and --cpu-limit > 0")
    # Ctrl-C stops the build at once, even when it was started with SIGINT ignored (a
    # background job of a shell without job control inherits that, and Python then
    # leaves it ignored): a run started so would otherwise finish every notebook.
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.default_int_handler)

    cache_path = args.path_output.resolve() / "_build" / ".jupyter_cache"
    cache = ExecutionCache(cache_path, library_fingerprint(), args.force)
    todo, cached = [], []
    for path in ([p.resolve() for p in args.notebooks] or notebooks()):
        (cached if cache.is_cached(path) else todo).append(path)
    for path in cached:
        print(f"cached   {_name(path)} (library and code cells unchanged)")
    if not todo:
        print("book execution: every notebook from the cache (nothing changed)")
        return 0

    times_path = cache_path.parent / TIMES_FILE
    times = read_times(times_path)
    reference_before = _reference_seconds()
    todo.sort(key=lambda path: -times.get(str(_name(path)), float("inf")))
    os.environ.update(KERNEL_ENVIRONMENT)
    stop = threading.Event()
    total, done, failures, start = 0.0, 0, [], time.perf_counter()
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs)
    futures = {pool.submit(execute, path, stop, args.stall, args.cpu_limit): path
               for path in todo}
    interrupted = False
    try:
        for future in concurrent.futures.as_completed(futures):
            path = futures[future]
            try:
                nb, seconds = future.result()
            except Stopped:
                continue
            except NotebookFailed as error:
                failures.append(str(error))
                print(f"FAILED   {error}", file=sys.stderr, flush=True)
                if not args.keep_going and not stop.is_set():
                    stop.set()
                    print("stopping the other notebooks (--keep-going runs them anyway)",
                          file=sys.stderr, flush=True)
                continue
            total += seconds
            done += 1
            times[str(_name(path))] = round(seconds, 1)
            cache.store(path, nb, seconds)
            EXECUTED.append(path)
            print(f"executed {_name(path)} in {seconds:.1f} s", flush=True)
    except KeyboardInterrupt:
        interrupted = True
        stop.set()
        print("\ninterrupted: stopping the kernels ...", file=sys.stderr, flush=True)
    finally:
        for future in futures:
            future.cancel()
        pool.shutdown(wait=True)
    wall = time.perf_counter() - start
    _write_atomic(times_path, json.dumps(times, indent=1, sort_keys=True))
    if done:
        _write_atomic(cache_path.parent / RECORD_FILE, json.dumps(_record(
            [path for path in todo if path in EXECUTED], times, args.jobs, wall,
            (reference_before, _reference_seconds())), indent=1))
    print(f"book execution: {done} of {len(todo)} notebooks executed in {total:.1f} s "
          f"(sum over notebooks; {wall:.1f} s wall, {args.jobs} at a time), "
          f"{len(cached)} from the cache")
    if library_fingerprint() != cache.fingerprint:  # the library changed meanwhile
        (cache_path / FINGERPRINT_FILE).unlink(missing_ok=True)
    if interrupted:
        print(f"interrupted: {done} notebooks executed and kept in the cache; the next "
              f"run executes only the other {len(todo) - done}", file=sys.stderr)
        return 130
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
