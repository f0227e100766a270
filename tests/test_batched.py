"""The batched learners give identical numbers to the per-agent ones, seed by seed.

The experiments run all seeds at once (`GoalOrientedBatch`, `ActorCriticBatch`,
the compiled loop of the Q-learner on the batched twins). Here each run is replayed with the per-agent
classes the book teaches (`GoalOrientedAgent`, `ActorCritic`, `QLearner`, one tabular
environment per seed, the same seeds), and every recorded array must be equal, not
close: same choices, same floats.
"""

import math

import numpy as np
import pytest

import icm
from icm.envs import buttons, rods
from icm.experiments import actor_critic as ac_experiment
from icm.experiments import goal_oriented as go_experiment
from icm.experiments import goal_oriented_results
from icm.experiments import rod_toppling as rod_experiment
from icm.experiments.seeding import run_seeds
from icm.learners import (ActorCritic, GoalOrientedAgent, LinearPredictor,
                          NearestNeighbourPredictor, QLearner)
from icm.learners.goal_oriented import GoalOrientedSettings


def obs_of(lights):
    return {"lights": np.asarray(lights), "boxes": np.zeros(2, dtype=np.int64)}


# --- the goal-oriented learner ---------------------------------------------------------

def reference_goal_oriented(n_seeds, n_trials, seed=0, presses_per_trial=3, red_button=2,
                            noisy_button=False, **settings):
    """run_goal_oriented's arrays, from the per-agent classes, one seed at a time, the
    learner built from its settings (`GoalOrientedAgent.from_settings`)."""
    settings = GoalOrientedSettings(**settings)
    interest_per = settings.interest_per
    layouts = buttons.layouts(red_button)
    queries = [(tuple(l.tolist()), b) for l in layouts for b in range(buttons.N_BUTTONS)]
    truth = np.array([buttons.press_outcome(np.array(c), b) for c, b in queries])
    n_actions = buttons.n_actions(noisy_button)
    greens = buttons.green_candidates(red_button)
    out = {k: np.zeros((n_seeds, n_trials, 2)) for k in ("interest", "prediction_error")}
    out["practice"] = np.zeros((n_seeds, n_trials, 2), dtype=np.int64)
    out["presses"] = np.zeros((n_seeds, n_trials, n_actions))
    out["action_interest"] = np.zeros((n_seeds, n_trials, n_actions))
    for run, (env_seed, agent_seed) in enumerate(run_seeds(seed, n_seeds, 2)):
        env = buttons.ButtonConsole(red_button, presses_per_trial, noisy_button=noisy_button,
                                    seed=env_seed)
        agent = GoalOrientedAgent.from_settings(n_actions, settings, seed=agent_seed)
        for trial in range(n_trials):
            step = env.reset()
            while not step.last():
                action = agent.select_action(step.observation)
                next_step = env.step(action)
                agent.learn(step.observation, action, next_step.observation)
                out["practice"][run, trial] += next_step.observation["boxes"]
                out["presses"][run, trial, action] += 1
                step = next_step
            if interest_per == "task":
                for i, task in enumerate(goal_oriented_results.TASKS):
                    out["interest"][run, trial, i] = agent.interest.interest(
                        go_experiment.TASK_KEYS[task])
            else:
                out["interest"][run, trial, 0] = agent.interest.interest(red_button)
                out["interest"][run, trial, 1] = np.mean(
                    [agent.interest.interest(g) for g in greens])
            out["action_interest"][run, trial] = np.mean(
                [agent.action_interests(obs_of(l)) for l in layouts], axis=0)
            predicted = np.array([agent.predictor.predict(c, b, default=(0, 0))
                                  for c, b in queries])
            out["prediction_error"][run, trial] = np.abs(predicted - truth).mean(axis=0)
    return out


