"""Benchmarks: how long the main computations take on this machine (`make bench`).

This machine's speed varies from run to run (by up to two times, seen here), so every
figure is printed with its ratio to a fixed reference workload timed in the same run,
alternately with it: a ratio moves much less than a time. Each figure is the best of
several repeats. The targets are those of the project's speed issue, in seconds on this
machine; a figure is marked "ok" when it meets its target.

It also reports where the book's execution and the test suite spend their time, from
the records the last book build and test run left in _build/ (each with the reference
workload timed in its own minutes): the execution per chapter and its slowest cells,
and the ten slowest tests.

    python benchmarks/bench.py [--quick] [--records]
"""

import argparse
import json
import os
import subprocess
import sys
import time

os.environ.setdefault("MUJOCO_GL", "egl")
# As the book's kernels run (book/_ext/execute_book.py): one BLAS thread, since the
# matrices are small and a second thread costs more than it saves.
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "benchmarks"))  # also when loaded by the tests

from reference import reference_seconds, reference_workload  # noqa: E402


def best_of(repeats, function):
    """The best of `repeats` timings of `function`, each next to a timing of the
    reference workload: (seconds, ratio to the reference at its best)."""
    times, references = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        reference_workload()
        references.append(time.perf_counter() - start)
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times), min(times) / min(references)


