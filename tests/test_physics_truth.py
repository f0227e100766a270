"""The physics environments do what they report: checks that a lying simulation fails.

A liar is a physics environment whose `step` answers from the tabular twin's rules
while the arm never moves (or while time passes with the arm idle). Its observations
equal the twin's, so every test that compares observations passes for it. The checks
here look at the simulation itself, through the public `step`, with an observer that
MuJoCo calls at every physics step (`mujoco.set_mjcb_control`), independent of the
environment's own helper methods:

- simulated time advances by a whole motion;
- the fingertip touches the pressed button, and no other, and that button's joint
  goes past the press depth; the boxes reported open are lids open in the simulation;
- the hand ends over the cell the observation reports; a reported topple is a rod
  tilted more than 45 degrees from its reset pose, pushed by the arm;
- the arm's joints move, and different seeds give different trajectories.

Each check is run on the real environments, and (`test_liars_are_caught`) on two
liars per scenario, each of which must fail at least two checks.
"""

import contextlib
import functools

import mujoco
import numpy as np
import pytest

import icm
from icm.envs import buttons, rods

ROBOT_GEOMS = ("r_upper_arm", "r_forearm", "r_palm", "r_finger")


class Observer:
    """Records, at every physics step of `physics`'s model, the time, the joint
    positions, the fingertip and which named geom pairs touch."""

    def __init__(self, physics, pairs):
        model = physics.model
        self.geom = {name: model.name2id(name, "geom")
                     for pair in pairs for name in pair}
        self.pairs = pairs
        self.site = model.name2id("fingertip", "site")
        self.clear()

    def clear(self):
        self.time, self.qpos, self.fingertip, self.touching = [], [], [], []

    def __call__(self, model, data):
        self.time.append(data.time)
        self.qpos.append(data.qpos.copy())
        self.fingertip.append(data.site_xpos[self.site].copy())
        contacts = {frozenset((int(c.geom1), int(c.geom2))) for c in data.contact[:data.ncon]}
        self.touching.append({pair for pair in self.pairs
                              if frozenset(self.geom[n] for n in pair) in contacts})

    def touched(self, pair):
        return any(pair in step for step in self.touching)

    def elapsed(self):
        return self.time[-1] - self.time[0] if len(self.time) > 1 else 0.0


@contextlib.contextmanager
def observing(physics, pairs=()):
    observer = Observer(physics, pairs)
    mujoco.set_mjcb_control(observer)
    try:
        yield observer
    finally:
        mujoco.set_mjcb_control(None)


def qpos_of(physics, joint):
    return physics.model.jnt_qposadr[physics.model.name2id(joint, "joint")]


# --- the checks, on the buttons -----------------------------------------------------------

BUTTON_ACTIONS = [2, 0, 4, 1, 3, 2]  # every button, with the red one twice
CAP_PAIRS = tuple(("r_finger", f"button{b}_cap") for b in range(buttons.N_BUTTONS))


@functools.lru_cache(maxsize=None)
def play_buttons(make, seed=0):
    """Plays BUTTON_ACTIONS (a fresh trial before each press), observing every press.

    Returns a list of (button, lights, observation after, observer records copy)."""
    env = make(seed=seed, presses_per_trial=1)
    played = []
    for button in BUTTON_ACTIONS:
        step = env.reset()
        lights = step.observation["lights"].copy()
        with observing(env.physics, CAP_PAIRS) as seen:
            step = env.step(button)
        data = env.physics.data
        lids = np.array([data.qpos[qpos_of(env.physics, name)] for name in ("red_lid", "green_lid")])
        played.append(dict(button=button, lights=lights, boxes=step.observation["boxes"],
                           lids=lids, seen=seen))
    return env, played


def check_presses_take_simulated_time(make):
    _, played = play_buttons(make)
    for press in played:
        assert press["seen"].elapsed() > 1.0, f"press of {press['button']}: no time passed"


