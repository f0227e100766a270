"""Progress bars for long runs: tqdm in terminals and notebooks, shown only for runs
that last longer than a second.

Where a bar goes:

- in a terminal, on standard error;
- in a reader's notebook, as a widget (tqdm.auto) under the cell;
- while the book is built (the kernels run with `BOOK_BUILD_VARIABLE` set, by
  `book/_ext/execute_book.py`), on the kernel's original standard error,
  `sys.__stderr__`, which is the terminal of whoever builds the book: progress
  belongs there, not in the page. Written to the cell's captured stream, a bar would
  become an output of the cell, and so text (or a dead widget) in the HTML.
"""

import os
import sys

BOOK_BUILD_VARIABLE = "ICM_BOOK_BUILD"
"""Set to "1" in the kernels that execute the book's notebooks."""


def in_book_build():
    """Whether this process is a kernel executing the book (`BOOK_BUILD_VARIABLE` is
    "1")."""
    return os.environ.get(BOOK_BUILD_VARIABLE) == "1"


def progress_bar(iterable, total, description, enabled=True, unit="seed"):
    """Wraps `iterable` in a tqdm progress bar if `enabled`; the bar appears only after
    one second, so quick runs stay quiet. See the module's docstring for where it goes.

    Raises:
      ValueError: if `enabled` is not True or False.
    """
    if not isinstance(enabled, bool):
        raise ValueError(f"progress must be True or False, got {enabled!r}")
    if not enabled:
        return iterable
    if in_book_build():
        from tqdm.std import tqdm

        return tqdm(iterable, total=total, desc=description, unit=unit, delay=1.0,
                    file=sys.__stderr__, mininterval=1.0)
    from tqdm.auto import tqdm

    return tqdm(iterable, total=total, desc=description, unit=unit, delay=1.0)
