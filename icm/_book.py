"""What the library and the book's build share: the environment variable that asks for
the static panels, the book's table of contents (`_toc.yml`), read in one place, and
the line that spares a notebook's processes a slow import (`SKIP_SLOW_IMPORT`)."""

import os
import pathlib

STATIC_ENV = "ICM_STATIC_PANELS"
"""Set to "1" (the book's build sets it in every kernel), the panels are the static
Vega-Lite ones and the live views are written for the page, not run."""

SKIP_SLOW_IMPORT = '__import__("sys").modules.setdefault("rfc3987_syntax", None)'
"""A line that the processes executing notebooks run first (the book's executor and
its kernels, the grader and its kernels): it marks `rfc3987_syntax` as missing, so
that jsonschema (which nbformat, and so myst-nb, nbclient and otter, imports) does
without it. Installed, it builds some 35 Lark parsers as it is imported, 1.5 s of CPU
in every process that imports nbformat, for jsonschema's "iri" format checks, which
no schema of nbformat, nbclient, myst-nb or otter asks for (jsonschema checks formats
only when given a format checker, which they never pass). jsonschema has no switch
for it (https://github.com/python-jsonschema/jsonschema/issues/1428), hence this
line. It defines no name: a notebook sees the namespace it would see anywhere else."""


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
