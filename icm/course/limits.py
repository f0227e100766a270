"""The ranges of the course commands' numbers, written once: the command line states
and checks them as it reads them (`icm.course.__main__`), and the functions check the
same (`icm.course.grade.grade`). This module imports nothing, so that the command line
reads it without loading the grader."""

import os

CORES = os.cpu_count() or 1
"""The machine's cores: the most submissions graded, or solutions checked, at once."""
TIME_LIMIT = (1.0, 86400.0)
"""Seconds one submission may take: at least a second, at most a day."""
CELL_TIMEOUT = (1.0, 86400.0)
"""Seconds one cell may run."""
MEMORY_LIMIT = (0.25, 1024.0)
"""GiB of memory for one submission, all its processes together."""
JOBS = (1, CORES)
"""Submissions graded at once."""
