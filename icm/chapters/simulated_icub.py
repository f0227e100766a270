"""The chapter "The simulated iCub" (book/simulated_icub.ipynb): whether the fast
tabular twins give the physics' outcomes, its claims in words (`CLAIMS`) checked on its
own runs when the book is built (`claims`)."""

import numpy as np

from icm import _validate
from icm.envs import rods
from icm.experiments.goal_oriented import GoalOrientedResult

CLAIMS = {
    "buttons_agree": "the physics and the tabular console give the same observations",
    "rods_agree": "the physics and the tabular rod table give the same observations",
    "learner_same": "the goal-oriented learner makes the same run on the physics as on "
                    "the tabular console",
    "red_more_pairs": "more (cell, move) pairs topple the red rod than the blue one",
    "forearm_topples_red": "moving right along the far row into the cell beside the red "
                           "rod topples it",
}
"""The claims the chapter states in words (`claims`)."""
FOREARM_PAIR = ((1, 2), rods.ACTIONS.index("right"))
"""The pair the chapter names: right, along the far row, into cell (2, 2), where the
forearm passes over the red rod."""
_RESULT_FIELDS = ("interest", "prediction_error", "mastery_trial", "practice", "button_share")


def claims(button_check, rod_check, topple_map, physics_run, tabular_run):
    """{claim name: whether it holds}, for each of `CLAIMS`.

    Args:
      button_check, rod_check: what `icm.envs.compare_twins` returned for the
        buttons and the rods.
      topple_map: the measured topple map (`icm.envs.rods.load_topple_map()`).
      physics_run, tabular_run: `GoalOrientedResult` objects of the same call, with
        `physics=True` and without.

    Returns:
      A dict of bools.
    """
    for name, check in (("button_check", button_check), ("rod_check", rod_check)):
        if not isinstance(check, dict) or "mismatches" not in check:
            raise _validate.ArgumentTypeError(f"{name} must be what compare_twins returns, "
                                              f"got {_validate.show(check)}")
    for name, run in (("physics_run", physics_run), ("tabular_run", tabular_run)):
        _validate.instance(name, run, GoalOrientedResult,
                           "a GoalOrientedResult (from icm.experiments.run_goal_oriented)")
    counts = rods.topple_counts(topple_map)
    return {
        "buttons_agree": button_check["mismatches"] == 0,
        "rods_agree": rod_check["mismatches"] == 0,
        "learner_same": all(np.array_equal(getattr(physics_run, f), getattr(tabular_run, f))
                            for f in _RESULT_FIELDS),
        "red_more_pairs": counts["red"] > counts["blue"],
        "forearm_topples_red": topple_map["topples"].get(FOREARM_PAIR) == "red",
    }
