"""A made-up interest signal, added as a user adds one: this file alone (one class,
registered by its decorator). tests/test_made_up.py imports it in a fixture, runs it
in the study "curiosity" end to end (on the buttons and on the rods' compiled loop)
and removes it again.

"last_error": a task's interest is the error of its last witnessing alone (the paper's
prediction error is the mean of the last k). As a reward it is the error of the move,
which the rods' compiled loop computes with its formula "error".
"""

import numpy as np

from icm.learners import interest


@interest.interest_signal
class LastErrorInterest(interest.InterestSignal):
    """Interest of each task as the error of its last witnessing (0 before)."""

    NAME = "last_error"
    COLOUR, LINESTYLE, MARKER = "#e7298a", "-", "v"
    KERNEL_FORMULA = "error"

    def record(self, task, error):
        """Appends the prediction error made when `task` was witnessed."""
        self._append(task, error)

    def interest(self, task):
        """The last error of `task` (0.0 if never witnessed)."""
        history = self._history.get(interest.check_state("task", task), ())
        return history[-1] if history else 0.0

    @staticmethod
    def table_values(table, rows):
        """Each task's last error (0 for a task never witnessed)."""
        return np.where(table.count[rows] > 0, table.errors[rows][..., -1], 0.0)