GOAL_CASES = [
    {}, {"reading": "literal"}, {"action_weight": 1.0}, {"presses_per_trial": 5},
    {"epsilon": 0.0}, {"epsilon": 1.0}, {"window": 8, "new_task_factor": 0.0},
    {"red_button": 0},
    {"interest": "prediction_error"}, {"interest": "novelty"}, {"interest": "random"},
    {"interest_per": "region"}, {"interest_per": "region", "interest": "prediction_error"},
    {"noisy_button": True}, {"noisy_button": True, "interest_per": "region",
                             "interest": "prediction_error"},
    {"noisy_button": True, "interest_per": "region"},
    {"noisy_button": True, "interest_per": "region", "interest": "novelty"},
    {"noisy_button": True, "interest": "random", "red_button": 4},
    # The readings of what the paper leaves open (the book's choice is the default).
    {"new_task_mean": "witnessed"}, {"short_history": "zero"}, {"tie": "earliest"},
    {"tie": "earliest", "action_weight": 1.0}, {"short_history": "zero", "window": 8},
    {"new_task_mean": "witnessed", "interest_per": "region", "noisy_button": True},
]


@pytest.mark.parametrize("case", GOAL_CASES, ids=lambda c: ",".join(f"{k}={v}" for k, v in c.items()) or "default")
def test_goal_oriented_batch_equals_the_per_agent_learner(case):
    batched = icm.experiments.run_goal_oriented(n_seeds=5, n_trials=30, seed=7,
                                                progress=False, **case)
    reference = reference_goal_oriented(5, 30, seed=7, **case)
    for name in ("interest", "prediction_error", "practice", "action_interest"):
        np.testing.assert_array_equal(getattr(batched, name), reference[name], err_msg=name)
    presses = batched.settings["presses_per_trial"]
    np.testing.assert_array_equal(batched.button_share, reference["presses"] / presses)


def test_seed_k_of_a_batch_equals_seed_k_alone_and_settings_ride_the_batch_axis():
    from icm.learners.goal_oriented import GoalOrientedBatch

    seeds = run_seeds(3, 6, 2)
    contexts = np.array(buttons.layouts())

    def play(rows, epsilon, window):
        env = buttons.ButtonConsoleBatch([seeds[r][0] for r in rows])
        agent = GoalOrientedBatch([seeds[r][1] for r in rows], contexts, buttons.EFFECTS, 5,
                                  epsilon=epsilon, window=window)
        record = []
        for _ in range(40):
            layout = env.new_trials()
            for _ in range(3):
                actions = agent.select_actions(layout)
                agent.learn(layout, actions, env.press(actions))
            record.append(agent.interest.values().copy())
        return np.array(record)

    together = play(range(6), np.array([0.1, 0.1, 0.3, 0.3, 0.0, 0.0]),
                    np.array([5, 5, 3, 3, 8, 8]))
    for row, (epsilon, window) in enumerate([(0.1, 5), (0.1, 5), (0.3, 3), (0.3, 3),
                                             (0.0, 8), (0.0, 8)]):
        alone = play([row], epsilon, window)
        np.testing.assert_array_equal(together[:, row], alone[:, 0])


# --- the actor-critic ---------------------------------------------------------------------