def check_fingertip_touches_the_pressed_button_only(make):
    _, played = play_buttons(make)
    for press in played:
        b = press["button"]
        assert press["seen"].touched(CAP_PAIRS[b]), f"the finger never touched button {b}"
        others = [o for o in range(buttons.N_BUTTONS) if o != b and press["seen"].touched(CAP_PAIRS[o])]
        assert others == [], f"pressing {b}, the finger touched {others}"


def check_pressed_button_passes_the_press_depth(make):
    env, played = play_buttons(make)
    for press in played:
        b = press["button"]
        assert press["seen"].qpos, "no physics step was taken"
        depths = -np.array(press["seen"].qpos)[:, [qpos_of(env.physics, f"button{o}")
                                                  for o in range(buttons.N_BUTTONS)]]
        assert depths[:, b].max() > buttons.PRESS_DEPTH, f"button {b} never went down"
        assert np.delete(depths, b, axis=1).max() < buttons.PRESS_DEPTH / 2


def check_reported_boxes_are_open_lids(make):
    _, played = play_buttons(make)
    opened = 0
    for press in played:
        expected = buttons.press_outcome(press["lights"], press["button"])
        lid_open = press["lids"] >= buttons.BOX_OPEN_ANGLE
        assert press["boxes"].tolist() == lid_open.astype(int).tolist(), \
            f"boxes {press['boxes']} reported, lids at {np.rad2deg(press['lids'])} degrees"
        assert lid_open.tolist() == expected.astype(bool).tolist()
        opened += int(lid_open.any())
    assert opened >= 2  # the red press at least, twice


def check_seeds_change_the_trajectory(make):
    def trajectory(seed):
        _, played = play_buttons(make, seed)
        return np.concatenate([np.array(p["seen"].qpos).ravel() for p in played] + [[0.0]])
    first, again, other = trajectory(1), trajectory(1), trajectory(2)
    assert len(first) > 1000, "no physics steps were taken"
    np.testing.assert_array_equal(first, again)
    assert first.shape != other.shape or not np.array_equal(first, other)


BUTTON_CHECKS = [check_presses_take_simulated_time,
                 check_fingertip_touches_the_pressed_button_only,
                 check_pressed_button_passes_the_press_depth,
                 check_reported_boxes_are_open_lids,
                 check_seeds_change_the_trajectory]


# --- the checks, on the rods ----------------------------------------------------------------

ROD_PAIRS = tuple((robot, f"{rod}_rod") for robot in ROBOT_GEOMS for rod in rods.ROD_NAMES)
# From (0, 0): right, right, forward (into the red rod); then from (4, 0) forward twice
# and left (into the blue rod, along the far row).
ROD_PLAYS = [((0, 0), [3, 3, 0]), ((4, 0), [0, 0, 2])]


def rod_tilts(physics):
    """The rods' tilts from their reset pose (degrees), read from the body frames."""
    tilts = []
    for name in rods.ROD_NAMES:
        body = physics.model.name2id(f"{name}_rod", "body")
        z = physics.data.xmat[body].reshape(3, 3)[:, 2]
        tilts.append(np.degrees(np.arccos(np.clip(z[2], -1.0, 1.0))))
    return np.array(tilts)


@functools.lru_cache(maxsize=None)
def play_rods(make):
    """Plays ROD_PLAYS, observing each move: a list of dicts."""
    played = []
    for start, actions in ROD_PLAYS:
        env = make(start_cell=start, max_moves=10)
        step = env.reset()
        for action in actions:
            cell = tuple(step.observation["hand"].tolist())
            with observing(env.physics, ROD_PAIRS) as seen:
                step = env.step(action)
            tip = env.physics.data.site_xpos[env.physics.model.name2id("fingertip", "site")]
            arm = np.array(seen.qpos)[:, [qpos_of(env.physics, j) for j in icm.envs.icub.ARM_JOINTS]] \
                if seen.qpos else np.zeros((1, 7))
            played.append(dict(start=cell, action=action, hand=tuple(step.observation["hand"]),
                               rods=step.observation["rods"].copy(), tilts=rod_tilts(env.physics),
                               tip=tip.copy(), centre=env.physics.cell_centre(
                                   tuple(step.observation["hand"])), seen=seen, arm=arm))
            if step.last():
                break
    return played


