"""retrace.load_results and the readers: a results folder as dicts and NumPy arrays."""

import numpy as np
import pytest

import retrace
from conftest import read_json


def test_load_results_reads_a_run_folder(small_runs):
    results = retrace.load_results(small_runs["py"])
    assert isinstance(results, retrace.Results) and list(results.modes) == ["partial",
                                                                            "consistent"]
    assert results.comparison["partial"]["success_rate"] == 1.0
    mode = results.modes["partial"]
    assert mode.metrics == read_json(small_runs["py"] / "partial" / "metrics.json")
    (run,) = mode.runs
    for trajectory in (run.est, run.gt, run.odom):
        assert trajectory.dtype == np.float64 and trajectory.ndim == 2
        assert trajectory.shape[1] == 4 and len(trajectory) > 100
    errors = run.errors
    assert set(errors) >= {"time", "map", "arc_length_m", "tracking_error_m",
                           "localization_error_m"}
    assert all(len(column) == len(errors["time"]) for column in errors.values())
    assert errors["localization_error_m"].dtype == np.float64
    assert run.events["event"][-1] == "end" and run.events["detail"][-1] == "success"
    assert run.snapshot["map"] in (0, 1)


def test_a_teach_folder_has_uint8_maps_and_taught_paths(small_runs):
    teach = retrace.load_results(small_runs["py"]).modes["partial"].teach
    assert teach.count == 2 and len(teach.maps) == 2 and len(teach.paths) == 2
    for grid in teach.maps:
        assert grid.image.dtype == np.uint8 and grid.image.ndim == 2
        assert set(np.unique(grid.image)) <= {0, 205, 254}
        assert (grid.image == 0).any() and (grid.image == 254).any()
        left, right, bottom, top = grid.extent
        assert right - left == pytest.approx(grid.image.shape[1] * grid.resolution)
    for path in teach.paths:
        assert path.shape[1] == 3 and len(path) > 2
    # One class for a taught map: the one a stepped Teaching hands out, path and switch pose in.
    for k, grid in enumerate(teach.maps):
        assert isinstance(grid, retrace.TaughtMap) and grid.index == k and grid.log_odds is None
        np.testing.assert_array_equal(grid.path, teach.paths[k])
        np.testing.assert_array_equal(grid.switch_pose, teach.switch_poses[k])
    with pytest.raises(ValueError, match="path: an"):
        retrace.TaughtMap(index=0, image=teach.maps[0].image, resolution=0.1, origin=(0, 0),
                          path=np.zeros((3, 2)), switch_pose=np.zeros(3))
    # Each map's path ends at its switch pose.
    np.testing.assert_allclose(teach.paths[0][-1], teach.switch_poses[0], atol=1e-6)
    assert teach.gt.shape[1] == 4 and teach.odom.shape == teach.gt.shape
    assert retrace.load_results(teach.path).count == 2  # a teach folder loads as one


def test_arrays_view_the_memory_the_reader_filled(small_runs):
    est = retrace.read_tum(small_runs["py"] / "partial" / "runs/0/est.tum")
    assert not est.flags.owndata and est.base is not None  # owned by a capsule, not copied
    del est  # the capsule frees the vector; nothing dangles
    image = retrace.read_map(small_runs["py"] / "partial" / "teach/maps/ogm_0.yaml")["image"]
    view = image[:2]
    del image
    assert view.shape[0] == 2 and view.sum() >= 0


def test_load_results_refuses_what_retrace_did_not_write(tmp_path):
    with pytest.raises(FileNotFoundError):
        retrace.load_results(tmp_path / "missing")
    with pytest.raises(ValueError, match="not a folder retrace writes"):
        retrace.load_results(tmp_path)


def test_a_malformed_file_raises_the_readers_line(tmp_path):
    bad = tmp_path / "bad.tum"
    bad.write_text("0 1 2\n")
    with pytest.raises(OSError, match="bad.tum:1"):
        retrace.read_tum(bad)
    with pytest.raises(FileNotFoundError):
        retrace.read_csv(tmp_path / "missing.csv")


def test_render_and_report_draw_a_run_folder(small_runs):
    figures = retrace.render(small_runs["py"])
    assert figures and all(f.suffix == ".png" and f.stat().st_size > 0 for f in figures)
    page = retrace.report(small_runs["py"])
    assert page == small_runs["py"] / "report.html" and "<html" in page.read_text()[:200]
    with pytest.raises(OSError):
        retrace.report(small_runs["py"] / "missing")
