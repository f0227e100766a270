"""Builds the book: executes the notebooks (`execute_book.py`), then runs Jupyter Book.

    python book/_ext/build_book.py [--path-output DIR] [--strict] [--force]
                                   [--keep-going] [--stall S] [--cpu-limit S]

`make book` runs it as it is; the tests and CI run it with `--force --strict`
(everything executed afresh, every warning fatal). What it adds to the two steps:

- **One build at a time in a folder.** A second build of the same folder waits for
  the first (and says so) instead of deleting the cache the first one has open. The
  lock is `<path-output>/_build/.icm-build.lock`; it is released when the process
  ends, however it ends.
- **A way out when the build fails.** If Jupyter Book fails after the notebooks were
  executed, the last line says what to do.
- **The build never executes a notebook itself**: every notebook's outputs come from
  the execution cache; a log that says otherwise fails the build.
- **Pages as fresh as their outputs.** Sphinx reads a page again only when its source
  changed; a notebook executed again (the library changed) has new outputs under the
  same source, so after any execution every page is written anew (`--all`).

Exit status: that of the first step that failed, 130 when interrupted.
"""

import argparse
import contextlib
import os
import pathlib
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

import execute_book  # noqa: E402 (beside this file)

ROOT = execute_book.ROOT
LOCK_FILE = ".icm-build.lock"


@contextlib.contextmanager
def build_lock(folder):
    """Holds an exclusive lock on `folder`/LOCK_FILE, waiting (and saying so) while
    another build holds it. Without fcntl (Windows) builds are not serialised."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover (not POSIX)
        yield
        return
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / LOCK_FILE
    with open(path, "a+") as handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.seek(0)
            holder = handle.read().strip() or "another process"
            print(f"waiting: another build of the book is running in {folder} ({holder}); "
                  f"this one starts when it ends", file=sys.stderr, flush=True)
            fcntl.flock(handle, fcntl.LOCK_EX)
        handle.seek(0)
        handle.truncate()
        handle.write(f"pid {os.getpid()}, since {time.strftime('%H:%M:%S')}")
        handle.flush()
        try:
            yield
        finally:
            handle.seek(0)
            handle.truncate()
            fcntl.flock(handle, fcntl.LOCK_UN)


JUPYTER_BOOK = (f"{execute_book._shared.SKIP_SLOW_IMPORT}\n"
                "from jupyter_book.cli.main import main\n"
                "main(prog_name='jupyter-book')")
"""The `jupyter-book` command, run by this Python after icm._book.SKIP_SLOW_IMPORT
(myst-nb imports nbformat, and so jsonschema: 1.5 s of CPU spared per build)."""


def jupyter_book(output, strict, everything=False):
    """Runs `jupyter-book build` (`everything`: every page read and written again),
    echoing its log; returns (status, log)."""
    command = [sys.executable, "-c", JUPYTER_BOOK, "build", str(ROOT),
               "--keep-going", "--path-output", str(output)] + (["-W"] if strict else []) \
        + (["--all"] if everything else [])
    process = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
    lines = []
    for line in process.stdout:
        lines.append(line)
        print(line, end="", flush=True)
    return process.wait(), "".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--path-output", type=pathlib.Path, default=ROOT,
                        help="where _build goes (default: the project)")
    parser.add_argument("--strict", action="store_true",
                        help="every Sphinx warning is an error (-W), as in the tests and CI")
    parser.add_argument("--force", action="store_true",
                        help="execute every notebook, whatever the cache holds")
    parser.add_argument("--keep-going", action="store_true",
                        help="after a notebook fails, execute the others anyway")
    parser.add_argument("--stall", type=float, default=execute_book.DEFAULT_STALL_SECONDS,
                        help="see execute_book.py")
    parser.add_argument("--cpu-limit", type=float, default=execute_book.DEFAULT_CPU_LIMIT,
                        help="see execute_book.py")
    args = parser.parse_args(argv)
    output = args.path_output.resolve()
    try:
        with build_lock(output / "_build"):
            executed = execute_book.main(
                ["--path-output", str(output), "--stall", str(args.stall),
                 "--cpu-limit", str(args.cpu_limit)]
                + ["--force"] * args.force + ["--keep-going"] * args.keep_going)
            if executed:
                return executed
            status, log = jupyter_book(output, args.strict, bool(execute_book.EXECUTED))
    except KeyboardInterrupt:
        print("\ninterrupted", file=sys.stderr)
        return 130
    if "Executing notebook" in log:
        print("build_book: Jupyter Book executed a notebook itself; the execution cache "
              "missed it (a bug: please report it)", file=sys.stderr)
        return 1
    if status:
        warnings = [line for line in log.splitlines() if "WARNING" in line or "ERROR" in line]
        if warnings:
            print("build_book: the warnings and errors of the build:\n  "
                  + "\n  ".join(warnings), file=sys.stderr)
        print("build_book: the book did not build (see the log above). If it mentions the "
              "execution cache or a notebook it cannot read, `make clean` empties _build "
              "and the next build starts afresh.", file=sys.stderr)
        return status
    print(f"Open the book: {output / '_build' / 'html' / 'index.html'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
