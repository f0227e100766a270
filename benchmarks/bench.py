"""Benchmarks: prints how long the main computations take on this machine (`make bench`).

Timings are the best of several repeats, in seconds, on one core.
"""

import os
import time

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # noqa: E402
import numpy as np  # noqa: E402

import icm  # noqa: E402
from icm import widgets  # noqa: E402


def best_of(repeats, function):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def widget_redraw():
    # What one slider move costs: the runs, the figure and its PNG for the browser.
    settings = {name: spec["value"] for name, spec in widgets.FIGURE5_SLIDERS.items()}
    settings["n_seeds"] = 20
    icm.figures.figure5_for(n_trials=60, **settings)._repr_png_()


def primitive_against_raw_steps(env, actions):
    """Wall time of the discrete actions `actions` on a physics env, the number of
    physics steps they took, and the wall time of as many raw mujoco.mj_step calls on
    the same model (from the same start state)."""
    env.reset()
    physics = env.physics
    start_state = (physics.data.qpos.copy(), physics.data.qvel.copy(), physics.data.ctrl.copy())
    t0 = physics.data.time
    start = time.perf_counter()
    for action in actions:
        env.step(action)
    primitive = time.perf_counter() - start
    n_steps = int(round((physics.data.time - t0) / physics.model.opt.timestep))
    model, data = physics.model.ptr, mujoco.MjData(physics.model.ptr)
    data.qpos[:], data.qvel[:], data.ctrl[:] = start_state
    start = time.perf_counter()
    for _ in range(n_steps):
        mujoco.mj_step(model, data)
    raw = time.perf_counter() - start
    return primitive / len(actions), n_steps / len(actions), raw / len(actions)


def render_fps(env, frames=40):
    env.reset()
    env.physics.render(480, 640, camera_id="over_shoulder")  # warm up the context
    start = time.perf_counter()
    for _ in range(frames):
        env.physics.render(480, 640, camera_id="over_shoulder")
    return frames / (time.perf_counter() - start)


def main():
    experiments = icm.experiments
    runs = [
        ("run_goal_oriented, 100 seeds x 100 trials (target <= 1 s)",
         lambda: experiments.run_goal_oriented(n_seeds=100, n_trials=100, progress=False)),
        ("Figure 5 widget redraw, 20 seeds x 60 trials (target <= 0.3 s)", widget_redraw),
        ("run_actor_critic, 100 seeds x 100 trials",
         lambda: experiments.run_actor_critic(n_seeds=100, n_trials=100, progress=False)),
        ("run_rod_toppling, 100 seeds x 300 episodes",
         lambda: experiments.run_rod_toppling(n_seeds=100, n_episodes=300, progress=False)),
    ]
    rows = [(name, f"{best_of(3, run):.3f} s") for name, run in runs]
    buttons_env = icm.envs.load("buttons", physics=True, seed=0, presses_per_trial=20)
    rods_env = icm.envs.load("rods", physics=True, start_cell=(0, 0), max_moves=50)
    scenes = [
        ("button press primitive", buttons_env, np.random.RandomState(0).randint(5, size=20)),
        # forward, right, backward, left around cells (0,0)-(1,1): no rod topples
        ("rod move", rods_env, [0, 3, 1, 2] * 5),
    ]
    for name, env, actions in scenes:
        # Best of 5 for each side separately: this machine's timings vary by ~15%.
        results = [primitive_against_raw_steps(env, actions) for _ in range(5)]
        per_action = min(r[0] for r in results)
        steps = results[0][1]
        raw = min(r[2] for r in results)
        rows += [
            (f"{name}: wall time per action", f"{per_action * 1000:.2f} ms"),
            (f"{name}: physics steps per action", f"{steps:.0f}"),
            (f"{name}: as many raw mujoco.mj_step calls", f"{raw * 1000:.2f} ms"),
            (f"{name}: ratio to raw stepping (target <= 1.25)", f"{per_action / raw:.2f}"),
        ]
    rows.append(("render 640x480, button scene", f"{render_fps(buttons_env):.1f} frames/s"))
    width = max(len(name) for name, _ in rows)
    for name, value in rows:
        print(f"{name:<{width}}  {value:>12}")


if __name__ == "__main__":
    main()
