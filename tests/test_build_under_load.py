"""The book's build holds on a machine made slow on purpose: its slowest chapter,
executed by `book/_ext/execute_book.py` while a CPU burner runs on every core, as a
student's laptop doing other work, a Binder fraction of a core or a shared CI runner
would run it. (The whole book is built once per run at the machine's own speed,
`conftest.built_book`; the rule that keeps a slow cell from being failed as hung is
tested on small notebooks in tests/test_build.py.)"""

import json
import subprocess
import sys
import time

from conftest import EXECUTE_BOOK, EXECUTION_RECORD, RECORDS, ROOT, cpu_burners

SLOWEST_CHAPTER = "book/simulated_icub.ipynb"
"""The chapter whose execution takes the most CPU time, when no build has left a record
of times here yet (a fresh clone, CI): 24.7 of the book's 103 CPU-seconds in a build of
2026-12-02 on an idle machine (the reference workload 0.020 s), since the panels' grids
are read from assets/ (rod_toppling.ipynb, the slowest before, 13.8 CPU-seconds now;
issue 30)."""


def slowest_chapter():
    """The chapter that used the most CPU time in the last build's record
    (`_build/icm-execution-record.json`), else `SLOWEST_CHAPTER`."""
    try:
        notebooks = json.loads((RECORDS / EXECUTION_RECORD).read_text())["notebooks"]
        name = max(notebooks, key=lambda name: notebooks[name]["cpu_seconds"])
    except (OSError, ValueError, KeyError, TypeError):
        return SLOWEST_CHAPTER
    return name if (ROOT / name).exists() else SLOWEST_CHAPTER


def test_the_slowest_chapter_executes_on_a_machine_made_slow(tmp_path, note):
    chapter = slowest_chapter()
    start = time.monotonic()
    with cpu_burners() as burning:
        completed = subprocess.run(
            [sys.executable, str(EXECUTE_BOOK), "--path-output", str(tmp_path), "--force",
             str(ROOT / chapter)], capture_output=True, text=True, cwd=ROOT)
    assert completed.returncode == 0, completed.stderr[-8000:]
    assert f"executed {chapter} in" in completed.stdout, completed.stdout
    assert "1 of 1 notebooks executed" in completed.stdout
    note(f"{chapter} executed with {burning} CPU burners running in "
         f"{time.monotonic() - start:.0f} s")
