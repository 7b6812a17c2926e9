"""A navigation stack written in Python inside retrace.run (python/stack_bindings.cpp): registered
by name, given its options, driven and scored by the loop `retrace run` drives; its errors end the
call with one exception naming the stack."""

import math

import pytest

import retrace
from conftest import SMALL, read_json


class DeadReckoning:
    """Replays map 0's taught path on dead reckoning (one map: the single mode), pure pursuit."""

    def __init__(self, context):
        self.path = context["maps"][0].path
        self.speed = float(context["options"]["speed"])
        self.pose = [0.0, 0.0, 0.0]
        self.i = 0
        self.scans = 0

    def on_odometry(self, t, distance, dtheta):
        x, y, yaw = self.pose
        # core::IntegrateOdometry: along the arc, at the midpoint heading.
        chord = distance if dtheta == 0.0 else distance * math.sin(dtheta / 2) / (dtheta / 2)
        self.pose = [x + chord * math.cos(yaw + dtheta / 2), y + chord * math.sin(yaw + dtheta / 2),
                     yaw + dtheta]

    def on_scan(self, scan):
        self.scans += 1

    def on_control_tick(self, t, dt):
        x, y, yaw = self.pose
        n = len(self.path)
        ahead = range(self.i, min(self.i + 30, n))
        self.i = min(ahead, key=lambda j: math.hypot(self.path[j, 0] - x, self.path[j, 1] - y))
        goal = self.path[min(self.i + 8, n - 1)]
        bearing = math.atan2(goal[1] - y, goal[0] - x) - yaw
        bearing = math.atan2(math.sin(bearing), math.cos(bearing))
        done = self.i == n - 1 and math.hypot(self.path[-1, 0] - x, self.path[-1, 1] - y) < 0.3
        return {"v": 0.0 if done else self.speed, "omega": max(-1.0, min(1.0, 2.0 * bearing)),
                "estimate": (x, y, yaw), "map": 0, "route_done": done}


def register_once(name, factory, **kwargs):
    if name not in retrace.registered_stacks():
        retrace.register_stack(name, factory, **kwargs)


def test_a_python_stack_runs_inside_retrace_run_and_is_scored(tmp_path):
    register_once("py_dead_reckoning", DeadReckoning, options={"speed": "0.5"})
    assert "py_dead_reckoning" in retrace.registered_stacks()
    result = retrace.run(SMALL, modes="single", repeats=1, out=tmp_path / "py", progress=False,
                         set=["playback.stack=py_dead_reckoning",
                              "playback.stack_options.speed=0.6"],
                         figures=False, report=False)
    metrics = read_json(tmp_path / "py" / "single" / "metrics.json")
    run = metrics["runs"][0]
    assert run["outcome"] in ("success", "timeout", "lost", "collision")
    assert run["progress_m"] > 5.0  # it drove along the route
    assert 0.0 < run["localization_error_m"]["rms"] < 2.0  # scored against the truth
    assert "playback stack: py_dead_reckoning" in result.summary


def test_a_python_stacks_mistakes_end_the_call_with_one_exception(tmp_path):
    class Broken(DeadReckoning):
        def on_control_tick(self, t, dt):
            raise KeyError("no such thing")

    class Mute(DeadReckoning):
        def on_control_tick(self, t, dt):
            return {"v": 0.1, "omega": 0.0}

    register_once("py_broken", Broken, options={"speed": "0.5"})
    register_once("py_mute", Mute, options={"speed": "0.5"})
    with pytest.raises(RuntimeError, match="stack 'py_broken', on_control_tick: KeyError"):
        retrace.run(SMALL, modes="single", repeats=1, out=tmp_path / "b", progress=False,
                    set="playback.stack=py_broken", figures=False, report=False)
    with pytest.raises(ValueError, match="stack 'py_mute' answered without 'estimate'"):
        retrace.run(SMALL, modes="single", repeats=1, out=tmp_path / "m", progress=False,
                    set="playback.stack=py_mute", figures=False, report=False)
    with pytest.raises(ValueError, match="a stack named 'py_mute' is registered already"):
        retrace.register_stack("py_mute", Mute)
    with pytest.raises(ValueError, match="stack 'py_mute' takes no option 'sped'"):
        retrace.run(SMALL, modes="single", repeats=1, out=tmp_path / "o", progress=False,
                    set=["playback.stack=py_mute", "playback.stack_options.sped=1"])


def test_compare_puts_a_python_stack_beside_retraces_on_the_same_seeds(tmp_path):
    register_once("py_dead_reckoning", DeadReckoning, options={"speed": "0.5"})
    result = retrace.compare(SMALL, modes="single", stacks=["retrace", "py_dead_reckoning"],
                             reference="single", seeds=2, repeats=1, out=tmp_path / "c",
                             progress=False, report=False)
    assert sorted(result.data["modes"]) == ["single/py_dead_reckoning", "single/retrace"]
    assert result.data["reference"] == "single/retrace"
    assert "single/py_dead_reckoning − single/retrace" in result.markdown
    with pytest.raises(ValueError, match="--stacks: 'retrace' is named twice"):
        retrace.compare(SMALL, modes="single", stacks=["retrace", "retrace"], seeds=2,
                        reference="single", out=tmp_path / "d", progress=False)


class WrappedBuiltin:
    """retrace's own navigator driven from Python: every call passed on, every answer passed
    back, the native stack kept as `native` (so the harness scores inside it as well)."""

    made = []

    def __init__(self, context):
        self.native = context["native"]("retrace")
        WrappedBuiltin.made.append(self.native)

    def on_odometry(self, t, distance, dtheta):
        self.native.on_odometry(t, distance, dtheta)

    def on_scan(self, scan):
        self.native.on_scan(scan)

    def on_control_tick(self, t, dt):
        return self.native.on_control_tick(t, dt)

    def resume(self):
        return self.native.resume()


def without_timings(metrics):
    """metrics.json without what the clock measured (the CPU block of the aggregate and runs)."""
    if isinstance(metrics, dict):
        return {k: without_timings(v) for k, v in metrics.items() if k != "cpu"}
    if isinstance(metrics, list):
        return [without_timings(v) for v in metrics]
    return metrics


def test_the_builtin_stack_wrapped_in_python_runs_as_retrace_run_to_the_bit(tmp_path):
    register_once("py_wrapped_retrace", WrappedBuiltin)
    for stack in ("retrace", "py_wrapped_retrace"):
        retrace.run(SMALL, modes="all", seed=3, out=tmp_path / stack, progress=False,
                    set=f"playback.stack={stack}", figures=False, report=False)
    native, wrapped = tmp_path / "retrace", tmp_path / "py_wrapped_retrace"
    runs = sorted(p.relative_to(native) for p in native.glob("*/runs/*/*") if p.is_file())
    assert len(runs) >= 4 * 2 * 5  # four modes, their runs, each run's trajectories and events
    for name in runs:
        assert (native / name).read_bytes() == (wrapped / name).read_bytes(), name
    for mode in ("single", "partial", "scan_matched", "consistent"):
        ours = read_json(native / mode / "metrics.json")
        assert "dynamic_points" in ours["aggregate"]  # scored inside the native stack too
        assert without_timings(read_json(wrapped / mode / "metrics.json")) == without_timings(ours)
    # A native stack serves only the run it was made for.
    with pytest.raises(RuntimeError, match="native stack 'retrace': the run it was made for has "
                                           "ended"):
        WrappedBuiltin.made[-1].on_odometry(0.0, 0.1, 0.0)
