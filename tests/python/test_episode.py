"""retrace.Teaching and retrace.Episode: runs stepped from Python. The built-in stack stepped
through them gives exactly `retrace run`'s metrics, in every mode; a stack's misuse of the
stepping raises one clear error."""

import math

import numpy as np
import pytest

import retrace
from conftest import SMALL, read_json, run_cli, without_timing

MODES = ("partial", "scan_matched", "single", "consistent")


@pytest.fixture(scope="module")
def cli_all_modes(tmp_path_factory, retrace_binary):
    """`retrace run` of the small scenario, every mode, two runs each."""
    out = tmp_path_factory.mktemp("steps") / "cli"
    cli = run_cli(retrace_binary, "run", SMALL, "--mode", "all", "--repeats", "2", "--seed", "3",
                  "--no-figures", "--no-report", "--out", out)
    assert cli.returncode == 0, cli.stderr
    return out


@pytest.mark.parametrize("mode", MODES)
def test_the_builtin_stack_stepped_gives_the_run_commands_metrics(cli_all_modes, mode):
    teaching = retrace.Teaching(SMALL, mode=mode, seed=3, progress=False)
    episodes = []
    for run in (0, 1):
        episode = teaching.episode(run, builtin=True)
        while not episode.done:
            episode.observe()
            episode.act()
        episodes.append(episode)
    written = read_json(cli_all_modes / mode / "metrics.json")
    for run, episode in enumerate(episodes):
        assert without_timing(episode.metrics()) == without_timing(written["runs"][run]), run
    assert without_timing(teaching.aggregate(episodes)) == without_timing(written["aggregate"])


def test_teaching_hands_out_the_recording_and_the_taught_maps():
    seen = []
    teaching = retrace.Teaching(SMALL, mode="partial", progress=seen.append)
    assert seen and {p.phase for p in seen} == {"teach"}
    assert (seen[-1].done, seen[-1].total) == (1, 1) and seen[-1].sim_time_s > 60
    assert teaching.mode == "partial" and len(teaching.maps) == 2
    recording = teaching.recording
    assert recording.odometry.shape[1] == 4 and recording.reference.shape == \
        (len(recording.odometry), 3)
    assert np.all(np.diff(recording.odometry[:, 0]) > 0)
    scan = recording.scans[0]
    assert len(scan) == scan.ranges.shape[0] == scan.angles.shape[0] > 100
    assert scan.ranges.dtype == np.float32 and not scan.ranges.flags.writeable
    assert scan.angles[0] == pytest.approx(scan.angle_min)
    for k, taught in enumerate(teaching.maps):
        assert taught.index == k and taught.image.dtype == np.uint8
        assert taught.image.shape == taught.log_odds.shape
        assert set(np.unique(taught.image)) <= {0, 205, 254}
        assert taught.path.shape[1] == 3 and taught.switch_pose.shape == (3,)
    # Map 0's frame is the teaching drive's odometry frame: its path is the odometry's track.
    path0 = teaching.maps[0].path
    odometry = recording.odometry[:, 1:3]
    assert min(np.hypot(*(odometry - path0[5, :2]).T)) < 0.05
    assert teaching.lidar_mount.shape == (3,) and teaching.robot_radius > 0


def drive_on_odometry(teaching, episode, on_observation=None, **answer):
    """Drives map 0's taught path to its end on dead reckoning (the estimate is the odometry);
    `on_observation` sees each observation first; `answer` adds keywords to every act()."""
    path = teaching.maps[0].path
    pose, i = np.zeros(3), 0
    while not episode.done:
        observation = episode.observe()
        if on_observation is not None:
            on_observation(observation)
        for _, distance, dtheta in observation.odometry:  # dead reckoning
            pose = np.array(retrace.integrate_odometry(pose, distance, dtheta))
        i = min(i + int(np.argmin(np.hypot(*(path[i:i + 30, :2] - pose[:2]).T))), len(path) - 1)
        goal = path[min(i + 8, len(path) - 1)]
        bearing = math.atan2(goal[1] - pose[1], goal[0] - pose[0]) - pose[2]
        bearing = math.atan2(math.sin(bearing), math.cos(bearing))
        at_end = i == len(path) - 1 and math.dist(pose[:2], path[-1, :2]) < 0.3
        episode.act(0.0 if at_end else 0.5, max(-1.0, min(1.0, 2.0 * bearing)), estimate=pose,
                    route_done=at_end, **answer)
    return episode.metrics()


