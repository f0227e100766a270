"""Goal babbling's choices, pinned by behaviour (issue 18, section 3): the exploration
noise shrinks near the goal, a region's interest is learning progress (distances going
down), and a share epsilon of the goals fall in a region chosen uniformly.

The checks read a run through its public result (goals, outcomes, movements, regions,
interest), so they hold whatever module the inverse model and the goal choice live in;
`test_a_region_is_chosen_uniformly_with_probability_epsilon` alone calls the goal
choice itself (`icm.learners.goal_choice.choose_region`, two uniform draws per choice).
"""

import numpy as np
import pytest

from icm.envs import buttons, icub
from icm.experiments import babbling_space, goal_babbling
from icm.learners import goal_choice

N_ROLLOUTS = 200


@pytest.fixture(scope="module")
def run():
    """Learning progress, 2 seeds of 200 rollouts (the first 20 random motor commands)."""
    return goal_babbling.run_goal_babbling("learning_progress", n_seeds=2,
                                           n_rollouts=N_ROLLOUTS, seed=3, progress=False)


def _with_goals(result):
    """The rollouts that had a goal.

    Args:
      result: a `GoalBabblingResult`.

    Returns:
      A list of (seed, rollout) pairs, rollouts counted from 0.
    """
    return [(k, i) for k in range(result.n_seeds) for i in range(result.n_rollouts)
            if result.regions[k, i] >= 0]


# --- the inverse model's exploration noise -------------------------------------------------

def test_the_exploration_noise_shrinks_in_proportion_near_the_goal(run):
    # The inverse model takes the movement whose outcome is nearest the goal and adds
    # Gaussian noise to each joint target: standard deviation 0.05 of the joint's range
    # while that outcome is 5 cm or more from the goal, times (distance / 5 cm) nearer.
    # Distances are in the run's outcome space (by default the finger's point and the
    # caps' depths, weighted).
    assert run.settings["exploration_noise"] == 0.05
    space, weight = run.settings["outcome_space"], run.settings["depth_weight"]
    arm = icub.Arm(buttons.load_physics())
    full = 0.05 * (arm.upper - arm.lower)
    near, far = [], []
    for k, i in _with_goals(run):
        reached = babbling_space.outcome_vectors(run.outcomes[k, :i], run.depths[k, :i],
                                                space, weight)
        wanted = babbling_space.goal_outcomes(run.goals[k, i], space, weight)
        distances = np.linalg.norm(reached - wanted, axis=1)
        nearest = int(np.argmin(distances))
        movement = run.movements[k, i]
        free = (movement > arm.lower) & (movement < arm.upper)  # not clipped at a limit
        z = ((movement - run.movements[k, nearest]) / full)[free]
        distance = distances[nearest]
        if distance >= 0.05:
            far.append(z)
        else:
            near.append((z, distance))
    assert len(far) >= 100 and len(near) >= 100
    far_z = np.concatenate(far)
    assert 0.85 < far_z.std() < 1.15  # the full noise
    near_z = np.concatenate([z for z, _ in near])
    scaled = np.concatenate([z / (d / 0.05) for z, d in near])
    assert 0.85 < scaled.std() < 1.15  # the full noise once the shrinking is undone
    assert near_z.std() < 0.8  # so it is smaller near the goal, ...
    closest = np.concatenate([z for z, d in near if d < 0.02])
    assert closest.size >= 50 and closest.std() < 0.5  # ... and smaller still nearer


# --- the regions' interest --------------------------------------------------------------

