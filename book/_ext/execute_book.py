"""Executes the book's notebooks into the execution cache that Jupyter Book reads.

    python book/_ext/execute_book.py [--path-output DIR] [--jobs N] [--timeout S]

`make book` and the tests run this before `jupyter-book build`, whose configuration
(`execute_notebooks: cache`) then takes every notebook's outputs from the cache
instead of executing it again. Doing the execution here, not inside Sphinx, gives:

- **No silent stalls.** nbclient waits for a cell's reply with one `get_msg` of the
  whole cell timeout; a wakeup lost in zmq.asyncio's edge-triggered polling then
  leaves the build idle for that whole timeout (900 s before), after which pyzmq's
  final non-blocking poll finds the reply and everything carries on without an error.
  Here every wait on the kernel's shell and iopub channels is cut into one-second
  polls, each of which ends with that non-blocking poll, so a lost wakeup costs at
  most a second. A cell that really hangs fails after `--timeout` seconds (default
  120) with the notebook and the cell named.
- **The execution time, printed**: per notebook and in total.
- **The book's versions of the panels**: the kernels run with `ICM_STATIC_PANELS=1`,
  so `icm.widgets` panels are drawn as their static, precomputed versions, which
  move in the HTML without a kernel (in Jupyter they are the live ipywidgets panels).
- **One BLAS thread per kernel**: two notebooks run at once on the two cores, and the
  library's matrices are small; a multithreaded BLAS then spends more time waiting
  for its threads than computing (measured: 0.2 ms against 1.5-8 ms for a band's
  matrix product).
- **Quick prose-only rebuilds**: a notebook whose code cells are unchanged is taken
  from the cache, but only as long as the library is unchanged: the cache is emptied
  whenever a file of `icm/`, `assets/`, `requirements.txt` or `pyproject.toml`
  changes (a fingerprint of them is kept in the cache folder). `--force` (the tests,
  CI) executes everything.
- **Launch cells skipped**: a cell tagged `skip-execution` (each notebook's first
  cell, which installs icm on Binder or Colab) is not run, as when Jupyter Book
  executes a notebook itself; its tag `remove-cell` keeps it out of the HTML.
"""

import argparse
import asyncio
import concurrent.futures
import hashlib
import json
import os
import pathlib
import shutil
import sys
import time
from queue import Empty

import nbformat
import yaml
from jupyter_client.channels import AsyncZMQSocketChannel
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError, CellTimeoutError

