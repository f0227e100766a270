"""Benchmarks: prints how long the main computations take on this machine (`make bench`).

Timings are the best of several repeats, in seconds, on one core.
"""

import time

import icm
from icm import widgets


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


def main():
    rows = [
        ("run_goal_oriented, 100 seeds x 100 trials (target <= 1 s)",
         best_of(3, lambda: icm.experiments.run_goal_oriented(n_seeds=100, n_trials=100))),
        ("Figure 5 widget redraw, 20 seeds x 60 trials (target <= 0.3 s)",
         best_of(3, widget_redraw)),
    ]
    width = max(len(name) for name, _ in rows)
    for name, seconds in rows:
        print(f"{name:<{width}}  {seconds:8.3f} s")


if __name__ == "__main__":
    main()
