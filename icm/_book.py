"""What the library and the book's build share: the environment variable that asks for
the static panels, and the book's table of contents (`_toc.yml`), read in one place."""

import os
import pathlib

STATIC_ENV = "ICM_STATIC_PANELS"
"""Set to "1" (the book's build sets it in every kernel), the panels are the static
Vega-Lite ones and the live views are written for the page, not run."""


def static_panels():
    """Whether the book is being built: `STATIC_ENV` is "1"."""
    return os.environ.get(STATIC_ENV) == "1"


def toc_pages(root, part=None):
    """The pages of `root`/_toc.yml in the book's order, as paths relative to `root`
    without their suffix (for example "book/goal_oriented").

    Args:
      root: the project's folder (a path).
      part: None for every page (the root page, the chapters outside parts, then each
        part's), or the caption of one part (for example "Chapters") for its pages only.

    Returns:
      A list of strings.

    Raises:
      ValueError: for a `part` the table of contents does not have.
    """
    import yaml  # here: only the build and the course read the table of contents

    toc = yaml.safe_load((pathlib.Path(root) / "_toc.yml").read_text())
    parts = toc.get("parts", [])
    if part is None:
        chapters = list(toc.get("chapters", []))
        for entry in parts:
            chapters += entry["chapters"]
        return [toc["root"]] + [chapter["file"] for chapter in chapters]
    for entry in parts:
        if entry.get("caption") == part:
            return [chapter["file"] for chapter in entry["chapters"]]
    captions = ", ".join(repr(entry.get("caption")) for entry in parts)
    raise ValueError(f"part must be a caption of {pathlib.Path(root) / '_toc.yml'} "
                     f"({captions}), got {part!r}")
