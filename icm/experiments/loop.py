"""The one loop every experiment plays: a world of many rows (one run each), a learner
with a row per run, and observers that see every step.

The loop knows nothing of buttons, rods or movements. A *world* says where each row's
episode starts and what an action does; a *learner* chooses and learns; the
experiment's own reductions (what a result keeps of a run), its recorders, its traces
and its progress bar are *observers*, each called once per step with a `Step`: the
state each row was in before the action, the action, what the learner knew when it
chose, the state after, what happened, and what the learner learned from it.

    world.reset(rows) -> the states the rows' episodes start from (None: no state)
    world.step(rows, states, actions) -> Transition(after, outcome, reward, discount, ended)
    learner.act(rows, states) -> (actions, info)
    learner.learn(step) -> what it learned (its errors, its rewards)

Rows move independently: a row whose episode ended starts its next one (the world
resets it) and stops once it has played its episodes. In the lockstep worlds (the
button console: every row a trial of the same presses) every row moves at every step.

The rods' compiled loop (`icm.experiments._rods_kernel`) is this loop's fast form for
the Q-learner on the tabular rods: it plays the same steps in the same order and feeds
the same recorder (`_rods_kernel.record_episode`), and a run with observers plays the
public loop instead (the same numbers; a test checks it).
"""

import dataclasses
from typing import Any, NamedTuple

import numpy as np

from icm import _validate
from icm.experiments.progress import progress_bar


class Transition(NamedTuple):
    """What a world's `step` returns for the rows that acted.

    Attributes:
      after: the rows' states after the action (None: the world has no state).
      outcome: what the action did (the box opened, the rod toppled, what a movement
        reached), one entry per row.
      reward: what the world paid, [rows], or None.
      discount: 0 where the action ended the episode for good (a terminal state), 1
        elsewhere: a number, or [rows].
      ended: [rows] bool, whether each row's episode ended (for good, or at a limit).
    """

    after: Any
    outcome: Any
    reward: Any
    discount: Any
    ended: np.ndarray


@dataclasses.dataclass(slots=True)
class Step:
    """One step of every row that acted, as the observers see it (after the learner
    learned from it).

    Attributes:
      episode: [rows] the episode (trial, rollout) each row is in, from 0.
      rows: [rows] the rows that acted, in order.
      before: their states before the action (None: the world has no state).
      action: what each did.
      info: what the learner knew when it chose (None: nothing it shows).
      after, outcome, reward, discount, ended: the world's `Transition`.
      learned: what the learner's `learn` returned.
    """

    episode: np.ndarray
    rows: np.ndarray
    before: Any
    action: Any
    info: Any
    after: Any
    outcome: Any
    reward: Any
    discount: Any
    ended: np.ndarray
    learned: Any = None


def play(world, learner, n_episodes, observers=()):
    """Plays `n_episodes` episodes in every row of `world` with `learner`, calling each
    observer with every `Step`, in order.

    Args:
      world: the rows' world (see the module's docstring), `len(world)` rows.
      learner: the learner, one row per world row.
      n_episodes: episodes each row plays (>= 1).
      observers: functions of one `Step` (None entries are left out).

    Raises:
      ValueError: for a bad `n_episodes` or an observer that is not a function.
    """
    n_episodes = _validate.integer_at_least("n_episodes", n_episodes, 1)
    observers = tuple(_validate.function(f"observers[{i}]", o)
                      for i, o in enumerate(observers) if o is not None)
    n = len(world)
    episode = np.zeros(n, dtype=np.int64)
    rows = np.arange(n)
    state = world.reset(rows)
    owned = False  # whether `state` is the loop's own array, which it may write into
    while rows.size:
        whole = rows.size == n  # every row acts: no copy of the states
        before = state if whole or state is None else state[rows]
        actions, info = learner.act(rows, before)
        moved = world.step(rows, before, actions)
        step = Step(episode.copy() if whole else episode[rows], rows, before, actions,
                    info, *moved)
        step.learned = learner.learn(step)
        for observe in observers:
            observe(step)
        if state is not None:
            if whole:
                state, owned = moved.after, False
            else:
                state[rows] = moved.after  # (owned: a row stopped before this step)
        if not moved.ended.any():
            continue
        done = rows[moved.ended]
        episode[done] += 1
        going = done[episode[done] < n_episodes]
        if going.size:
            started = world.reset(going)
            if state is not None:
                if going.size == n:
                    state, owned = started, False
                else:
                    if not owned:  # never write into an array the world or a step holds
                        state, owned = np.array(state, copy=True), True
                    state[going] = started
        if going.size != done.size:
            rows = rows[episode[rows] < n_episodes]
            if state is not None and not owned:
                state, owned = np.array(state, copy=True), True


def progress(total, description, enabled, unit, per=1):
    """An observer that moves a progress bar (`icm.experiments.progress.progress_bar`)
    on by the episodes that end, `per` row-episodes a unit (the rows of a lockstep world,
    whose bar counts trials), or None when `enabled` is False. Its `close()` closes the
    bar."""
    bar = progress_bar(None, total, description, enabled, unit=unit)
    if bar is None:
        return None
    return _Progress(bar, per)


class _Progress:
    """A progress bar moved on by the steps' ended episodes."""

    def __init__(self, bar, per):
        self.bar, self.per, self._ended = bar, per, 0

    def __call__(self, step):
        ended = int(np.count_nonzero(step.ended))
        if ended:
            self._ended += ended
            whole, self._ended = divmod(self._ended, self.per)
            if whole:
                self.bar.update(whole)

    def close(self):
        """Closes the bar."""
        self.bar.close()
