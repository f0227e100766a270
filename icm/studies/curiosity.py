"""The study "curiosity": the interest signals on the buttons and the intrinsic rewards
on the rods of the chapter "Which curiosity?", on many seeds, one setting and its seeds
a unit (`python -m icm study curiosity`): every signal (`icm.learners.interest.SIGNALS`)
at both places of interest in both worlds, and every reward (`icm.learners.q_learning.
REWARDS`) with and without the wobbly rod, each run's `seed_summaries()` kept. A signal
or a reward added to its registry is in the study from then on.
"""

import itertools

from icm.experiments import goal_oriented, rod_toppling
from icm.learners import goal_oriented as goal_oriented_learner
from icm.learners import interest, q_learning
from icm.studies.registry import Study, plain, register

CURIOSITY_SEED = 0
"""The root seed of the comparisons' runs (that of the curiosity functions' default)."""


def units(settings):
    """The study's units: ["signal", signal, interest_per, noisy_button] for every
    signal, place of interest and world, then ["reward", reward, wobbly_rod] for every
    reward and world."""
    return ([["signal", s, per, noisy] for s, per, noisy in itertools.product(
                interest.SIGNALS, goal_oriented_learner.INTEREST_PER, (False, True))]
            + [["reward", r, wobbly] for r, wobbly in itertools.product(
                q_learning.REWARDS, (False, True))])


def run_unit(settings, unit):
    """One setting of `icm.experiments.curiosity.run_signal_comparison` or
    `run_reward_comparison` on all the study's seeds (the same seeds for every setting,
    as there): its runs' `seed_summaries()`."""
    if unit[0] == "signal":
        _, signal, per, noisy = unit
        result = goal_oriented.run_goal_oriented(
            n_seeds=settings["seeds"], n_trials=settings["trials"], interest=signal,
            interest_per=per, noisy_button=noisy, seed=CURIOSITY_SEED, progress=False)
    else:
        _, reward, wobbly = unit
        result = rod_toppling.run_rod_toppling(
            n_seeds=settings["seeds"], n_episodes=settings["episodes"], reward=reward,
            wobbly_rod=wobbly, seed=CURIOSITY_SEED, progress=False)
    return plain(result.seed_summaries())


SEED_SECONDS = 0.0005
"""CPU seconds a seed of one setting costs, roughly, at the study's default trials (100)
or episodes (300), in proportion to them: the 24 settings at 100 seeds took 0.04 s each
(2026-12-05)."""


def unit_seconds(settings, unit):
    """A rough figure of one unit's CPU seconds (`SEED_SECONDS`): `Study.unit_seconds`."""
    length = settings["trials"] / 100 if unit[0] == "signal" else settings["episodes"] / 300
    return SEED_SECONDS * settings["seeds"] * length


def assemble(settings, units, results):
    """The study's file: {"n_seeds", "n_trials", "n_episodes", "seed", "signals":
    {"signal|interest_per|noisy": rows}, "rewards": {"reward|wobbly": rows}}."""
    signals = {"|".join(map(str, u[1:])): r for u, r in zip(units, results)
               if u[0] == "signal"}
    rewards = {"|".join(map(str, u[1:])): r for u, r in zip(units, results)
               if u[0] == "reward"}
    return {"n_seeds": settings["seeds"], "n_trials": settings["trials"],
            "n_episodes": settings["episodes"], "seed": CURIOSITY_SEED,
            "signals": signals, "rewards": rewards}


register(Study(
    name="curiosity",
    description="the interest signals on the buttons and the intrinsic rewards on the rods "
                "(icm.studies.curiosity), one setting and its seeds a unit",
    seeds=(100, "per setting, the same for every setting"),
    options={"trials": (100, 1, "trials per run on the buttons"),
             "episodes": (300, 1, "episodes per run on the rods")},
    units=units, run_unit=run_unit, assemble=assemble, unit_seconds=unit_seconds,
    seeding=(f"every setting runs seeds 0..n-1 of root seed {CURIOSITY_SEED} (the same "
             "seeds for every setting, as in icm.experiments.curiosity)")))
