"""retrace.run, teach and playback against the command line's `retrace run`, `teach` and
`playback` with the same arguments."""

import pathlib

import pytest

import retrace
from conftest import SHORT_ROUTE, SMALL, read_json, run_cli, without_timing


def test_run_writes_the_metrics_the_command_line_writes(small_runs):
    cli, py = small_runs["cli"], small_runs["py"]
    for mode in ("partial", "consistent"):
        assert without_timing(read_json(py / mode / "metrics.json")) == \
            without_timing(read_json(cli / mode / "metrics.json")), mode
        # The trajectories, byte for byte: the same library call, the same episode.
        for name in ("est.tum", "gt.tum", "errors.csv"):
            assert (py / mode / "runs/0" / name).read_bytes() == \
                (cli / mode / "runs/0" / name).read_bytes(), f"{mode}/runs/0/{name}"
    assert without_timing(read_json(py / "comparison.json")) == \
        without_timing(read_json(cli / "comparison.json"))


def test_run_result_holds_each_modes_summary_and_aggregate(small_runs):
    result, py = small_runs["result"], small_runs["py"]
    assert result.out == py and isinstance(result.out, pathlib.Path)
    assert list(result.modes) == ["partial", "consistent"]
    assert result.exit_code == 0 and result.success
    assert "partial" in result.summary and "consistent" in result.summary
    for name, mode in result.modes.items():
        assert (mode.mode, mode.runs, mode.successes) == (name, 1, 1)
        assert mode.metrics == read_json(py / name / "metrics.json")["aggregate"]
    # The manifest records the call as the command line records its own.
    manifest = (py / "partial" / "manifest.yaml").read_text()
    assert "retrace.run(" in manifest and "modes='partial,consistent'" in manifest


def test_progress_callback_sees_each_phase_count_up(small_runs):
    seen = small_runs["progress"]
    assert all(isinstance(p, retrace.Progress) for p in seen)
    phases = [p.phase for p in seen]
    assert phases[0] == "teach" and phases[-1] == "playback"
    last = [p for p in seen if p.phase == "playback"][-1]
    assert (last.done, last.total) == (2, 2)
    assert max(p.sim_time_s for p in seen) > 0


def test_teach_then_playback_of_its_teach_folder(tmp_path, retrace_binary):
    taught = retrace.teach(SMALL, modes="consistent", set=SHORT_ROUTE, out=tmp_path / "t",
                           progress=False)
    mode = taught.modes["consistent"]
    assert (mode.runs, mode.metrics) == (0, None)
    teach_dir = tmp_path / "t" / "consistent" / "teach"
    played = retrace.playback(SMALL, teach_dir, repeats=1, set=SHORT_ROUTE, figures=False,
                              report=False, out=tmp_path / "p", progress=False)
    assert list(played.modes) == ["consistent"]  # the mode from the teach folder's name
    cli = run_cli(retrace_binary, "playback", SMALL, "--teach", teach_dir, "--mode", "consistent",
                  "--repeats", "1", "--set", SHORT_ROUTE[0], "--set", SHORT_ROUTE[1],
                  "--no-figures", "--no-report", "--out", tmp_path / "c")
    assert cli.returncode == 0, cli.stderr
    assert without_timing(read_json(tmp_path / "p/consistent/metrics.json")) == \
        without_timing(read_json(tmp_path / "c/consistent/metrics.json"))


def test_set_takes_a_dict_of_values(tmp_path):
    taught = retrace.teach(SMALL, modes=["partial"], seed=5, out=tmp_path,
                           set={"route.points": [[1, 1], [9, 1], [9, 5]],
                                "route.switch_points": "[6]", "teach.teacher.speed": 0.8},
                           progress=False)
    assert list(taught.modes) == ["partial"]
    manifest = (tmp_path / "partial" / "manifest.yaml").read_text()
    assert "speed: 0.8" in manifest


def test_a_scenario_warning_is_a_retrace_warning(tmp_path):
    # A switch point after the route comes back over itself: taught all the same, warned.
    with pytest.warns(retrace.RetraceWarning, match="the switch is too late"):
        retrace.teach(SMALL, modes="partial", out=tmp_path, progress=False,
                      set="route.switch_points=[30]")
    assert (tmp_path / "partial" / "teach").is_dir()


def test_compare_writes_the_study_the_command_line_writes(tmp_path, retrace_binary):
    args = dict(modes="partial,consistent", seeds=2, repeats=1, set=SHORT_ROUTE, report=False)
    study = retrace.compare(SMALL, out=tmp_path / "py", progress=False, **args)
    assert study.data == read_json(tmp_path / "py" / "comparison.json")
    assert "partial" in study.markdown and study.data["seeds"] == [1, 2]
    cli = run_cli(retrace_binary, "compare", SMALL, "--modes", "partial,consistent", "--seeds", "2",
                  "--repeats", "1", "--set", SHORT_ROUTE[0], "--set", SHORT_ROUTE[1],
                  "--no-report", "--out", tmp_path / "cli")
    assert cli.returncode == 0, cli.stderr
    navigation = {mode: {k: v for k, v in metrics.items() if not k.startswith("cpu.")}
                  for mode, metrics in study.data["modes"].items()}
    cli_data = read_json(tmp_path / "cli" / "comparison.json")
    assert navigation == {mode: {k: v for k, v in metrics.items() if not k.startswith("cpu.")}
                          for mode, metrics in cli_data["modes"].items()}
    assert isinstance(retrace.load_results(study.out), retrace.Comparison)
