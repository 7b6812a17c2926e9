"""A Gymnasium-shaped environment on retrace's playback loop (docs/PYTHON.md, "Gymnasium").

``TeachRepeatEnv(scenario, mode=...)`` teaches the scenario's route once per seed (``Teaching``)
and drives one playback run per episode (``Episode``): the agent's action is the command
(v, omega); the environment keeps the agent's place on the taught route by dead reckoning in the
taught maps' frames (moving into map k+1 by eq. (1) at the end of path k, as a stack without
localization does) and answers the harness with it, so every run is scored exactly as
``retrace run`` scores a stack.

The class subclasses ``gymnasium.Env`` and its spaces are ``gymnasium.spaces`` when Gymnasium is
installed; without it (Gymnasium is not a Debian package) it offers the same methods and spaces
of the same shape (``Box``, ``Dict`` below), so that code written against Gymnasium runs here.
"""

import math

import numpy as np

from ._retrace import Teaching
from ._retrace import integrate_odometry as _integrate

try:  # pragma: no cover - depends on the user's environment
    import gymnasium
    from gymnasium import spaces as _spaces

    _Env = gymnasium.Env
except ImportError:  # Gymnasium's shape without Gymnasium
    gymnasium = None
    _spaces = None
    _Env = object


class Box:
    """A box in R^n (Gymnasium's ``spaces.Box`` shape): ``low``, ``high``, ``shape``, ``dtype``."""

    def __init__(self, low, high, shape, dtype, seed=None):
        self.shape = tuple(shape)
        self.dtype = np.dtype(dtype)
        self.low = np.broadcast_to(np.asarray(low, dtype=self.dtype), self.shape).copy()
        self.high = np.broadcast_to(np.asarray(high, dtype=self.dtype), self.shape).copy()
        self._rng = np.random.default_rng(seed)

    def seed(self, seed=None):
        self._rng = np.random.default_rng(seed)
        return [seed]

    def contains(self, x):
        x = np.asarray(x)
        return (x.shape == self.shape and np.can_cast(x.dtype, self.dtype, "same_kind")
                and bool(np.all(x >= self.low)) and bool(np.all(x <= self.high)))

    def sample(self):
        low = np.where(np.isfinite(self.low), self.low, -1e3)
        high = np.where(np.isfinite(self.high), self.high, 1e3)
        return self._rng.uniform(low, high).astype(self.dtype)

    def __repr__(self):
        return f"Box({self.low.min()}, {self.high.max()}, {self.shape}, {self.dtype})"


class Dict:
    """A dict of spaces (Gymnasium's ``spaces.Dict`` shape)."""

    def __init__(self, spaces):
        self.spaces = dict(spaces)

    def __getitem__(self, key):
        return self.spaces[key]

    def keys(self):
        return self.spaces.keys()

    def seed(self, seed=None):
        for i, space in enumerate(self.spaces.values()):
            space.seed(None if seed is None else seed + i)

    def contains(self, x):
        return (isinstance(x, dict) and x.keys() == self.spaces.keys()
                and all(space.contains(x[k]) for k, space in self.spaces.items()))

    def sample(self):
        return {k: space.sample() for k, space in self.spaces.items()}


def _box(low, high, shape, dtype):
    if _spaces is not None:
        return _spaces.Box(low=low, high=high, shape=shape, dtype=dtype)
    return Box(low, high, shape, dtype)


def _dict(spaces):
    return _spaces.Dict(spaces) if _spaces is not None else Dict(spaces)