def test_a_regions_interest_is_learning_progress_not_distances_going_up(run):
    # After each rollout with a goal, the distance between goal and outcome (in the
    # run's outcome space) joins its region's history; a region's interest is the
    # decrease of its last `window` distances (minus the least-squares slope, 0 if they
    # go up); a region with one distance gets half the mean interest of the others (the
    # paper's new-task share).
    window = run.settings["window"]
    space, weight = run.settings["outcome_space"], run.settings["depth_weight"]
    up = down = 0
    for k in range(run.n_seeds):
        history = {}
        for i in range(run.n_rollouts):
            region = run.regions[k, i]
            if region < 0:
                assert not run.interest[k, i].any()
                continue
            reached = babbling_space.outcome_vectors(run.outcomes[k, i], run.depths[k, i],
                                                    space, weight)
            distance = np.linalg.norm(babbling_space.goal_outcomes(run.goals[k, i], space,
                                                                  weight) - reached)
            history.setdefault(int(region), []).append(distance)
            known = {}
            for r, distances in history.items():
                if len(distances) >= 2:
                    recent = distances[-window:]
                    slope = np.polyfit(np.arange(len(recent)), recent, 1)[0]
                    known[r] = max(0.0, -slope)
                    up, down = up + (slope > 1e-9), down + (slope < -1e-9)
            share = 0.5 * np.mean(list(known.values())) if known else 0.0
            expected = np.zeros(run.interest.shape[2])
            for r, distances in history.items():
                expected[r] = known.get(r, share)
            np.testing.assert_allclose(run.interest[k, i], expected, rtol=0, atol=1e-12,
                                       err_msg=f"seed {k}, rollout {i}")
    assert up >= 100 and down >= 100  # both directions were met


# --- the share of goals in a region chosen uniformly ---------------------------------------

class _Draws:
    """A stand-in for a generator that gives the goal choice the uniform numbers it is
    told to.

    Args:
      numbers: the numbers `random` returns, in order.
    """

    def __init__(self, numbers):
        self.numbers = list(numbers)

    def random(self, size):
        """The next `size` numbers, as an array."""
        drawn, self.numbers = self.numbers[:size], self.numbers[size:]
        return np.array(drawn)


def test_a_region_is_chosen_uniformly_with_probability_epsilon():
    choose = goal_choice.choose_region
    n = int(np.prod(babbling_space.REGION_GRID))
    interest = np.zeros(n)
    interest[3] = 1.0
    # Given draws: the first number below epsilon picks the region uniformly by the
    # second, floor(second * regions); above it, by interest; no interest, uniformly.
    assert choose(interest, 0.3, _Draws([0.29, 0.5])) == int(0.5 * n)
    assert choose(interest, 0.3, _Draws([0.31, 0.5])) == 3
    assert choose(np.zeros(n), 0.3, _Draws([0.9, 0.5])) == int(0.5 * n)
    # Frequencies: a share epsilon of choices is uniform over the regions, the rest in
    # proportion to the interest (here 1 and 3 in regions 5 and 9).
    interest = np.zeros(n)
    interest[[5, 9]] = [1.0, 3.0]
    rng = np.random.default_rng(0)
    counts = np.bincount([choose(interest, 0.3, rng) for _ in range(20_000)], minlength=n)
    expected = np.full(n, 0.3 / n)
    expected[[5, 9]] += 0.7 * np.array([0.25, 0.75])
    np.testing.assert_allclose(counts / 20_000, expected, atol=0.006)
    # The runs' default share is 0.3 (explauto's).
    assert goal_choice.DEFAULT_EPSILON == 0.3


def test_a_run_draws_a_share_epsilon_of_its_goals_in_uniformly_chosen_regions(run):
    # A region of no interest is chosen only uniformly: with probability 0.3 times the
    # share of such regions (or that share while no region has interest). Over the run,
    # the count of such choices is that sum of probabilities, within 3 standard
    # deviations.
    assert run.settings["epsilon"] == 0.3
    observed = expected = variance = 0.0
    for k, i in _with_goals(run):
        before = run.interest[k, i - 1]  # the interest the choice saw
        idle = before == 0
        p = idle.mean() * (0.3 if before.any() else 1.0)
        observed += idle[run.regions[k, i]]
        expected, variance = expected + p, variance + p * (1 - p)
    assert abs(observed - expected) < 3 * np.sqrt(variance)
    assert expected > 50