ROOT = pathlib.Path(__file__).resolve().parents[2]
POLL_SECONDS = 1.0
"""The longest single wait on a kernel channel: a lost wakeup costs at most this."""
DEFAULT_TIMEOUT = 120
"""Seconds a cell may run before it fails (every cell of the book takes far less)."""
LIBRARY = ("icm", "assets", "requirements.txt", "pyproject.toml")
KERNEL_ENVIRONMENT = {"ICM_STATIC_PANELS": "1", "OPENBLAS_NUM_THREADS": "1",
                      "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
"""Set for the kernels (which inherit this process's environment): see above."""
SKIP_TAG = "skip-execution"
"""Cells with this tag are not executed (nbclient's and so Jupyter Book's convention)."""


def notebooks():
    """The book's notebooks, in table-of-contents order."""
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    files = [toc["root"]]
    for part in toc.get("parts", []):
        files += [chapter["file"] for chapter in part["chapters"]]
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


class BookClient(NotebookClient):
    """nbclient's NotebookClient, with every wait on the kernel cut into short polls
    and errors that name the notebook and the cell."""

    def __init__(self, nb, path, **kwargs):
        super().__init__(nb, on_notebook_start=self._slice_channels,
                         on_cell_execute=self._note_cell, **kwargs)
        self.path = path
        self.cell_index = None

    def _slice_channels(self, notebook, **_):
        for channel in (self.kc.shell_channel, self.kc.iopub_channel):
            assert isinstance(channel, AsyncZMQSocketChannel)
            channel.get_msg = sliced(channel.get_msg)

    def _note_cell(self, cell, cell_index, **_):
        self.cell_index = cell_index


def _name(path):
    """`path` relative to the project, if it is inside it."""
    return path.relative_to(ROOT) if ROOT in path.parents else path


class NotebookFailed(Exception):
    """A notebook's cell failed or hung; the message names the notebook and the cell."""


def execute(path, timeout):
    """Executes the notebook at `path` in its folder; returns (notebook, seconds)."""
    nb = nbformat.read(path, as_version=4)
    client = BookClient(nb, path, timeout=timeout, allow_errors=False, record_timing=False,
                        skip_cells_with_tag=SKIP_TAG,
                        resources={"metadata": {"path": str(path.parent)}})
    start = time.perf_counter()
    try:
        client.execute()
    except (CellExecutionError, CellTimeoutError) as error:
        what = "hung" if isinstance(error, CellTimeoutError) else "failed"
        cell = client.cell_index
        raise NotebookFailed(f"{_name(path)}: cell {cell} {what}"
                             f"{f' (more than {timeout} s)' if what == 'hung' else ''}:\n"
                             f"{error}") from None
    return nb, time.perf_counter() - start


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--path-output", type=pathlib.Path, default=ROOT,
                        help="as jupyter-book build --path-output: the cache is "
                             "<path-output>/_build/.jupyter_cache (default: the project)")
    parser.add_argument("--jobs", type=int, default=2, help="notebooks at once (default 2)")
    parser.add_argument("--timeout", type=int, default=DEFAULT_TIMEOUT,
                        help=f"seconds a cell may run (default {DEFAULT_TIMEOUT})")
    parser.add_argument("--force", action="store_true",
                        help="execute every notebook, whatever the cache holds")
    parser.add_argument("notebooks", nargs="*", type=pathlib.Path,
                        help="notebooks to execute (default: every one of the book)")
    args = parser.parse_args(argv)
    if args.jobs < 1 or args.timeout < 1:
        parser.error("--jobs and --timeout must be >= 1")

    from jupyter_cache import get_cache
    from jupyter_cache.base import CacheBundleIn

    cache_path = args.path_output.resolve() / "_build" / ".jupyter_cache"
    fingerprint = library_fingerprint()
    stamp = cache_path / "icm-library-fingerprint"
    if args.force or not stamp.exists() or stamp.read_text() != fingerprint:
        shutil.rmtree(cache_path, ignore_errors=True)
    cache_path.mkdir(parents=True, exist_ok=True)
    cache = get_cache(str(cache_path))

    todo, cached = [], []
    for path in ([p.resolve() for p in args.notebooks] or notebooks()):
        try:
            cache.match_cache_notebook(nbformat.read(path, as_version=4))
            cached.append(path)
        except KeyError:
            todo.append(path)
    for path in cached:
        print(f"cached   {_name(path)} (library and code cells unchanged)")
    if not todo:
        print("book execution: every notebook from the cache (nothing changed)")
        return 0

    # Longest first (the times of the last run, kept beside the cache): with two at a
    # time, a long notebook started last would finish alone.
    times_path = cache_path.parent / "icm-notebook-seconds.json"
    times = json.loads(times_path.read_text()) if times_path.exists() else {}
    todo.sort(key=lambda path: -times.get(str(_name(path)), float("inf")))
    os.environ.update(KERNEL_ENVIRONMENT)
    total, failures, start = 0.0, [], time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(execute, path, args.timeout): path for path in todo}
        for future in concurrent.futures.as_completed(futures):
            path = futures[future]
            try:
                nb, seconds = future.result()
            except NotebookFailed as error:
                failures.append(str(error))
                print(f"FAILED   {error}", file=sys.stderr)
                continue
            total += seconds
            times[str(_name(path))] = round(seconds, 1)
            cache.cache_notebook_bundle(
                CacheBundleIn(nb, str(path), data={"execution_seconds": seconds}),
                check_validity=False, overwrite=True)
            print(f"executed {_name(path)} in {seconds:.1f} s", flush=True)
    wall = time.perf_counter() - start
    print(f"book execution: {len(todo) - len(failures)} notebooks executed in {total:.1f} s "
          f"(sum over notebooks; {wall:.1f} s wall, {args.jobs} at a time), "
          f"{len(cached)} from the cache")
    times_path.write_text(json.dumps(times, indent=1, sort_keys=True))
    if failures:
        return 1
    stamp.write_text(fingerprint)
    return 0


if __name__ == "__main__":
    sys.exit(main())