def _compose(a, b):
    """The planar pose a ∘ b; poses are (x, y, yaw) tuples."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], a[2] + b[2])


def _inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2])


#: The reward's terms and their default weights (``TeachRepeatEnv(reward=...)`` replaces any).
DEFAULT_REWARD = {
    "progress": 1.0,     # per metre the estimate advanced along the taught route
    "tracking": -1.0,    # per metre of the estimate's distance from the taught path, per second
    "personal": -1.0,    # per second with a person inside metrics.personal_zone (truth)
    "collision": -10.0,  # once per collision (truth)
    "success": 10.0,     # once, when the run succeeds
}


class TeachRepeatEnv(_Env):
    """One taught route, driven again by a learning agent.

    Observation (a dict):
      ``scan``      (B,) float32, the latest scan's ranges in the LiDAR frame, m; no return and
                    invalid readings are ``range_max``
      ``odometry``  (3,) float64, the run's odometry pose (x, y, yaw) since it started
      ``path``      (P, 2) float32, the next P points of the taught path, ``path_spacing`` m
                    apart, in the robot frame by the dead-reckoned estimate
    Action: (2,) float32 (v m/s, omega rad/s) within ``max_speed``, ``max_yaw_rate``.
    Terminated: success (the route's end reached), a collision (``limits.stop_on_collision`` is
    set), or lost (the run's own end conditions). Truncated: the run's time limit (timeout or
    stall) or ``max_steps``. ``info`` holds the tick as the harness recorded it (``tick``), the
    map, and at the end the run's ``metrics`` as ``retrace run`` writes them.
    """

    metadata = {"render_modes": []}

    def __init__(self, scenario, mode="partial", *, set=(), reward=None, path_points=10,
                 path_spacing=0.5, max_speed=1.0, max_yaw_rate=1.5, max_steps=None,
                 personal_zone=1.2):
        if path_points < 1 or not path_spacing > 0 or not max_speed > 0 or not max_yaw_rate > 0:
            raise ValueError("path_points >= 1, path_spacing, max_speed and max_yaw_rate > 0")
        unknown = (reward or {}).keys() - DEFAULT_REWARD.keys()
        if unknown:
            raise ValueError(f"reward: unknown terms {sorted(unknown)}; "
                             f"expected some of {sorted(DEFAULT_REWARD)}")
        self.scenario, self.mode = str(scenario), mode
        self.overrides = ["limits.stop_on_collision=true"] + list(
            [set] if isinstance(set, str) else set)
        self.reward_weights = {**DEFAULT_REWARD, **(reward or {})}
        self.path_points, self.path_spacing = int(path_points), float(path_spacing)
        self.max_steps = max_steps
        self.personal_zone = float(personal_zone)  # m; metrics.personal_zone's default
        self._teachings = {}
        self._episode = None
        self.teaching = self._teach(None)
        beams = len(self.teaching.recording.scans[0].ranges)
        self._range_max = float(self.teaching.recording.scans[0].range_max)
        self.observation_space = _dict({
            "scan": _box(0.0, self._range_max, (beams,), np.float32),
            "odometry": _box(-np.inf, np.inf, (3,), np.float64),
            "path": _box(-np.inf, np.inf, (self.path_points, 2), np.float32),
        })
        self.action_space = _box(np.array([-max_speed, -max_yaw_rate]),
                                 np.array([max_speed, max_yaw_rate]), (2,), np.float32)

    def _teach(self, seed):
        if seed not in self._teachings:
            self._teachings[seed] = Teaching(self.scenario, mode=self.mode, seed=seed,
                                             set=self.overrides, progress=False)
        return self._teachings[seed]

    def reset(self, *, seed=None, options=None):
        """Starts a run: ``seed`` the scenario's seed (its teaching is reused), ``options``
        {"run": i} the playback run (default 0). Returns (observation, info)."""
        if _Env is not object:
            super().reset(seed=seed)
        options = options or {}
        self.teaching = self._teach(seed)
        self._episode = self.teaching.episode(int(options.get("run", 0)))
        self._maps = self.teaching.maps
        self._paths = [m.path for m in self._maps]
        self._arcs = [np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p[:, :2], axis=0).T))])
                      for p in self._paths]
        self._k, self._i, self._s = 0, 0, 0.0
        self._pose = (0.0, 0.0, 0.0)
        self._odom = (0.0, 0.0, 0.0)
        self._scan = np.full(self.observation_space["scan"].shape, self._range_max, np.float32)
        self._steps, self._collisions = 0, 0
        self._dt = 1.0 / self.teaching.control_rate_hz
        observation = self._observe()
        return observation, {"map": self._k, "tick": None}

    def _observe(self):
        o = self._episode.observe()
        for _, distance, dtheta in o.odometry.tolist():  # dead reckoning, increment by increment
            self._pose = _integrate(self._pose, distance, dtheta)
            self._odom = _integrate(self._odom, distance, dtheta)
        if o.scans:
            r = np.asarray(o.scans[-1].ranges, dtype=np.float32)
            self._scan = np.where(np.isfinite(r), np.minimum(r, self._range_max),
                                  np.float32(self._range_max)).astype(np.float32)
        return self._last_observation()

    def _path_ahead(self):
        path, arc = self._paths[self._k], self._arcs[self._k]
        wanted = arc[self._i] + self.path_spacing * np.arange(1, self.path_points + 1)
        xs = np.interp(wanted, arc, path[:, 0])
        ys = np.interp(wanted, arc, path[:, 1])
        inv = _inverse(self._pose)
        c, s = math.cos(inv[2]), math.sin(inv[2])
        local = np.stack([inv[0] + c * xs - s * ys, inv[1] + s * xs + c * ys], axis=1)
        return local.astype(np.float32)

    def _advance(self):
        """Moves the estimate's place along its map's path; the metres advanced and the
        distance from the path. At the end of a path the next map (eq. (1))."""
        path, arc = self._paths[self._k], self._arcs[self._k]
        ahead = path[self._i:self._i + 40, :2]
        near = np.hypot(ahead[:, 0] - self._pose[0], ahead[:, 1] - self._pose[1])
        step = int(np.argmin(near))
        advanced = float(arc[self._i + step] - arc[self._i])
        self._i += step
        done = self._i == len(path) - 1 and near.min() < 0.3
        if done and self._k + 1 < len(self._maps):
            self._pose = _compose(_inverse(self._maps[self._k].switch_pose), self._pose)
            self._k, self._i = self._k + 1, 0
            done = False
        return advanced, float(near.min()), done

    def step(self, action):
        """Sends (v, omega); returns (observation, reward, terminated, truncated, info)."""
        if self._episode is None or self._episode.done:
            raise RuntimeError("step() needs a running episode: call reset() first")
        a = np.asarray(action, dtype=np.float64).reshape(-1)
        if a.shape != (2,) or not np.all(np.isfinite(a)):
            raise ValueError(f"action: (v, omega), two finite numbers; got {action!r}")
        low, high = self.action_space.low, self.action_space.high
        v = min(max(float(a[0]), float(low[0])), float(high[0]))
        omega = min(max(float(a[1]), float(low[1])), float(high[1]))
        advanced, off_path, route_done = self._advance()
        done = self._episode.act(v, omega, estimate=self._pose, map=self._k,
                                 route_done=route_done)
        self._steps += 1
        tick = self._episode.tick
        w = self.reward_weights
        reward = w["progress"] * advanced + w["tracking"] * off_path * self._dt
        if tick["pedestrian_gap"] < self.personal_zone:
            reward += w["personal"] * self._dt
        reward += w["collision"] * (tick["collisions"] - self._collisions)
        self._collisions = tick["collisions"]
        info = {"map": self._k, "tick": tick}
        terminated = truncated = False
        if done:
            metrics = self._episode.metrics()
            info["metrics"] = metrics
            terminated = metrics["outcome"] in ("success", "collision", "lost")
            truncated = not terminated
            if metrics["success"]:
                reward += w["success"]
            return self._last_observation(), float(reward), terminated, truncated, info
        if self.max_steps is not None and self._steps >= self.max_steps:
            truncated = True
        return self._observe(), float(reward), terminated, truncated, info

    def _last_observation(self):
        return {"scan": self._scan.copy(), "odometry": np.array(self._odom),
                "path": self._path_ahead()}

    def close(self):
        self._episode = None
