"""The command that writes the book's panel grids into assets/: every panel's
(`python -m icm.experiments.panel_grids`) or those named as arguments
(`python -m icm.experiments.panel_grids figure7`), each computed with
`panel_data.compute_grid` (a progress bar over its settings; about 5 s for figure5,
17 s for figure6, 25 s for figure7) and written with `panel_data.save_grid` to
assets/panel_<name>.npz. `panel_data.precompute` reads them while their recorded spec
is the panel's; after changing a learner, an experiment or a panel, write them again
and commit them (a test reruns some settings of each and expects their numbers).

The command is a module of its own because `panel_data` is imported with
`icm.experiments`: run as `python -m icm.experiments.panel_data`, it would be imported
twice.
"""

import sys

from icm import _validate
from icm.experiments import panel_data


def write(names=None, folder=None, progress=True):
    """Computes the grids of the panels `names` (default: every panel of
    `panel_data.PANELS`) and writes each to its file in `folder` (default: assets/).
    Every name is checked before any grid is computed.

    Args:
      names: a list of panel names, or None for all of them.
      folder: the folder to write to (a `pathlib.Path`), or None for assets/.
      progress: show a progress bar over each grid's settings.

    Returns:
      The paths written, in order.

    Raises:
      ValueError: for a name that is not a panel, naming the panels.
    """
    allowed = tuple(panel_data.PANELS)
    if names is None:
        names = list(allowed)
    if not isinstance(names, (list, tuple)) or not names:
        raise _validate.ArgumentTypeError(f"names must be a non-empty list of panel names "
                                          f"or None, got {_validate.show(names)}")
    names = [_validate.one_of("names", name, allowed) for name in names]
    progress = _validate.boolean("progress", progress)
    written = []
    for name in names:
        path = panel_data.grid_path(name, folder)
        panel_data.save_grid(panel_data.compute_grid(name, progress=progress), path)
        written.append(path)
    return written


def main(argv=None):
    """Writes the grids of the panels named in `argv` (default: the command line's
    arguments; none: every panel) to assets/ and says which files it wrote."""
    argv = sys.argv[1:] if argv is None else argv
    for path in write(list(argv) or None):
        size = path.stat().st_size / 1e6
        print(f"wrote {path} ({size:.2f} MB)")


if __name__ == "__main__":
    main()