def test_a_stack_on_odometry_alone_is_scored_against_the_truth():
    """Driving the taught path of each map on dead reckoning: the estimate is the odometry, its
    error the drift, and the run is scored like any other."""
    teaching = retrace.Teaching(SMALL, mode="single", progress=False)
    episode = teaching.episode(0)
    metrics = drive_on_odometry(teaching, episode)
    assert metrics["outcome"] == "success"
    assert 0.0 < metrics["localization_error_m"]["rms"] < 1.0
    samples = episode.samples()
    assert samples["est"].shape == samples["gt"].shape == (metrics["samples"], 3)


def test_a_stepped_answer_is_a_whole_stack_answer():
    """act() takes what a registered stack answers: a stack that says it is off every map is
    counted so; a map_change must end in the map answered."""
    teaching = retrace.Teaching(SMALL, mode="single", progress=False)
    metrics = drive_on_odometry(teaching, teaching.episode(0), off_map=True)
    assert metrics["localizer"]["off_map_time_s"] > 0.9 * metrics["time_s"]
    episode = teaching.episode(1)
    episode.observe()
    with pytest.raises(ValueError, match="map_change into map 1 answered in map 0"):
        episode.act(0.1, 0.0, estimate=(0, 0, 0), map_change=(0, 1, (0, 0, 0), (0, 0, 0)))
    with pytest.raises(ValueError, match="map_change that is not \\(from, to"):
        episode.act(0.1, 0.0, estimate=(0, 0, 0), map_change=(0, 1))


def test_a_python_stack_is_told_when_an_operator_hands_the_robot_back():
    """A scripted takeover drives the robot from 3 m along the route to (8.5, 1); the observation
    after the operator hands it back says so, once (C++ stacks get NavigationStack::Resume)."""
    takeover = "events=[{action: takeover, at_route_s: 3, drive: [[6, 1], [8.5, 1]]}]"
    teaching = retrace.Teaching(SMALL, mode="single", set=[takeover], progress=False)
    handed_back = []
    drive_on_odometry(teaching, teaching.episode(0),
                      lambda observation: handed_back.append(observation.handed_back))
    assert sum(handed_back) == 1 and handed_back.index(True) > 10


def test_misuse_of_the_stepping_raises_one_error():
    teaching = retrace.Teaching(SMALL, mode="partial", progress=False)
    episode = teaching.episode(0)
    # Steps out of order are RuntimeErrors; a missing or bad answer a ValueError naming it.
    with pytest.raises(RuntimeError, match="act: nothing to answer yet: observe\\(\\) first"):
        episode.act(0.1, 0.0, estimate=(0, 0, 0))
    episode.observe()
    with pytest.raises(RuntimeError, match="the last observation is not answered yet"):
        episode.observe()
    with pytest.raises(ValueError, match="estimate: missing: act\\(\\) needs the stack's estimate"):
        episode.act(0.1, 0.0)
    with pytest.raises(ValueError, match="command: missing") as error:
        episode.act(estimate=(0, 0, 0))
    assert error.value.key == "command"
    with pytest.raises(TypeError, match="v: a number"):
        episode.act("fast", 0.0, estimate=(0, 0, 0))
    with pytest.raises(TypeError, match="estimate"):
        episode.act(0.1, 0.0, estimate="here")
    with pytest.raises(ValueError, match="must be \\(x, y, yaw\\)"):
        episode.act(0.1, 0.0, estimate=(0, 0))
    with pytest.raises(ValueError, match="finite"):
        episode.act(0.1, 0.0, estimate=(math.nan, 0, 0))
    with pytest.raises(ValueError, match="map 2 is not a map of the route"):
        episode.act(0.1, 0.0, estimate=(0, 0, 0), map=2)
    with pytest.raises(RuntimeError, match="metrics: the run is not done yet"):
        episode.metrics()
    assert episode.act(0.1, 0.0, estimate=(0, 0, 0)) is False  # the errors left it answerable
    builtin = teaching.episode(1, builtin=True)
    builtin.observe()
    with pytest.raises(ValueError, match="built-in stack answers"):
        builtin.act(0.5, 0.0)
    with pytest.raises(ValueError) as error:
        retrace.Teaching(SMALL, mode="all", progress=False)
    assert error.value.key == "mode"
    with pytest.raises(ValueError, match="must be >= 0"):
        teaching.episode(-1)
    other = retrace.Teaching(SMALL, mode="single", progress=False)
    with pytest.raises(ValueError, match="another Teaching"):
        other.aggregate([episode])
