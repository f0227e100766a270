"""Installs icm's dependencies into a Python that has icm but not them (Colab).

    python -m icm._install [--dry-run]

The notebooks' first cell runs `pip install --no-deps <icm>` and then this, on Binder
or Colab when icm is missing (CONTRIBUTING shows the cell). It needs nothing but the
standard library and pip (`import icm` loads nothing else), and asks pip for:

1. dm-control, without its dependencies;
2. icm's declared dependencies (`pyproject.toml`, read from the installed metadata)
   with its extra `notebooks` (myst-nb, whose glue the notebooks use), and
   dm-control's but `SKIPPED`, in one resolution, keeping whatever the Python
   already has where it fits (Colab's numpy, scipy, matplotlib, pandas, ...).

dm-control asks for labmaze, which only its locomotion mazes import (icm never does)
and which has no wheel for Python 3.13 and later (Colab's Python since August 2026):
pip would build it from source with Bazel, and fail.

Exit status: pip's, 0 when everything is installed.
"""

import importlib.metadata
import re
import subprocess
import sys

EXTRA = "notebooks"
"""icm's extra that the notebooks need (pyproject.toml: myst-nb, for glue)."""
PHYSICS = "dm-control"
"""The dependency installed without its own dependencies (see the module's docstring)."""
SKIPPED = {"labmaze"}
"""dm-control's dependencies that icm does not need (its locomotion mazes)."""


def _name(requirement):
    """The normalised project name of a requirement string."""
    return re.sub(r"[-_.]+", "-", re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)",
                                          requirement).group(1)).lower()


def _plain(requirements, extra=None):
    """The requirements without an extra, and those of `extra`, without their marker
    for it (pip evaluates the other markers)."""
    chosen = []
    for requirement in requirements or []:
        named = re.search(r"""extra\s*==\s*['"]([^'"]+)['"]""", requirement)
        if named is None:
            chosen.append(requirement)
        elif named.group(1) == extra:
            chosen.append(re.sub(r"""\s*;\s*extra\s*==\s*['"][^'"]+['"]\s*$""", "",
                                 requirement))
    return chosen


def pip(arguments, dry_run=False):
    """Runs `python -m pip install --quiet --no-warn-conflicts ARGUMENTS` (printed
    instead with `dry_run`); returns its exit status. (Without labmaze, pip would warn
    after every install that dm-control misses it.)"""
    command = [sys.executable, "-m", "pip", "install", "--quiet", "--no-warn-conflicts"] \
        + list(arguments)
    if dry_run:
        print(" ".join(command))
        return 0
    return subprocess.call(command)


def main(argv=None, requires=None):
    """Installs icm's dependencies (see the module's docstring); returns pip's status.
    `requires`: icm's requirements as its metadata lists them (default: read from the
    installed icm)."""
    argv = sys.argv[1:] if argv is None else argv
    dry_run = argv == ["--dry-run"]
    if argv and not dry_run:
        print("usage: python -m icm._install [--dry-run]", file=sys.stderr)
        return 2
    requires = importlib.metadata.requires("icm") if requires is None else requires
    wanted = _plain(requires, EXTRA)
    physics = [r for r in wanted if _name(r) == PHYSICS]
    others = [r for r in wanted if _name(r) != PHYSICS]
    if physics:
        status = pip(["--no-deps"] + physics, dry_run)
        if status:
            return status
        try:
            others = [r for r in _plain(importlib.metadata.requires(PHYSICS))
                      if _name(r) not in SKIPPED] + others
        except importlib.metadata.PackageNotFoundError:  # a dry run: not installed
            pass
    # One resolution for all of them, so that pip keeps them consistent with each other
    # and with what the Python already has.
    return pip(others, dry_run)


if __name__ == "__main__":
    sys.exit(main())