def check_moves_take_simulated_time(make):
    for move in play_rods(make):
        assert move["seen"].elapsed() > 0.3, f"move {move['action']} from {move['start']}: no time"


def check_hand_ends_over_the_reported_cell(make):
    for move in play_rods(make):
        assert move["hand"] == rods.next_cell(move["start"], move["action"])
        if not move["rods"].any():
            gap = np.linalg.norm(move["tip"][:2] - move["centre"][:2])
            assert gap < 0.015, f"the fingertip is {gap * 100:.1f} cm from cell {move['hand']}"


def check_reported_topples_are_tilted_rods(make):
    topples = 0
    for move in play_rods(make):
        tilted = move["tilts"] > 45.0
        assert move["rods"].astype(bool).tolist() == tilted.tolist(), \
            f"rods {move['rods']} reported, tilts {np.round(move['tilts'])} degrees"
        topples += int(tilted.any())
    assert topples == 2  # the plays end on the red and on the blue rod


def check_the_arm_pushes_the_rod_it_topples(make):
    for move in play_rods(make):
        for i, rod in enumerate(rods.ROD_NAMES):
            touched = any(move["seen"].touched((robot, f"{rod}_rod")) for robot in ROBOT_GEOMS)
            if move["rods"][i]:
                assert touched, f"the {rod} rod fell without the arm touching it"


def check_the_arm_moves(make):
    for move in play_rods(make):
        if move["hand"] != move["start"]:
            travel = np.ptp(move["arm"], axis=0).max()
            assert travel > 0.05, f"the arm's joints moved by {travel:.3f} rad at most"


ROD_CHECKS = [check_moves_take_simulated_time, check_hand_ends_over_the_reported_cell,
              check_reported_topples_are_tilted_rods, check_the_arm_pushes_the_rod_it_topples,
              check_the_arm_moves]


# --- on the real environments ------------------------------------------------------------

def physics_buttons(**kwargs):
    return icm.envs.load("buttons", physics=True, **kwargs)


def physics_rods(**kwargs):
    return icm.envs.load("rods", physics=True, **kwargs)


@pytest.mark.parametrize("check", BUTTON_CHECKS, ids=lambda c: c.__name__)
def test_button_console_physics(check):
    check(physics_buttons)


@pytest.mark.parametrize("check", ROD_CHECKS, ids=lambda c: c.__name__)
def test_rod_table_physics(check):
    check(physics_rods)


# --- the liars are caught ---------------------------------------------------------------

class RulesOnlyConsole(buttons.PhysicsButtonConsole):
    """Answers from the twin's rules and never steps the physics."""

    def _press(self, button):
        return buttons.press_outcome(self._lights, button)


class IdleArmConsole(buttons.PhysicsButtonConsole):
    """Lets simulated time pass with the arm holding still, then answers from the rules."""

    def _press(self, button):
        self.arm.hold(1.6)
        return buttons.press_outcome(self._lights, button)


class RulesOnlyRodTable(rods.PhysicsRodTable):
    """Answers from the stored topple map and never steps the physics."""

    def _move(self, action):
        toppled = rods.load_topple_map()["topples"][(self._cell, action)]
        self._cell = rods.next_cell(self._cell, action)
        return self._cell, [int(toppled == name) for name in rods.ROD_NAMES]


class IdleArmRodTable(RulesOnlyRodTable):
    """Lets simulated time pass with the arm holding still, then answers from the map."""

    def _move(self, action):
        self.arm.hold(0.7)
        return super()._move(action)


LIARS = [("buttons", RulesOnlyConsole, BUTTON_CHECKS), ("buttons", IdleArmConsole, BUTTON_CHECKS),
         ("rods", RulesOnlyRodTable, ROD_CHECKS), ("rods", IdleArmRodTable, ROD_CHECKS)]


@pytest.mark.parametrize("scenario, liar, checks", LIARS, ids=lambda v: getattr(v, "__name__", v)
                         if not isinstance(v, list) else "checks")
