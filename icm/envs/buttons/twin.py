"""The button experiment's episode rules and its fast tabular twin, one run or many."""

import collections
import functools

import dm_env
import numpy as np

from icm import _streams, _validate
from icm.envs._common import check_discrete_action, check_seed
from icm.envs.suite import SUITE
from icm.envs.buttons.rules import (DEFAULT_PRESSES_PER_TRIAL, PRESSES_PER_TRIAL,
                                        DEFAULT_RED_BUTTON, EFFECTS, GREEN, N_BUTTONS,
                                        NOISY_BUTTON, action_spec, check_red_button,
                                        check_rewarded_box, draw_green, extrinsic_reward,
                                        layout_index, layouts, lights_for,
                                        n_actions, noisy_effect, noisy_outcome,
                                        observation_spec, press_outcome)


class ButtonTrials(dm_env.Environment):
    """The episode rules of the button experiment, shared by `ButtonConsole` (tabular)
    and `PhysicsButtonConsole` (simulated iCub), so both follow them by construction.

    One episode is one trial of `presses_per_trial` presses. The first time step of a
    trial shows the new light layout with both boxes closed; every later one shows the
    boxes right after the press. The last step of a trial is a time limit, not a
    termination, so its discount is 1.0. By default the reward is always 0.0: nothing
    outside the robot pays it to press anything. For the extrinsic actor-critic of the
    paper's Figure 3a, `rewarded_box` makes the environment pay 1.0 for each press that
    opens that box. A step after the end of a trial starts a new one. With
    `noisy_button`, action 5 is the noisy button (see `icm.envs.buttons.rules`).

    Subclasses say how a trial starts (`_new_trial`, returning the lights) and what a
    press does (`_press`, returning the boxes).
    """

    def __init__(self, presses_per_trial, rewarded_box, noisy_button=False):
        self.presses_per_trial = PRESSES_PER_TRIAL.check(presses_per_trial,
                                                         "presses_per_trial")
        self.rewarded_box = check_rewarded_box(rewarded_box)
        self.noisy_button = _validate.boolean("noisy_button", noisy_button)
        self.n_actions = n_actions(self.noisy_button)
        self._lights = None
        self._presses = 0
        self._reset_next_step = True

    def _new_trial(self):
        raise NotImplementedError

    def _press(self, button):
        raise NotImplementedError

    @property
    def lights(self):
        """A copy of the current light layout (None before the first reset)."""
        return None if self._lights is None else self._lights.copy()

    @property
    def green_button(self):
        """Index of the button lit green in the current trial."""
        return int(np.flatnonzero(self._lights == GREEN)[0])

    def _observation(self, boxes):
        return collections.OrderedDict(lights=self._lights.copy(), boxes=boxes)

    def reset(self):
        """Starts a new trial: a new layout, both boxes shut.

        Returns:
          The FIRST time step: the new layout, both boxes shut.
        """
        self._lights = self._new_trial()
        self._presses = 0
        self._reset_next_step = False
        return dm_env.restart(self._observation(np.zeros(2, dtype=np.int64)))

    def step(self, action):
        """Presses button `action` (0-4, or 0-5 with the noisy button).

        Returns:
          The time step after the press: the lights and the boxes as they are after it;
          the first step after the end of a trial starts a new one instead.

        Raises:
          ValueError: if `action` is not a button index.
        """
        button = check_discrete_action(action, self.n_actions)
        if self._reset_next_step:
            return self.reset()
        boxes = self._press(button)
        self._presses += 1
        observation = self._observation(boxes)
        reward = extrinsic_reward(boxes, self.rewarded_box)
        if self._presses >= self.presses_per_trial:
            self._reset_next_step = True
            return dm_env.truncation(reward, observation, discount=1.0)
        return dm_env.transition(reward, observation)

    def observation_spec(self):
        """The observation spec: `lights` and `boxes` (see `observation_spec()`)."""
        return observation_spec()

    def action_spec(self):
        """The action spec: one of the 5 (or 6) buttons (see `action_spec()`)."""
        return action_spec(self.noisy_button)


@SUITE.add("buttons", episodes=ButtonTrials,
           physics="icm.envs.buttons.physics:PhysicsButtonConsole",
           continuous="icm.envs.buttons.physics:load_continuous",
           task="icm.envs.buttons.physics:ButtonsTask")
