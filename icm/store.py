"""Where the package keeps its data: the MJCF models and the measured and computed files
of assets/ (resolved from the package, not from the working directory). Imports nothing
heavy, so the tabular twins can read their data without loading MuJoCo."""

import pathlib

from icm import _validate

_PACKAGE = pathlib.Path(__file__).resolve().parent
ASSETS = next((folder for folder in (_PACKAGE / "assets", _PACKAGE.parent / "assets")
               if folder.is_dir()), _PACKAGE / "assets")
"""The folder of MJCF models and data: `icm/assets`, a copy in an installed package and
a link to the top-level `assets/` in a checkout; the top-level folder itself in a
checkout without symbolic links."""


def asset_path(name):
    """The path of a file in `assets/`, checked to exist."""
    path = ASSETS / _validate.text("name", name)
    if not path.exists():
        raise FileNotFoundError(f"missing asset {path}")
    return path
