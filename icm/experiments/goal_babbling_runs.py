"""The goal-babbling runs the chapter "Forming actions" shows: the three strategies
(`goal_babbling.STRATEGIES`) on the chapter's seeds, kept in
assets/goal_babbling_runs.npz because they take about two minutes of CPU, which every
build of the book would otherwise spend again.

`chapter_runs()` reads them (`chapter_runs(recompute=True)` runs them again, with the
same numbers); `run_chapter` runs them with `run_goal_babbling`; `main` writes the
file (`python -m icm.experiments.goal_babbling_runs`) with the settings of each run
and the versions of Python, NumPy and MuJoCo that computed it; a test reruns the first
seed of each strategy (the first k seeds of a root seed are the same in any larger
run) and expects the file's arrays, exactly. After changing goal babbling, write the
file again and commit it.
"""

import dataclasses
import json
import platform

import numpy as np

from icm import _validate
from icm.store import ASSETS, asset_path
from icm.experiments import babbling_results, goal_babbling

RUNS_FILE = "goal_babbling_runs.npz"
"""The file in assets/ that holds the chapter's runs."""
N_SEEDS = 10
"""The chapter's seeds per strategy."""
SEED = 0
"""The chapter's root seed."""
ARRAYS = tuple(field.name for field in dataclasses.fields(babbling_results.GoalBabblingResult)
               if field.name != "settings")
"""The arrays of a `GoalBabblingResult`, each kept whole."""


def run_chapter(n_seeds=N_SEEDS, seed=SEED, progress=True):
    """Runs the three strategies with the defaults of `run_goal_babbling` on the first
    `n_seeds` seeds of the root seed `seed`: {strategy: GoalBabblingResult}, in the
    order of `goal_babbling.STRATEGIES`.

    Args:
      n_seeds: seeds per strategy (>= 1).
      seed: the root seed (an integer >= 0).
      progress: show progress bars.
    """
    n_seeds = _validate.integer_at_least("n_seeds", n_seeds, 1)
    seed = _validate.seed("seed", seed)
    return {strategy: goal_babbling.run_goal_babbling(strategy, n_seeds=n_seeds, seed=seed,
                                                      progress=progress)
            for strategy in goal_babbling.STRATEGIES}


def chapter_runs(recompute=False, progress=True):
    """The chapter's runs, {strategy: GoalBabblingResult}: the three strategies on
    `N_SEEDS` seeds of root seed `SEED` at the default budget.

    Args:
      recompute: run them again (about two minutes of CPU) instead of reading them
        from assets/goal_babbling_runs.npz; the numbers are the same.
      progress: show progress bars while recomputing.
    """
    if _validate.boolean("recompute", recompute):
        return run_chapter(progress=progress)
    return load_runs()


def versions():
    """The versions that compute the runs: Python, NumPy and MuJoCo, and the machine's
    kind."""
    import mujoco
    return {"python": platform.python_version(), "numpy": np.__version__,
            "mujoco": mujoco.__version__, "machine": platform.machine()}


def save_runs(results, path):
    """Writes `results` ({strategy: GoalBabblingResult}) to the .npz file `path`, every
    array whole, with each run's settings and `versions()`."""
    arrays = {f"{strategy}/{name}": getattr(result, name)
              for strategy, result in results.items() for name in ARRAYS}
    about = {"settings": {strategy: result.settings for strategy, result in results.items()},
             "versions": versions()}
    arrays["about"] = np.array(json.dumps(about))  # the strategies in their order
    np.savez_compressed(path, **arrays)


def load_runs(path=None):
    """The runs `save_runs` wrote, as {strategy: GoalBabblingResult} (default: the
    chapter's, assets/goal_babbling_runs.npz)."""
    path = asset_path(RUNS_FILE) if path is None else path
    with np.load(path, allow_pickle=False) as stored:
        about = json.loads(str(stored["about"]))
        out = {}
        for strategy, settings in about["settings"].items():
            settings = dict(settings, demonstrations=tuple(settings["demonstrations"]))
            out[strategy] = babbling_results.GoalBabblingResult(
                settings, **{name: stored[f"{strategy}/{name}"] for name in ARRAYS})
    return out


def recorded_versions(path=None):
    """The versions (`versions()`) recorded with the stored runs."""
    path = asset_path(RUNS_FILE) if path is None else path
    with np.load(path, allow_pickle=False) as stored:
        return json.loads(str(stored["about"]))["versions"]


def main():
    """Runs the chapter's runs and writes assets/goal_babbling_runs.npz."""
    path = ASSETS / RUNS_FILE
    save_runs(run_chapter(), path)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
