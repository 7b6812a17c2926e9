"""The log calls on a recorded drive: the small scenario's teaching drive, shortened to 12 m, as
tests/cli records it (retrace.teach(record_log=...))."""

import numpy as np
import pytest

import retrace
from conftest import SHORT_ROUTE, SMALL, read_json, run_cli, without_timing


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("logs")
    retrace.teach(SMALL, modes="partial", set=SHORT_ROUTE, out=tmp / "sim",
                  record_log=tmp / "logs", progress=False)
    return tmp


def test_log_info_describes_the_recorded_drive(recorded):
    info = retrace.log_info(recorded / "logs" / "teach.mcap")
    assert info.format == "MCAP file" and info.problem == "" and not info.needs_choice
    assert info.scan["scans"] > 100 and info.scan["beams"] > 0
    assert info.odometry.shape[1] == 4 and info.odometry.dtype == np.float64
    assert info.reference.shape[1] == 4 and len(info.reference) > 0
    assert any(t["type"] == "sensor_msgs/msg/LaserScan" for t in info.topics)
    assert info.text.startswith(str(recorded / "logs" / "teach.mcap"))


def test_log_teach_then_log_localize_write_what_the_command_line_writes(recorded,
                                                                         retrace_binary):
    log = recorded / "logs" / "teach.mcap"
    taught = retrace.log_teach(log, out=recorded / "taught", modes="partial",
                               switch_points="6", figures=False)
    assert taught.modes == ["partial"] and "partial" in taught.summary
    teach = recorded / "taught" / "partial" / "teach"
    assert retrace.load_results(teach).count == 2
    localized = retrace.log_localize(log, teach=teach, out=recorded / "py", seed=2,
                                     figures=False)
    assert localized.metrics == read_json(recorded / "py" / "metrics.json")
    assert localized.metrics["scans"] > 100
    cli = run_cli(retrace_binary, "log-localize", log, "--teach", teach, "--seed", "2",
                  "--no-figures", "--out", recorded / "cli")
    assert cli.returncode == 0, cli.stderr
    assert without_timing(localized.metrics) == \
        without_timing(read_json(recorded / "cli" / "metrics.json"))
    results = retrace.load_results(recorded / "py")
    assert isinstance(results, retrace.Localization)
    assert results.est.shape == results.reference.shape
    assert len(results.errors["localization_error_m"]) == localized.metrics["scans"]


def test_log_localize_refuses_a_bad_initial_pose_before_reading(recorded):
    with pytest.raises(ValueError, match="initial_pose: must be"):
        retrace.log_localize(recorded / "logs" / "teach.mcap", teach=recorded, out=recorded / "x",
                             initial_pose=[1.0, 2.0])
    assert not (recorded / "x").exists()
