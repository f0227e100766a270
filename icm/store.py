"""Where the package keeps its data: the MJCF models and the measured and computed files
of assets/, and the book's sources the course kit reads (resolved from the package, not
from the working directory). Imports nothing
heavy, so the tabular twins can read their data without loading MuJoCo."""

import pathlib

from icm import _validate, files

_PACKAGE = pathlib.Path(__file__).resolve().parent
ASSETS = next((folder for folder in (_PACKAGE / "assets", _PACKAGE.parent / "assets")
               if folder.is_dir()), _PACKAGE / "assets")
"""The folder of MJCF models and data: `icm/assets`, a copy in an installed package and
a link to the top-level `assets/` in a checkout; the top-level folder itself in a
checkout without symbolic links."""


PROJECT = next((folder for folder in (_PACKAGE / "project", _PACKAGE.parent)
                if (folder / "book").is_dir() and (folder / "_toc.yml").is_file()),
               _PACKAGE / "project")
"""The book's sources the course kit reads (`icm.course.assign`): `_toc.yml`,
`_config.yml`, `requirements.txt` and the chapters' notebooks in `book/`, package data
of `icm.project` (declared in pyproject.toml): `icm/project` holds links to the
project's own files in a checkout and copies of them in an installed package, so the
course finds the book through the package, wherever it is installed; the top-level
folder itself in a checkout without symbolic links."""


def asset_path(name):
    """The path of a file in `assets/`, checked to exist."""
    path = ASSETS / _validate.text("name", name)
    if not path.exists():
        raise FileNotFoundError(f"missing asset {path}")
    return path


def write_text(path, text):
    """Writes `text` to the file `path` through a temporary file in the same folder and a
    rename, so that `path` is never half written: the one writer of the package's stored
    files (the studies', the panels' grids, the chapters' runs and replications, the
    measured maps), each with its "produced_by" (`provenance`)."""
    write_bytes(path, text.encode("utf-8"))


def write_bytes(path, data):
    """Writes the bytes `data` to the file `path` as `write_text` writes text (one
    writer for the project: `icm.files.write_bytes`)."""
    files.write_bytes(path, data)


def versions(*others):
    """The versions of what computes a stored file: Python, icm and NumPy, then those of
    the packages named in `others` (e.g. "mujoco", "numba"), by name."""
    import importlib
    import platform
    import sys

    import numpy

    # icm itself is loaded whenever one of its modules is (its version read from there,
    # not imported: the package imports every layer, this module is below them all).
    found = {"python": platform.python_version(), "icm": sys.modules["icm"].__version__,
             "numpy": numpy.__version__}
    for name in others:
        found[name] = importlib.import_module(_validate.text("others[i]", name)).__version__
    return found


def provenance(command, settings, versions, **more):
    """What produced a stored file, in the one form every one of them records under
    "produced_by": {"command" (the command line that writes it again), "settings" (what
    decides its numbers), "versions" (`versions`), and `more` (e.g. its seeds and its
    units)}, in that order."""
    return {"command": _validate.text("command", command),
            "settings": _validate.instance("settings", settings, dict),
            "versions": _validate.instance("versions", versions, dict), **more}
