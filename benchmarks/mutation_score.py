"""The mutation score of `make mutants`: the share of mutants that made a test fail.

    python benchmarks/mutation_score.py [--least 0.9]

Reads mutmut's results (run `mutmut run` first; `make mutants` does both), prints how
many mutants each status counts and each mutant that lived, with the line it changed,
grouped by function. A mutant counts as killed when a test failed on it or it ran past
mutmut's time limit (an endless loop is caught); one that no selected test reaches ("no
tests") lives, like one that passed every test. Exit status 1 when the killed share is
below --least (default 0.9), 2 when there are no results to read.

mutmut prints its own summary, but neither a score nor the changed lines of the
survivors in one list, which is what CONTRIBUTING.md argues survivor by survivor.
"""

import argparse
import collections
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
MUTMUT = pathlib.Path(sys.executable).with_name("mutmut")
KILLED = {"killed", "timeout"}
"""The statuses that count as killed (`mutmut results --all true` names them)."""


def results():
    """{mutant name: status} of every mutant mutmut has run."""
    text = subprocess.run([str(MUTMUT), "results", "--all", "true"], cwd=ROOT, check=True,
                          capture_output=True, text=True).stdout
    found = {}
    for line in text.splitlines():
        match = re.match(r"\s*(\S+): (.+?)\s*$", line)
        if match:
            found[match.group(1)] = match.group(2)
    return found


def changed_line(name):
    """The line a mutant changed, as `mutmut show` prints it ('-' old, '+' new)."""
    text = subprocess.run([str(MUTMUT), "show", name], cwd=ROOT, capture_output=True,
                          text=True).stdout
    return [line.strip() for line in text.splitlines()
            if line.startswith(("-", "+")) and not line.startswith(("---", "+++"))]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--least", type=float, default=0.9,
                        help="the killed share below which the exit status is 1 (0.9)")
    args = parser.parse_args(argv)
    if not 0 < args.least <= 1:
        parser.error(f"--least must be in (0, 1], got {args.least}")
    found = {name: status for name, status in results().items() if status != "not checked"}
    if not found:
        print("no mutation results: run `make mutants` (or mutmut run) first",
              file=sys.stderr)
        return 2
    counts = collections.Counter(found.values())
    killed = sum(counts[status] for status in KILLED)
    share = killed / len(found)
    print(f"mutation score: {killed} of {len(found)} mutants killed ({share:.1%}); "
          + ", ".join(f"{status} {n}" for status, n in counts.most_common()))
    lived = sorted(name for name, status in found.items() if status not in KILLED)
    by_function = collections.defaultdict(list)
    for name in lived:
        by_function[name.split("__mutmut_")[0]].append(name)
    for function, names in sorted(by_function.items()):
        print(f"\n{function}: {len(names)} lived")
        for name in names:
            print(f"  {name} ({found[name]}): " + " => ".join(changed_line(name)))
    return 0 if share >= args.least else 1


if __name__ == "__main__":
    sys.exit(main())
