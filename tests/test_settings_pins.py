"""The settings' two refusals (issue 30, section 3), for every learner's settings class:
a per-row setting refuses an empty list of values, and a grid (`Settings.stack`)
refuses blocks that differ in a setting that is one value for the whole batch."""

import numpy as np
import pytest

from icm import _validate
from icm.learners import actor_critic, goal_oriented, q_learning

CLASSES = [goal_oriented.GoalOrientedSettings, actor_critic.ActorCriticSettings,
           q_learning.QLearnerSettings]


def _other_value(spec):
    """A value of `spec` other than its default, that it accepts."""
    if spec.kind == "choice":
        return next(c for c in spec.choices if c != spec.default)
    candidates = [spec.default + 1, spec.default - 1, spec.default * 0.5, spec.default * 2]
    for value in candidates:
        try:
            if spec.check(value) != spec.default:
                return spec.check(value)
        except ValueError:
            continue
    raise AssertionError(f"no other value for {spec.name}")


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_a_per_row_setting_refuses_an_empty_list_of_values(cls):
    per_row = [name for name, spec in cls.specs().items() if spec.per_row]
    assert per_row
    for name in per_row:
        for empty in ([], (), np.array([])):
            with pytest.raises(ValueError, match=rf"^{name} must be one value or a 1-d array "
                                                 r"of values, one per row, got "):
                cls(**{name: empty})
        one = cls(**{name: [cls.spec(name).default]})  # one value per row is fine
        assert len(getattr(one, name)) == 1


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_a_grid_refuses_blocks_that_differ_in_a_setting_that_is_not_per_row(cls):
    whole_batch = [name for name, spec in cls.specs().items() if not spec.per_row]
    default = cls()
    for name in whole_batch:
        other = default.replace(**{name: _other_value(cls.spec(name))})
        for blocks in ([default, other], [other, default], [default, default, other]):
            with pytest.raises(ValueError, match=rf"^{name} must be the same in every "
                                                 r"setting of a grid"):
                cls.stack(blocks, 3)
        # The same value everywhere: kept, once for the batch.
        same = cls.stack([other, other], 3)
        assert getattr(same, name) == getattr(other, name)
    # A per-row setting may differ: each block's value for its rows.
    name = next(n for n, spec in cls.specs().items() if spec.per_row)
    value = _other_value(cls.spec(name))
    stacked = cls.stack([default, default.replace(**{name: value})], 2)
    assert list(stacked.per_row(name, 4)) == [getattr(default, name)] * 2 + [value] * 2


def test_a_grid_of_no_block_or_no_row_is_refused_naming_the_argument():
    cls = goal_oriented.GoalOrientedSettings
    with pytest.raises(_validate.ArgumentTypeError, match="^blocks must be a non-empty list"):
        cls.stack([], 3)
    with pytest.raises(_validate.ArgumentTypeError, match="^blocks must be a non-empty list"):
        cls.stack([actor_critic.ActorCriticSettings()], 3)
    with pytest.raises(ValueError, match="n_rows"):
        cls.stack([cls()], 0)
    with pytest.raises(ValueError, match="^epsilon must be one value in each block"):
        cls.stack([cls(epsilon=[0.1, 0.2])], 2)