def subprocess_time(code, repeats=5):
    """The best wall time of running `python -c code` (a fresh interpreter each time)."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return min(times)


def redraw(run, draw, png=None, **settings):
    """A redraw: the run at 100 seeds, the figure and its PNG, made by `png(figure)`
    (a live panel's `icm.widgets._common.panel_png`, at the width and pixel ratio it
    is shown at), or, without it, as a notebook shows the figure (`_repr_png_`)."""
    def go():
        figure = draw(run(n_seeds=100, progress=False, **settings))
        figure._repr_png_() if png is None else png(figure)
    return go


def primitive_against_c(make_env, actions, repeats=5):
    """A discrete action on the physics against the same physics steps in C.

    Returns (wall ms per action, steps per action, C replay ms per action, raw nstep ms
    per action). "C replay" rolls out, with mujoco.rollout from the same initial state,
    the very controls the primitive applied at each step (recorded through
    mujoco.set_mjcb_control in a twin environment): the same trajectory, with no Python
    in between. "raw nstep" is mujoco.mj_step(model, data, nstep=n) from the same state
    with the controls held: the same number of steps, but of an arm at rest.
    """
    import mujoco
    from mujoco import rollout

    # The controls of every step, from a twin environment (same seed, same actions).
    twin = make_env()
    twin.reset()
    controls = []
    mujoco.set_mjcb_control(lambda model, data: controls.append(data.ctrl.copy()))
    try:
        for action in actions:
            twin.step(action)
    finally:
        mujoco.set_mjcb_control(None)
    walls, replays, raws = [], [], []
    for _ in range(repeats):
        env = make_env()
        env.reset()
        model, data = env.physics.model.ptr, env.physics.data.ptr
        spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
        state = np.empty(mujoco.mj_stateSize(model, spec))
        mujoco.mj_getState(model, data, state, spec)
        start = time.perf_counter()
        for action in actions:
            env.step(action)
        walls.append(time.perf_counter() - start)
        n_steps = len(controls)
        scratch = mujoco.MjData(model)
        start = time.perf_counter()
        rollout.rollout(model, scratch, state, np.array(controls)[None], nstep=n_steps)
        replays.append(time.perf_counter() - start)
        mujoco.mj_setState(model, scratch, state, spec)
        scratch.ctrl[:] = controls[0]
        start = time.perf_counter()
        mujoco.mj_step(model, scratch, nstep=n_steps)
        raws.append(time.perf_counter() - start)
    n = len(actions)
    return (min(walls) / n * 1e3, len(controls) / n, min(replays) / n * 1e3,
            min(raws) / n * 1e3)


def babbling_against_raw(repeats=5, n_movements=40):
    """Goal-babbling rollouts per second against raw stepping.

    Figures, each the best of `repeats`: `MovementLab.perform` (the rollouts of a
    run: reach and hold, stepped in C by mujoco.rollout, then measured) on one thread
    and on `movements.default_threads()`, the same with the return home, and the
    rollouts of a whole `run_goal_babbling` (learning progress, 10 seeds, inverse
    model and goal choice included, without the final press test) on one thread and
    on the default threads. Each is set against mujoco.mj_step(model, data, nstep=n)
    on one thread from the same initial state with the controls held, for the same
    number of physics steps: the arm at rest, no contacts, so the ratio is an upper
    bound on the cost of everything but stepping (below 1 with several threads).

    Returns [(name, rollouts per second, raw rollouts per second)].
    """
    import mujoco

    from icm.envs.buttons import movements
    from icm.experiments import goal_babbling

    threads = movements.default_threads()
    labs = {1: movements.MovementLab(threads=1), threads: movements.MovementLab(threads)}
    lab = labs[1]
    targets = np.random.default_rng(0).uniform(lab.lower, lab.upper, (n_movements, 7))
    scratch = mujoco.MjData(lab.model)
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS

    def raw(n_steps):
        mujoco.mj_setState(lab.model, scratch, lab.initial_state, spec)
        scratch.ctrl[:] = lab.initial_ctrl
        mujoco.mj_step(lab.model, scratch, nstep=n_steps)

    def best(function):
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            function()
            times.append(time.perf_counter() - start)
        return min(times)

    n_seeds = 10
    n_rollouts = n_movements // n_seeds

    def whole_run(lab):  # the rollouts of a run (the library's settings), no press test
        return lambda: goal_babbling.babble(
            goal_babbling.make_agent(lab, range(n_seeds), n_rollouts), lab, n_rollouts)

    short, full = lab.outcome_step + 1, lab.n_steps
    cases = [("rollouts, reach and hold, 1 thread", lambda: lab.perform(targets), short),
             ("rollouts with the return home, 1 thread",
              lambda: lab.perform(targets, retract=True), full),
             (f"the rollouts of run_goal_babbling, {n_seeds} seeds, 1 thread", whole_run(lab),
              short)]
    if threads > 1:
        cases[1:1] = [(f"rollouts, reach and hold, {threads} threads",
                       lambda: labs[threads].perform(targets), short)]
        cases.append((f"the rollouts of run_goal_babbling, {n_seeds} seeds, {threads} threads",
                      whole_run(labs[threads]), short))
    out = []
    for name, go, steps in cases:
        go()
        seconds = best(go)
        raw_seconds = best(lambda: raw(steps * n_movements))
        out.append((name, n_movements / seconds, n_movements / raw_seconds))
    return out


RECORDS = os.path.join(ROOT, "_build")
"""Where the last book build and test run leave their records of times."""


def _read_record(name):
    """The JSON record `name` in RECORDS, or None."""
    try:
        with open(os.path.join(RECORDS, name)) as handle:
            return json.load(handle)
    except (OSError, ValueError):
        return None


def book_execution_report(reference, slowest_cells=8):
    """Lines: the book's execution per chapter, from the last build's record
    (`_build/icm-execution-record.json`, written by `make book`, or by `make test` for
    the book it builds), each time with its ratio to the reference workload timed
    in that build; then its slowest cells. `reference`: the workload's time now."""
    record = _read_record("icm-execution-record.json")
    if not record or not record.get("notebooks"):
        return ["The book's execution: no record yet (make book, or make test, writes "
                "_build/icm-execution-record.json)."]
    then = record["reference_seconds"]
    timed = [t for t in (then.get("before"), then.get("after")) if t]
    base = min(timed) if timed else None
    notebooks = record["notebooks"]
    total = sum(n["seconds"] for n in notebooks.values())
    lines = [f"The book's execution, per chapter (the build of {record['finished']}, "
             f"{record['jobs']} notebooks at a time, {record['wall_seconds']:.0f} s wall; "
             f"reference workload then "
             + (" and ".join(f"{t:.4f} s" for t in timed) if timed else "not timed")
             + f", now {reference:.4f} s; ratio = seconds / reference then):"]
    width = max(len(name) for name in notebooks)
    lines.append(f"  {'notebook':<{width}}  {'seconds':>8}  {'ratio':>7}  {'CPU s':>7}  "
                 f"{'share':>6}")
    for name, entry in sorted(notebooks.items(), key=lambda item: -item[1]["seconds"]):
        ratio = f"{entry['seconds'] / base:7.0f}" if base else "      -"
        lines.append(f"  {name:<{width}}  {entry['seconds']:8.1f}  {ratio}  "
                     f"{entry['cpu_seconds']:7.1f}  {entry['seconds'] / total:6.0%}")
    lines.append(f"  {'sum':<{width}}  {total:8.1f}  "
                 + (f"{total / base:7.0f}" if base else "      -")
                 + "  (target: <= 150 s on an idle machine, issue 30)")
    cells = sorted(((cell[1], cell[2], name, cell[0], cell[3])
                    for name, entry in notebooks.items() for cell in entry["cells"]),
                   reverse=True)[:slowest_cells]
    lines.append(f"  its {slowest_cells} slowest cells (seconds, CPU seconds, notebook, "
                 f"cell, first line):")
    lines += [f"    {seconds:6.1f}  {cpu:6.1f}  {name.split('/')[-1]} cell {index}: {code}"
              for seconds, cpu, name, index, code in cells]
    return lines