def reference_actor_critic(n_seeds, n_trials, seed=0, temperature=0.2, lr_actor=0.5,
                           lr_critic=0.5, gamma=0.5, reward="intrinsic", variant="standard",
                           rewarded_box="green", action_selection="softmax", epsilon=0.1,
                           action_weight=10.0, presses_per_trial=3, red_button=2):
    """run_actor_critic's arrays, from the per-agent ActorCritic, one seed at a time."""
    shape = (n_seeds, n_trials, 2)
    out = {"prediction_error": np.zeros(shape), "press_probability": np.zeros(shape),
           "practice": np.zeros(shape, dtype=np.int64), "reward": np.zeros(shape[:2]),
           "max_abs_value": np.zeros(shape[:2])}
    queries = ac_experiment.probe_queries(red_button)
    starts = [tuple(l.tolist()) + (0, 0) for l in buttons.layouts(red_button)]
    greens = buttons.green_candidates(red_button)
    for run, (env_seed, agent_seed) in enumerate(run_seeds(seed, n_seeds, 2)):
        env = buttons.ButtonConsole(red_button, presses_per_trial,
                                    rewarded_box if reward == "extrinsic" else None,
                                    seed=env_seed)
        agent = ActorCritic(5, temperature, lr_actor, lr_critic, gamma, reward, variant,
                            NearestNeighbourPredictor(action_weight),
                            action_selection=action_selection, epsilon=epsilon,
                            seed=agent_seed)
        for trial in range(n_trials):
            step = env.reset()
            while not step.last():
                action = agent.select_action(step.observation)
                next_step = env.step(action)
                r, _ = agent.learn(step.observation, action, next_step.observation,
                                   next_step.reward, next_step.discount)
                out["reward"][run, trial] += r
                out["practice"][run, trial] += next_step.observation["boxes"]
                step = next_step
            for task, state, button, truth in queries:
                error = math.dist(agent.predict(state, button), truth)
                if task == "red":
                    out["prediction_error"][run, trial, 0] = error
                else:
                    out["prediction_error"][run, trial, 1] += error / 4
            for state, green in zip(starts, greens):
                policy = agent.policy(state)
                out["press_probability"][run, trial, 0] += policy[red_button] / len(starts)
                out["press_probability"][run, trial, 1] += policy[green] / len(starts)
            out["max_abs_value"][run, trial] = max(map(abs, agent.critic.values()), default=0.0)
    return out


AC_CASES = [
    {}, {"variant": "printed_td"}, {"variant": "printed_reward"}, {"variant": "printed"},
    {"reward": "extrinsic"}, {"reward": "extrinsic", "rewarded_box": "red"},
    {"reward": "extrinsic", "action_selection": "epsilon_greedy"},
    {"action_selection": "epsilon_greedy", "epsilon": 0.3},
    {"temperature": 1e9}, {"temperature": 0.05, "lr_actor": 0.1, "lr_critic": 0.9,
                           "gamma": 0.95},
    {"action_weight": 1.0, "presses_per_trial": 5},
]


@pytest.mark.parametrize("case", AC_CASES, ids=lambda c: ",".join(f"{k}={v}" for k, v in c.items()) or "default")
def test_actor_critic_batch_equals_the_per_agent_learner(case):
    batched = icm.experiments.run_actor_critic(n_seeds=5, n_trials=30, seed=3,
                                               progress=False, **case)
    reference = reference_actor_critic(5, 30, seed=3, **case)
    for name, expected in reference.items():
        np.testing.assert_array_equal(getattr(batched, name), expected, err_msg=name)


# --- the Q-learner on the rods ------------------------------------------------------------