def test_liars_are_caught(scenario, liar, checks):
    # The liar's observations equal the tabular twin's: the comparison of twins passes.
    twin = icm.envs.load(scenario, seed=0)
    lying = liar(seed=0)
    twin.reset(), lying.reset()
    for action in [2, 0, 3, 1, 0, 2] if scenario == "buttons" else [3, 3, 0, 1]:
        a, b = lying.step(action), twin.step(action)
        for key in a.observation:
            np.testing.assert_array_equal(a.observation[key], b.observation[key])
    caught = []
    for check in checks:
        try:
            check(liar)
        except AssertionError:
            caught.append(check.__name__)
    assert len(caught) >= 2, f"{liar.__name__} passed all but {caught}"


# --- the noisy button (chapter "Which curiosity?") -----------------------------------------

NOISY_CAP_PAIRS = CAP_PAIRS + (("r_finger", f"button{buttons.NOISY_BUTTON}_cap"),)


@functools.lru_cache(maxsize=None)
def play_noisy(make, presses=6):
    """Presses the noisy button `presses` times (a fresh trial before each), observing."""
    env = make(seed=0, presses_per_trial=1, noisy_button=True)
    played = []
    for _ in range(presses):
        env.reset()
        with observing(env.physics, NOISY_CAP_PAIRS) as seen:
            step = env.step(buttons.NOISY_BUTTON)
        data = env.physics.data
        lids = np.array([data.qpos[qpos_of(env.physics, name)] for name in ("red_lid", "green_lid")])
        played.append(dict(boxes=step.observation["boxes"], lids=lids, seen=seen,
                           joints=[qpos_of(env.physics, f"button{b}") for b in range(6)]))
    return played


def check_noisy_presses_take_simulated_time(make):
    for press in play_noisy(make):
        assert press["seen"].elapsed() > 1.0, "no time passed"


def check_fingertip_touches_the_noisy_button_only(make):
    for press in play_noisy(make):
        assert press["seen"].touched(NOISY_CAP_PAIRS[-1]), "the finger never touched it"
        assert not any(press["seen"].touched(pair) for pair in CAP_PAIRS)


def check_noisy_button_passes_the_press_depth(make):
    for press in play_noisy(make):
        assert press["seen"].qpos, "no physics step was taken"
        depths = -np.array(press["seen"].qpos)[:, press["joints"]]
        assert depths[:, buttons.NOISY_BUTTON].max() > buttons.PRESS_DEPTH
        assert depths[:, :buttons.N_BUTTONS].max() < buttons.PRESS_DEPTH / 2


def check_noisy_boxes_are_open_lids(make):
    opened = 0
    for press in play_noisy(make):
        lid_open = press["lids"] >= buttons.BOX_OPEN_ANGLE
        assert press["boxes"].tolist() == lid_open.astype(int).tolist()
        opened += int(lid_open.any())
    assert opened >= 2


NOISY_CHECKS = [check_noisy_presses_take_simulated_time,
                check_fingertip_touches_the_noisy_button_only,
                check_noisy_button_passes_the_press_depth, check_noisy_boxes_are_open_lids]


@pytest.mark.parametrize("check", NOISY_CHECKS, ids=lambda c: c.__name__)
def test_noisy_button_physics(check):
    check(physics_buttons)


class RulesOnlyNoisyConsole(buttons.PhysicsButtonConsole):
    """Answers the noisy button from the task's generator and never steps the physics."""

    def _press(self, button):
        return buttons.noisy_outcome(self.task.generator.random())


def test_a_noisy_liar_is_caught():
    twin = icm.envs.load("buttons", seed=0, presses_per_trial=1, noisy_button=True)
    lying = RulesOnlyNoisyConsole(seed=0, presses_per_trial=1, noisy_button=True)
    twin.reset(), lying.reset()
    for _ in range(6):
        a, b = lying.step(buttons.NOISY_BUTTON), twin.step(buttons.NOISY_BUTTON)
        np.testing.assert_array_equal(a.observation["boxes"], b.observation["boxes"])
    caught = []
    for check in NOISY_CHECKS:
        try:
            check(RulesOnlyNoisyConsole)
        except AssertionError:
            caught.append(check.__name__)
    assert len(caught) >= 2, f"the liar passed all but {caught}"
