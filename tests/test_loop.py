"""The one loop (`icm.experiments.loop.play`): rows that move independently, each
episode reset, every step shown to every observer in order, with the state before and
after the action; and every experiment plays it: a run's observer sees every step of
the run it is part of, and the rods' run with an observer (the public loop, per-agent
learners) is the compiled run, number for number."""

import numpy as np
import pytest

from icm.experiments import loop, rod_toppling, run_actor_critic
from icm.experiments import actor_critic as ac_experiment


class Corridor:
    """A made-up world: row r walks a corridor of r + 2 cells from cell 0; an episode
    ends at its last cell, or after 3 steps."""

    def __init__(self, n_rows):
        self.n_rows, self.resets, self.moves = n_rows, [], np.zeros(n_rows, dtype=int)

    def __len__(self):
        return self.n_rows

    def reset(self, rows):
        self.resets.append(rows.tolist())
        self.moves[rows] = 0
        return np.zeros(len(rows), dtype=int)

    def step(self, rows, cells, actions):
        after = cells + actions
        self.moves[rows] += 1
        terminal = after == rows + 1
        ended = terminal | (self.moves[rows] >= 3)
        return loop.Transition(after, terminal.astype(int), None,
                               np.where(terminal, 0.0, 1.0), ended)


class Walker:
    """Always one step forward; learns nothing but counts its steps."""

    def __init__(self):
        self.learned = 0

    def act(self, rows, cells):
        return np.ones(len(rows), dtype=int), {"cells": cells.copy()}

    def learn(self, step):
        self.learned += len(step.rows)
        return step.after * 10


def test_rows_move_independently_and_each_plays_its_episodes():
    world, steps, order = Corridor(3), [], []
    loop.play(world, Walker(), 2, [lambda s: steps.append(s) or order.append("first"),
                                   None, lambda s: order.append("second")])
    assert order == ["first", "second"] * len(steps)
    # Row 0 takes 1 step an episode, row 1 two, row 2 three (its corridor ends after 3).
    moves = {r: [(int(s.episode[list(s.rows).index(r)]), int(s.before[list(s.rows).index(r)]),
                  int(s.after[list(s.rows).index(r)])) for s in steps if r in s.rows]
             for r in range(3)}
    assert moves[0] == [(0, 0, 1), (1, 0, 1)]
    assert moves[1] == [(0, 0, 1), (0, 1, 2), (1, 0, 1), (1, 1, 2)]
    assert moves[2] == [(0, 0, 1), (0, 1, 2), (0, 2, 3), (1, 0, 1), (1, 1, 2), (1, 2, 3)]
    # Every row starts, and a row is reset only for an episode it will play.
    assert world.resets == [[0, 1, 2], [0], [1], [2]]
    # The learner's view and its return are the step's: info before, learned after.
    for s in steps:
        np.testing.assert_array_equal(s.info["cells"], s.before)
        np.testing.assert_array_equal(s.learned, s.after * 10)


def test_a_step_an_observer_keeps_is_never_written_into():
    kept = []
    loop.play(Corridor(4), Walker(), 3, [lambda s: kept.append(
        (s, s.before.copy() if s.before is not None else None, s.after.copy(),
         s.episode.copy()))])
    for step, before, after, episode in kept:
        np.testing.assert_array_equal(step.before, before)
        np.testing.assert_array_equal(step.after, after)
        np.testing.assert_array_equal(step.episode, episode)


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="n_episodes"):
        loop.play(Corridor(2), Walker(), 0)
    with pytest.raises(ValueError, match="observers"):
        loop.play(Corridor(2), Walker(), 1, [5])


def test_the_goal_oriented_runs_observer_sees_every_press():
    seen = []
    result, = icm_grid([{}], n_seeds=3, n_trials=4, seed=2, progress=False,
                       observe=seen.append)
    assert len(seen) == 4 * result.settings["presses_per_trial"]
    assert [int(s.episode[0]) for s in seen] == [t for t in range(4) for _ in range(3)]
    counts = np.zeros_like(result.button_share)
    for s in seen:
        counts[s.rows, s.episode, s.action] += 1
        assert s.after is s.before  # the boxes shut before every press: the layout stays
    np.testing.assert_array_equal(counts / 3, result.button_share)


def icm_grid(*args, **kwargs):
    from icm.experiments import run_goal_oriented_grid

    return run_goal_oriented_grid(*args, **kwargs)


def test_the_actor_critics_loop_is_its_run_and_shows_states_before_and_after():
    from icm.envs import buttons
    from icm.experiments.seeding import run_seeds

    run = run_actor_critic(n_seeds=3, n_trials=5, seed=1, progress=False)
    env, agent = ac_experiment.make(run.settings, run_seeds(1, 3, 2))
    seen = []
    again = ac_experiment.play(env, agent, 5, observe=seen.append, settings=run.settings)
    for field in ("prediction_error", "practice", "press_probability", "reward"):
        np.testing.assert_array_equal(getattr(again, field), getattr(run, field))
    for s in seen:  # the state after a press: the layout and the effect it had
        np.testing.assert_array_equal(s.after, (s.before // 3) * 3 + s.outcome)
    assert len(seen) == 5 * buttons.DEFAULT_PRESSES_PER_TRIAL


@pytest.mark.parametrize("kwargs", [
    dict(),
    dict(wobbly_rod=True, reward="learning_progress"),
    dict(off_grid="end", reward="novelty", snapshot_episodes=(3,)),
    dict(max_moves=None, reward="random", epsilon=0.3),
])
def test_a_rod_run_with_an_observer_plays_the_public_loop_with_the_same_numbers(kwargs):
    compiled = rod_toppling.run_rod_toppling(n_seeds=3, n_episodes=12, seed=5,
                                             progress=False, **kwargs)
    moves = []
    observed = rod_toppling.run_rod_toppling(n_seeds=3, n_episodes=12, seed=5,
                                             progress=False, observe=moves.append, **kwargs)
    for name in ("toppled", "episode_length", "edge_moves", "prediction_error", "rod_error",
                 "rod_error_toppled", "predicted_well", "predicted_well_toppled",
                 "snapshot_episode", "q_table", "predictions", "confidence"):
        np.testing.assert_array_equal(getattr(observed, name), getattr(compiled, name),
                                      err_msg=name)
    assert sum(len(s.rows) for s in moves) == compiled.episode_length.sum()