class ButtonConsole(ButtonTrials):
    """The tabular button experiment: the paper's rules applied directly, no physics.

    The episode rules are those of `ButtonTrials`: one trial of `presses_per_trial`
    presses, ended by a time limit (discount 1.0); reward 0.0 unless `rewarded_box`.

    Args:
      red_button: index (0-4) of the button that is always red. Default 2, the middle.
      presses_per_trial: presses in one trial (>= 1). Default 3.
      rewarded_box: None (default, no reward), "red" or "green": the box whose
        opening pays 1.0.
      noisy_button: add the noisy button, action 5 (default False).
      seed: None, an integer >= 0 or a `numpy.random.Generator`; draws the green
        buttons (one number per trial) and the noisy button's outcomes (one per press).

    Raises:
      ValueError: for a red button outside 0..4, presses_per_trial < 1, an unknown
        rewarded box, a bad seed, or (in `step`) an action that is not a button index.
    """

    def __init__(self, red_button=DEFAULT_RED_BUTTON,
                 presses_per_trial=DEFAULT_PRESSES_PER_TRIAL, rewarded_box=None,
                 noisy_button=False, seed=None):
        self.red_button = check_red_button(red_button)
        super().__init__(presses_per_trial, rewarded_box, noisy_button)
        self._random = check_seed(seed)

    def reseed(self, seed):
        """Restarts the environment's random generator from `seed` (None, an integer
        >= 0 or a Generator); the next step starts a new trial."""
        self._random = check_seed(seed)
        self._reset_next_step = True

    def _new_trial(self):
        return lights_for(self.red_button, draw_green(self._random, self.red_button))

    def _press(self, button):
        if button == NOISY_BUTTON:
            return noisy_outcome(self._random.random())
        return press_outcome(self._lights, button)


def outcome_table(red_button=DEFAULT_RED_BUTTON):
    """The effect index of every (layout, button) pair of the 5 lit buttons, an int
    array [4, 5] (layouts in the order of `layouts`)."""
    return _outcome_table(check_red_button(red_button)).copy()


@functools.lru_cache(maxsize=N_BUTTONS)
def _outcome_table(red_button):
    table = np.zeros((4, N_BUTTONS), dtype=np.int64)
    for layout, lights in enumerate(layouts(red_button)):
        for button in range(N_BUTTONS):
            table[layout, button] = EFFECTS.index(tuple(press_outcome(lights, button).tolist()))
    return table


class ButtonConsoleBatch:
    """Many tabular button consoles at once, one per row, each with its own seed.

    Row k draws exactly the numbers `ButtonConsole(seed=seeds[k])` would draw, so it
    makes the same trials: the batched learners' runs equal the per-run ones. A trial is
    a layout index (into `layouts(red_button)`); a press gives an effect index (into
    `EFFECTS`).

    Args:
      seeds: one integer seed (or Generator) per row.
      red_button: the button that is always red.
      noisy_button: add the noisy button, action 5.

    Attributes:
      effects: the effects a press can have, `EFFECTS` (never both boxes).
    """

    def __init__(self, seeds, red_button=DEFAULT_RED_BUTTON, noisy_button=False):
        self.red_button = check_red_button(red_button)
        self.noisy_button = _validate.boolean("noisy_button", noisy_button)
        self.n_actions = n_actions(self.noisy_button)
        self.streams = _streams.Streams(seeds)
        self.outcomes = outcome_table(self.red_button)
        self._outcomes_flat = self.outcomes.reshape(-1)
        self.layout = np.zeros(len(self.streams), dtype=np.int64)
        self.effects = EFFECTS

    def __len__(self):
        return len(self.streams)

    def new_trials(self):
        """Starts a trial in every row; returns the layout indices [rows]."""
        self.layout = layout_index(self.streams.draw(k=1)[:, 0])
        return self.layout

    def press(self, actions):
        """Presses button `actions[k]` in row k; returns the effect indices [rows]."""
        actions = np.asarray(actions)
        if not self.noisy_button:
            return self._outcomes_flat.take(self.layout * N_BUTTONS + actions)
        effects = self.outcomes[self.layout, np.minimum(actions, N_BUTTONS - 1)]
        noisy = np.flatnonzero(actions == NOISY_BUTTON)
        if noisy.size:
            effects[noisy] = noisy_effect(self.streams.draw(noisy, k=1)[:, 0])
        return effects