def reference_rod_toppling(n_seeds, n_episodes, seed=0, epsilon=0.1, alpha=0.5, gamma=0.9,
                           predictor_lr=0.2, initial_q=0.1, max_moves=30, start_cell=(0, 0),
                           snapshot_episodes=(), reward="prediction_error", window=5,
                           wobbly_rod=False, off_grid="stay"):
    """run_rod_toppling's arrays, from the per-agent QLearner and LinearPredictor on one
    RodTable per seed, each run kept whole and its moments found afterwards (the
    package's earlier implementation)."""
    n_states, n_actions, grid = rods.N_CELLS, len(rods.ACTIONS), (rods.N_COLUMNS, rods.N_ROWS)
    n_rods = 3 if wobbly_rod else 2
    names = rod_experiment.MOMENTS + tuple(f"episode {e}" for e in snapshot_episodes)
    truth = rod_experiment.true_outcomes()
    if wobbly_rod:  # no red or blue pair topples the wobbly rod
        truth = np.concatenate([truth, np.where(np.isnan(truth[..., :1]), np.nan, 0.0)], axis=-1)
    standing = ~np.isnan(truth[..., 0, 0])
    topples = np.nan_to_num(truth) == 1
    to_grid = lambda h: np.swapaxes(h.reshape((h.shape[0], rods.N_ROWS, rods.N_COLUMNS)
                                              + h.shape[2:]), 1, 2)
    out = {"toppled": np.full((n_seeds, n_episodes), -1),
           "episode_length": np.zeros((n_seeds, n_episodes), dtype=np.int64),
           "edge_moves": np.zeros((n_seeds, n_episodes), dtype=np.int64),
           "prediction_error": np.zeros((n_seeds, n_episodes, n_rods)),
           "rod_error": np.zeros((n_seeds, n_episodes, 2)),
           "rod_error_toppled": np.full((n_seeds, n_episodes, 2), np.nan),
           "predicted_well_toppled": np.full((n_seeds, 2), -1),
           "snapshot_episode": np.full((n_seeds, len(names)), -1),
           "q_table": np.full((n_seeds, len(names)) + grid + (n_actions,), np.nan),
           "predictions": np.full((n_seeds, len(names)) + grid + (n_actions, n_rods), np.nan),
           "confidence": np.full((n_seeds, len(names)) + grid, np.nan)}
    for run, (env_seed, agent_seed) in enumerate(run_seeds(seed, n_seeds, 2)):
        env = rods.RodTable(start_cell, max_moves, wobbly_rod=wobbly_rod, seed=env_seed,
                            off_grid=off_grid)
        predictor = LinearPredictor(n_actions, n_rods, lr=predictor_lr)
        agent = QLearner(n_states, n_actions, predictor, alpha, gamma, epsilon, initial_q,
                         reward=reward, window=window, seed=agent_seed)
        q_history = np.zeros((n_episodes, n_states, n_actions))
        p_history = np.zeros((n_episodes, n_states, n_actions, n_rods))
        c_history = np.zeros((n_episodes, n_states))
        found = np.full((n_states, n_actions, n_rods), n_episodes)
        for episode in range(n_episodes):
            state = rods.cell_number(env.reset().observation["hand"])
            episode_errors = np.zeros(n_rods)
            moves = 0
            while True:
                action = agent.select_action(state)
                step = env.step(action)
                observed = step.observation["rods"].tolist()
                next_state = rods.cell_number(step.observation["hand"])
                if reward == "prediction_error":  # the package's earlier implementation
                    errors = predictor.update_per_output(state, action, observed)
                    agent.update(state, action, sum(errors), next_state, step.discount)
                else:  # the per-agent learner's own step
                    errors = [abs(o - p) for o, p in zip(observed, predictor.predict(state, action))]
                    agent.learn(state, action, observed, next_state, step.discount)
                episode_errors += errors
                moves += 1
                out["edge_moves"][run, episode] += next_state == state  # off the grid
                if step.last():
                    break
                state = next_state
            out["episode_length"][run, episode] = moves
            out["prediction_error"][run, episode] = episode_errors
            if any(observed):
                rod = observed.index(1)
                out["toppled"][run, episode] = rod
                found[state, action, rod] = min(found[state, action, rod], episode)
            q_history[episode] = agent.q
            p_history[episode] = predictor.table(range(n_states))
            c_history[episode] = [predictor.confidence(s) for s in range(n_states)]
        q_grid, p_grid, c_grid = to_grid(q_history), to_grid(p_history), to_grid(c_history)
        pair_error = np.abs(truth[None] - p_grid).sum(axis=-1)
        found_grid = to_grid(found[None])[0]
        episodes = np.arange(n_episodes)[:, None, None, None]
        for i in range(2):
            out["rod_error"][run, :, i] = pair_error[:, topples[..., i]].max(axis=1)
            known = (found_grid[None, ..., i] <= episodes) & topples[None, ..., i]
            any_known = known.any(axis=(1, 2, 3))
            known_error = np.where(known, pair_error, -np.inf).max(axis=(1, 2, 3))
            out["rod_error_toppled"][run, any_known, i] = known_error[any_known]
            good = np.flatnonzero(any_known & (known_error < 0.1))
            out["predicted_well_toppled"][run, i] = good[0] + 1 if good.size else -1
        red_well = icm.stats.first_from_which(out["rod_error"][run, :, 0] < 0.1)
        blue_hits = np.flatnonzero(out["toppled"][run] == 1)
        chosen = [0, int(red_well), out["predicted_well_toppled"][run, 0] - 1,
                  int(blue_hits[0]) if blue_hits.size else -1]
        chosen += [e - 1 for e in snapshot_episodes]
        for k, index in enumerate(chosen):
            if index < 0:
                continue
            out["snapshot_episode"][run, k] = index + 1
            out["q_table"][run, k] = np.where(standing[..., None], q_grid[index], np.nan)
            out["predictions"][run, k] = np.where(standing[..., None, None], p_grid[index],
                                                  np.nan)
            out["confidence"][run, k] = np.where(standing, c_grid[index], np.nan)
    well = icm.stats.first_from_which(np.moveaxis(out["rod_error"] < 0.1, 1, 2))
    out["predicted_well"] = np.where(well >= 0, well + 1, -1)
    return out


