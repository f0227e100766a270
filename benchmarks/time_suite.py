"""Times a command (a test suite: `make test-quick`'s pytest, say) with the reference
workload (benchmarks/reference.py) timed just before and just after it, and appends one
JSON line to a record: the machine's speed varies from hour to hour, so two suites are
compared by their ratios to the workload timed beside each, not by their seconds.

    python benchmarks/time_suite.py --label after --record times.jsonl -- \\
        .venv/bin/python -m pytest -n auto --dist loadscope --no-loadscope-reorder \\
        -m "not book and not browser and not launch and not slow"

`--cwd` runs the command in another folder (a copy of the project at an earlier commit,
say: `python -m pytest` puts its folder first on the path, so it tests that copy's
package).
"""

import argparse
import json
import pathlib
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from reference import reference_seconds  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--label", required=True, help="what was timed (e.g. before, after)")
    parser.add_argument("--record", type=pathlib.Path, required=True,
                        help="the JSON-lines file the timing is appended to")
    parser.add_argument("--cwd", type=pathlib.Path, default=None)
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args(argv)
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("give the command to time after --")
    before = reference_seconds()
    start = time.perf_counter()
    status = subprocess.run(command, cwd=args.cwd).returncode
    wall = time.perf_counter() - start
    after = reference_seconds()
    row = {"label": args.label, "started": time.strftime("%Y-%m-%dT%H:%M:%S"),
           "command": command, "cwd": str(args.cwd or "."), "status": status,
           "wall_seconds": round(wall, 1), "reference_before": round(before, 4),
           "reference_after": round(after, 4),
           "ratio": round(wall / ((before + after) / 2), 1)}
    with open(args.record, "a", encoding="utf-8") as file:
        file.write(json.dumps(row) + "\n")
    print(json.dumps(row))
    return status


if __name__ == "__main__":
    sys.exit(main())
