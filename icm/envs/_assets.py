"""Where the MJCF models and measured data live (resolved from the package, not from the
working directory); imports nothing heavy, so the tabular twins can read their data
without loading MuJoCo."""

import pathlib

from icm import _validate

ASSETS = pathlib.Path(__file__).resolve().parents[2] / "assets"
"""The folder of MJCF models and data."""


def asset_path(name):
    """The path of a file in `assets/`, checked to exist."""
    path = ASSETS / _validate.text("name", name)
    if not path.exists():
        raise FileNotFoundError(f"missing asset {path}")
    return path
