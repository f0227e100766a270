"""Measuring the topple map in physics: `python -m icm.envs.rods` runs every move from
every standable cell on fresh upright rods and writes assets/rod_topple_map.json, then
does the same in the scene with the wobbly rod and writes assets/rod_wobble_map.json
(which moves pass beside it)."""

import collections
import json

import numpy as np

from icm import _validate
from icm.envs import icub
from icm.envs._common import check_discrete_action
from icm.envs.rods.physics import ROD_GEOMS, PhysicsRodTable, RodsPhysics
from icm.envs.rods.rules import (ACTIONS, N_COLUMNS, N_ROWS, ROD_NAMES, TOPPLE_MAP_FILE,
                                     WOBBLE_MAP_FILE, check_cell, load_topple_map)


def arm_touches_a_rod(physics):
    """True if any part of the arm is in contact with a rod."""
    _validate.instance("physics", physics, RodsPhysics)
    rods = {physics.model.name2id(name, "geom") for name in ROD_GEOMS}
    robot = {physics.model.name2id(name, "body")
             for name in ("r_upper_arm", "r_forearm", "r_hand")}
    for contact in physics.data.contact[:physics.data.ncon]:
        bodies = {physics.model.geom_bodyid[contact.geom1], physics.model.geom_bodyid[contact.geom2]}
        if {contact.geom1, contact.geom2} & rods and bodies & robot:
            return True
    return False


def measure_pair(env, cell, action):
    """Runs one move from `cell` on fresh standing rods, in physics.

    Returns:
      A dict: "topples" ("red", "blue" or None), "hand" (the cell it ends over), and
      "disturbance" (the largest displacement, in metres, of a rod that did not topple:
      a nudge that would make later moves depend on history).
    """
    _validate.instance("env", env, PhysicsRodTable)
    cell = check_cell("cell", cell)
    action = check_discrete_action(action, len(ACTIONS))
    env.start_cell = cell  # any cell: the map is what is being measured
    env.reset()
    before = env.physics.rod_positions()
    step = env.step(action)
    rods = step.observation["rods"]
    if rods.all():
        raise RuntimeError(f"the move {ACTIONS[action]} from {cell} topples both rods: the "
                           "rules (and the tabular twin) allow one; move the rods apart")
    moved = np.linalg.norm(env.physics.rod_positions() - before, axis=1)
    standing = rods == 0
    return {"topples": ROD_NAMES[int(np.argmax(rods))] if rods.any() else None,
            "hand": tuple(int(v) for v in step.observation["hand"]),
            "disturbance": float(moved[standing].max()) if standing.any() else 0.0}


def measure_topple_map(cells=None):
    """Measures which (cell, action) pairs topple which rod, by running each in physics.

    A cell is *standable* if the arm, placed over it, touches no rod. Every action from
    every standable cell (or from `cells`, if given) is run on fresh upright rods.

    Returns:
      {"standable": sorted list of cells, "pairs": [{"cell", "action", "topples",
      "hand", "disturbance"}, ...]}.
    """
    if cells is not None:
        if isinstance(cells, (str, bytes)) or not hasattr(cells, "__iter__"):
            raise _validate.ArgumentTypeError(
                f"cells must be None or a list of (column, row) cells, got {cells!r}")
        cells = [check_cell("cells[i]", cell) for cell in cells]
    env = PhysicsRodTable(max_moves=1)
    standable = []
    for row in range(N_ROWS):
        for column in range(N_COLUMNS):
            env.start_cell = (column, row)
            env.reset()
            if not arm_touches_a_rod(env.physics):
                standable.append((column, row))
    pairs = []
    for cell in (standable if cells is None else cells):
        for action in range(len(ACTIONS)):
            result = measure_pair(env, cell, action)
            pairs.append({"cell": list(cell), "action": action, **result,
                          "hand": list(result["hand"])})
    return {"standable": [list(c) for c in standable], "pairs": pairs}


def measure_wobble_map(seed=0):
    """Runs every move from every standable cell of the stored topple map in the scene
    with the wobbly rod, on fresh upright rods.

    Args:
      seed: the task's seed (whether a move beside the wobbly rod topples it is drawn
        from it; which moves pass beside it does not depend on it).

    Returns:
      {"pairs": [{"cell", "action", "wobbles", "topples", "touched", "disturbance"},
      ...]}: "wobbles", whether the move passes beside the wobbly rod (the task drew
      for it); "topples", "red", "blue", "wobbly" or None; "touched", whether the arm
      ever touched the wobbly rod; "disturbance", how far (metres) the rods that stayed
      up moved.
    """
    env = PhysicsRodTable(max_moves=1, wobbly_rod=True, seed=seed)
    physics = env.physics
    wobbly = physics.model.name2id("wobbly_rod", "geom")
    robot = {physics.model.name2id(name, "body") for name in ("r_upper_arm", "r_forearm",
                                                              "r_hand")}

    def touching(_):
        for contact in physics.data.contact[:physics.data.ncon]:
            if wobbly in (contact.geom1, contact.geom2) and \
                    {physics.model.geom_bodyid[contact.geom1],
                     physics.model.geom_bodyid[contact.geom2]} & robot:
                touched[0] = True

    pairs = []
    for cell in sorted(load_topple_map()["standable"], key=lambda c: (c[1], c[0])):
        for action in range(len(ACTIONS)):
            env.start_cell = cell
            env.reset()
            before = physics.rod_positions()
            touched = [False]
            rods = env.move(action, recorder=touching)
            moved = np.linalg.norm(physics.rod_positions() - before, axis=1)
            standing = rods == 0
            pairs.append({"cell": list(cell), "action": action,
                          "wobbles": bool(env.task.wobble_log),
                          "topples": physics.rod_names[int(np.argmax(rods))] if rods.any()
                          else None,
                          "touched": touched[0],
                          "disturbance": float(moved[standing].max()) if standing.any()
                          else 0.0})
    return {"pairs": pairs}


def main():
    """Measures the topple map in physics and writes assets/rod_topple_map.json; then
    the wobble map (assets/rod_wobble_map.json)."""
    measured = measure_topple_map()
    path = icub.ASSETS / TOPPLE_MAP_FILE
    lines = ",\n  ".join(json.dumps(pair) for pair in measured["pairs"])
    path.write_text('{"standable": ' + json.dumps(measured["standable"]) +
                    ',\n "pairs": [\n  ' + lines + "\n ]\n}\n")
    counts = collections.Counter(p["topples"] for p in measured["pairs"])
    print(f"wrote {path}: {len(measured['pairs'])} pairs from {len(measured['standable'])} "
          f"standable cells; red {counts['red']}, blue {counts['blue']}")
    write_wobble_map()


def write_wobble_map():
    """Measures the wobble map in physics (`measure_wobble_map`) and writes
    assets/rod_wobble_map.json."""
    wobble = measure_wobble_map()
    path = icub.ASSETS / WOBBLE_MAP_FILE
    lines = ",\n  ".join(json.dumps({k: pair[k] for k in ("cell", "action", "wobbles")})
                         for pair in wobble["pairs"])
    path.write_text('{"pairs": [\n  ' + lines + "\n]}\n")
    beside = [(tuple(p["cell"]), p["action"]) for p in wobble["pairs"] if p["wobbles"]]
    print(f"wrote {path}: moves beside the wobbly rod {beside}")


if __name__ == "__main__":
    main()