ROD_CASES = [{}, {"epsilon": 0.0}, {"initial_q": 0.0}, {"initial_q": 1.0},
             {"predictor_lr": 1.0}, {"gamma": 0.0, "alpha": 1.0}, {"epsilon": 1.0},
             {"max_moves": 5}, {"start_cell": (4, 0)}, {"snapshot_episodes": (1, 17, 60)},
             {"reward": "learning_progress"}, {"reward": "learning_progress", "window": 3},
             {"reward": "novelty"}, {"reward": "random"}, {"wobbly_rod": True},
             {"wobbly_rod": True, "reward": "learning_progress"},
             {"wobbly_rod": True, "reward": "random", "max_moves": 5},
             {"max_moves": None}, {"off_grid": "end"}, {"off_grid": "end", "max_moves": None},
             {"off_grid": "end", "reward": "learning_progress", "wobbly_rod": True},
             {"reward": "random", "max_moves": None, "epsilon": 0.0}]


@pytest.mark.parametrize("case", ROD_CASES, ids=lambda c: ",".join(f"{k}={v}" for k, v in c.items()) or "default")
def test_q_learner_batch_equals_the_per_agent_learner(case):
    batched = icm.experiments.run_rod_toppling(n_seeds=5, n_episodes=60, seed=5,
                                               progress=False, **case)
    reference = reference_rod_toppling(5, 60, seed=5, **case)
    for name, expected in reference.items():
        np.testing.assert_array_equal(getattr(batched, name), expected, err_msg=name)


def test_rod_results_of_a_batch_equal_those_of_each_run_alone():
    batch = icm.experiments.run_rod_toppling(n_seeds=5, n_episodes=120, seed=9,
                                             snapshot_episodes=(40,), progress=False)
    for k in range(5):
        alone = icm.experiments.run_rod_toppling(n_seeds=1, n_episodes=120, seed=9, first_run=k,
                                                 snapshot_episodes=(40,), progress=False)
        for name in ("toppled", "rod_error", "rod_error_toppled", "predicted_well",
                     "predicted_well_toppled", "snapshot_episode", "q_table", "predictions",
                     "confidence"):
            np.testing.assert_array_equal(getattr(batch, name)[k], getattr(alone, name)[0],
                                          err_msg=name)


def test_q_learner_batch_equals_the_per_agent_learner_when_the_wobbly_rod_draws_often():
    """Long enough that the tables' streams and the learners' refill many times
    between runs of the compiled loop (and the learners' buffer grows to full size)."""
    batched = icm.experiments.run_rod_toppling(n_seeds=3, n_episodes=300, seed=5,
                                               wobbly_rod=True, progress=False)
    reference = reference_rod_toppling(3, 300, seed=5, wobbly_rod=True)
    for name, expected in reference.items():
        np.testing.assert_array_equal(getattr(batched, name), expected, err_msg=name)
