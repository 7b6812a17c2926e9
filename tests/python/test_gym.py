"""retrace.gym.TeachRepeatEnv against Gymnasium's contract, checked as gymnasium's env_checker
does (Gymnasium itself is not installable here): reset() and step() return types and shapes,
observations inside the observation space, the same seed giving the same episode, terminated vs
truncated, and step() before reset() refused."""

import numpy as np
import pytest

from conftest import SMALL
from retrace import gym as rgym


@pytest.fixture(scope="module")
def env():
    return rgym.TeachRepeatEnv(SMALL, mode="partial")


def follow(observation):
    """A scripted policy: drive towards the taught path's point 1 m ahead (pure pursuit)."""
    x, y = observation["path"][1]
    curvature = 2.0 * y / max(x * x + y * y, 1e-6)
    return np.array([0.5, np.clip(0.5 * curvature, -1.5, 1.5)], dtype=np.float32)


def check_observation(env, observation):
    assert isinstance(observation, dict)
    assert set(observation) == {"scan", "odometry", "path"}
    for key, value in observation.items():
        space = env.observation_space[key]
        assert isinstance(value, np.ndarray), key
        assert value.shape == space.shape, key
        assert value.dtype == space.dtype, key
    assert env.observation_space.contains(observation)


def test_spaces_are_described_with_shape_dtype_and_bounds(env):
    scan = env.observation_space["scan"]
    assert scan.dtype == np.float32 and scan.shape[0] > 100
    assert np.all(scan.low == 0.0) and np.all(np.isfinite(scan.high))
    assert env.observation_space["odometry"].shape == (3,)
    assert env.observation_space["path"].shape == (10, 2)
    assert env.action_space.shape == (2,) and env.action_space.dtype == np.float32
    assert np.all(env.action_space.low < 0) and np.all(env.action_space.high > 0)
    assert env.action_space.contains(env.action_space.sample())


def test_step_before_reset_is_refused():
    fresh = rgym.TeachRepeatEnv(SMALL, mode="partial")
    with pytest.raises(RuntimeError, match="reset"):
        fresh.step(np.zeros(2, dtype=np.float32))


def test_reset_and_step_return_gymnasiums_types(env):
    observation, info = env.reset(seed=1)
    check_observation(env, observation)
    assert isinstance(info, dict)
    for _ in range(20):
        observation, reward, terminated, truncated, info = env.step(follow(observation))
        check_observation(env, observation)
        assert isinstance(reward, float) and np.isfinite(reward)
        assert isinstance(terminated, bool) and isinstance(truncated, bool)
        assert isinstance(info, dict) and info["tick"]["time"] > 0
    with pytest.raises(ValueError, match="action"):
        env.step(np.array([np.nan, 0.0]))


def run_episode(env, seed, steps=None):
    observation, _ = env.reset(seed=seed)
    trace, total = [observation["odometry"].copy()], 0.0
    n = 0
    while True:
        observation, reward, terminated, truncated, info = env.step(follow(observation))
        trace.append(observation["odometry"].copy())
        total += reward
        n += 1
        if terminated or truncated or (steps is not None and n >= steps):
            return np.array(trace), total, terminated, truncated, info


def test_the_same_seed_gives_the_same_episode(env):
    a, ra, _, _, _ = run_episode(env, seed=2, steps=200)
    b, rb, _, _, _ = run_episode(env, seed=2, steps=200)
    assert np.array_equal(a, b) and ra == rb
    c, _, _, _, _ = run_episode(env, seed=3, steps=200)
    assert not np.array_equal(a, c)


def test_a_scripted_policy_drives_the_route_and_terminates_with_the_runs_metrics(env):
    _, total, terminated, truncated, info = run_episode(env, seed=1)
    metrics = info["metrics"]
    assert metrics["outcome"] in ("success", "collision", "lost", "timeout")
    assert terminated == (metrics["outcome"] != "timeout")
    assert truncated == (not terminated)
    assert total > 0.0  # it made progress along the route


def test_max_steps_truncates():
    short = rgym.TeachRepeatEnv(SMALL, mode="partial", max_steps=5)
    observation, _ = short.reset(seed=1)
    flags = []
    for _ in range(5):
        observation, _, terminated, truncated, _ = short.step(follow(observation))
        flags.append((terminated, truncated))
    assert flags[-1] == (False, True) and all(f == (False, False) for f in flags[:-1])


def test_a_bad_reward_term_is_refused():
    with pytest.raises(ValueError, match="reward: unknown terms"):
        rgym.TeachRepeatEnv(SMALL, reward={"speed": 1.0})