def slowest_tests_report(reference, count=10):
    """Lines: the test suite's `count` slowest tests, from the last run's record
    (`_build/icm-test-durations.json`, written by each run of the whole suite: `make
    test`), with the reference workload timed at its end."""
    record = _read_record("icm-test-durations.json")
    if not record:
        return ["The test suite's slowest tests: no record yet (make test writes "
                "_build/icm-test-durations.json)."]
    then = record["reference_seconds"]
    lines = [f"The test suite's {count} slowest tests (setup, call and teardown; the run "
             f"of {record['finished']}, `{record['command']}`, {record['tests']} tests in "
             f"{record['wall_seconds']:.0f} s; reference workload then {then:.4f} s, now "
             f"{reference:.4f} s; ratio = seconds / reference then):"]
    lines.append(f"  {'seconds':>9}  {'ratio':>7}  {'CPU s':>7}  test")
    lines += [f"  {entry[1]:7.1f} s  {entry[1] / then:7.0f}  "
              f"{entry[2] if len(entry) > 2 else float('nan'):7.1f}  {entry[0]}"
              for entry in record["durations"][:count]]
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats")
    parser.add_argument("--records", action="store_true",
                        help="only the records of the last book build and test run")
    args = parser.parse_args(argv)
    repeats = 3 if args.quick else 9
    if args.records:
        reference = reference_seconds(repeats)
        print("\n".join(book_execution_report(reference) + [""]
                        + slowest_tests_report(reference)))
        return

    import icm
    from icm import figures
    from icm.experiments import actor_critic, goal_oriented, rod_toppling
    from icm.widgets._common import panel_png

    rows = []

    def row(name, seconds, ratio, target, ratio_target=None):
        met = seconds <= target if ratio_target is None else ratio <= ratio_target
        rows.append((name, f"{seconds:.3f} s", f"{ratio:6.2f}",
                     f"<= {target:g} s" if ratio_target is None else f"<= {ratio_target:g} x",
                     "ok" if met else "MISSED"))

    experiments = icm.experiments
    for name, run, target in [
            ("run_goal_oriented, 100 seeds x 100 trials",
             lambda: experiments.run_goal_oriented(n_seeds=100, n_trials=100, progress=False),
             0.05),
            ("run_actor_critic, 100 seeds x 100 trials",
             lambda: experiments.run_actor_critic(n_seeds=100, n_trials=100, progress=False),
             0.05),
            ("run_rod_toppling, 200 seeds x 300 episodes",
             lambda: experiments.run_rod_toppling(n_seeds=200, n_episodes=300, progress=False),
             1.0)]:
        run()  # warm up (Numba's compiled loop is loaded from its cache)
        row(name, *best_of(repeats, run), target)
    # What a reader waits for when a live slider moves (target: issue 30's 5 times the
    # reference workload for Figure 5), and a figure of the book with the checks its
    # PNG records (text fitted, legends, overlaps, text out of its box), drawn once.
    for name, go, ratio_target in [
            ("Figure 5 panel redraw, 100 seeds, PNG as shown", redraw(
                goal_oriented.run_goal_oriented, figures.figure5_panel_figure, panel_png,
                n_trials=60),
             5.0),
            ("Figure 6 panel redraw, 100 seeds, PNG as shown", redraw(
                actor_critic.run_actor_critic, figures.figure6_panel_figure, panel_png,
                n_trials=60),
             None),
            ("Figure 7 panel redraw, 100 seeds, PNG as shown", redraw(
                rod_toppling.run_rod_toppling, figures.figure7_panel_figure, panel_png,
                n_episodes=150), None),
            ("Figure 5 of the book, 100 seeds, checked PNG", redraw(
                goal_oriented.run_goal_oriented, figures.figure5, n_trials=60), None)]:
        go()
        row(name, *best_of(repeats, go), 0.15, ratio_target)

    from icm.experiments import panel_data

    # The grids' computation (`compute_grid`), not `precompute`, which reads them from
    # assets/ while their panels are unchanged.
    for name, target in (("figure5", 5.0), ("figure6", 20.0), ("figure7", 20.0)):
        spec = panel_data.PANELS[name]
        start = time.perf_counter()
        panel_data.compute_grid(name, progress=False)
        seconds = time.perf_counter() - start
        reference, _ = best_of(1, reference_workload)
        row(f"{name} static panel grid, {len(spec.settings())} settings x "
            f"{spec.fixed['n_seeds']} seeds (once)", seconds, seconds / reference, target)

    reference, _ = best_of(repeats, reference_workload)
    for name, code, target in [
            ("python -m icm --help (fresh interpreter)",
             "import runpy, sys; sys.argv = ['icm', '--help']\n"
             "try:\n runpy.run_module('icm', run_name='__main__')\nexcept SystemExit: pass",
             1.5),
            ("import icm and its learners and experiments (fresh interpreter)",
             "import icm; icm.envs; icm.learners; icm.experiments", 1.5)]:
        seconds = subprocess_time(code)
        row(name, seconds, seconds / reference, target)

    print(f"reference workload: {reference:.4f} s (best of {repeats}); ratio = figure / "
          "reference\n")
    width = max(len(r[0]) for r in rows)
    print(f"{'computation':<{width}}  {'figure':>9}  {'ratio':>6}  {'target':>10}")
    for name, seconds, ratio, target, verdict in rows:
        print(f"{name:<{width}}  {seconds:>9}  {ratio}  {target:>10}  {verdict}")

    print()
    print("\n".join(book_execution_report(reference)))
    print()
    print("\n".join(slowest_tests_report(reference)))

    print("\nPhysics primitives against the same steps in C (target: <= 1.25 x the replay):")
    scenes = [
        ("button press", lambda: icm.envs.load("buttons", physics=True, seed=0,
                                               presses_per_trial=20),
         np.random.RandomState(0).randint(5, size=20).tolist()),
        # forward, right, backward, left around cells (0,0)-(1,1): no rod topples
        ("rod move", lambda: icm.envs.load("rods", physics=True, max_moves=50),
         [0, 3, 1, 2] * 5)]
    for name, make, actions in scenes:
        wall, steps, replay, raw = primitive_against_c(make, actions, 3 if args.quick else 5)
        verdict = "ok" if wall <= 1.25 * replay else "MISSED"
        print(f"  {name}: {wall:.2f} ms per action, {steps:.0f} physics steps; the same "
              f"controls replayed in C (mujoco.rollout) {replay:.2f} ms: {wall / replay:.2f} x "
              f"{verdict}; mj_step(nstep={steps:.0f}) with the arm at rest {raw:.2f} ms: "
              f"{wall / raw:.2f} x")

    print("\nGoal babbling: movements stepped in C (mujoco.rollout) against raw "
          "mj_step(nstep) of the same steps, one thread:")
    for name, per_second, raw_per_second in babbling_against_raw(3 if args.quick else 5):
        print(f"  {name}: {per_second:.0f} rollouts/s; mj_step(nstep) of the same number "
              f"of steps, arm at rest, {raw_per_second:.0f} rollouts/s: "
              f"{raw_per_second / per_second:.2f} x the time")

    env = icm.envs.load("buttons", physics=True, seed=0)
    env.reset()
    env.physics.render(480, 640, camera_id="over_shoulder")
    start = time.perf_counter()
    for _ in range(20):
        env.physics.render(480, 640, camera_id="over_shoulder")
    print(f"\nrender 640x480, button scene: {20 / (time.perf_counter() - start):.1f} frames/s")

    import live_viewer  # benchmarks/live_viewer.py

    print("\nThe live iCub in headless Chromium (benchmarks/live_viewer.py):")
    print("\n".join(live_viewer.report(live_viewer.measure(3 if args.quick else 5))))

    import page_load  # benchmarks/page_load.py

    print("\nThe built book's pages, interactive in headless Chromium, offline, best of "
          "3 (benchmarks/page_load.py):")
    print("\n".join(page_load.report(page_load.measure())))


if __name__ == "__main__":
    main()
