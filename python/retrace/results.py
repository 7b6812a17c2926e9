"""load_results: a folder that retrace wrote, read into Python values (docs/FORMATS.md).

Metrics come as dicts (the JSON files as they are), trajectories as (N, 4) float64 arrays
[t, x, y, yaw], taught paths as (N, 3) arrays [x, y, yaw], tables as dicts of columns (float64
arrays; text columns as lists of str), maps as uint8 images. Files are read when first asked
for and then kept, so loading a large folder costs nothing until its parts are used. Each file
is read by retrace's own reader (the extension's read_* functions): a malformed one raises the
error the command line would print.
"""

import errno
import functools
import pathlib

import numpy as np

from . import _retrace

MODES = ("partial", "scan_matched", "single", "consistent")


def _optional(path, read):
    """read(path), or None when the file is not there."""
    return read(path) if path.exists() else None


class Teach:
    """A teach folder (<mode>/teach): the partial maps, their taught paths, the drive's truth."""

    def __init__(self, folder):
        self.path = pathlib.Path(folder)

    @functools.cached_property
    def count(self):
        """The number of partial maps (sub_map_num.txt)."""
        return int((self.path / "sub_map_num.txt").read_text().split()[0])

    @functools.cached_property
    def maps(self):
        """[TaughtMap] in map order: each map (maps/ogm_<k>.yaml and its image) with its taught
        path and switch pose; log_odds is None (the image keeps only the three classes)."""
        maps = []
        for k in range(self.count):
            grid = _retrace.read_map(self.path / "maps" / f"ogm_{k}.yaml")
            maps.append(_retrace.TaughtMap(
                index=k, image=grid["image"], resolution=grid["resolution"],
                origin=grid["origin"], path=self.paths[k], switch_pose=self.switch_poses[k]))
        return maps

    @functools.cached_property
    def paths(self):
        """[(N, 3) array [x, y, yaw]]: the taught path of each map, in its own frame."""
        return [_retrace.read_path(self.path / "paths" / f"path_{k}.txt")
                for k in range(self.count)]

    @functools.cached_property
    def switch_poses(self):
        """(K, 3) array [x, y, yaw]: row k is X_{M_k S}, where map k ended."""
        rows = [line.split() for line in
                (self.path / "switch_poses.txt").read_text().splitlines()
                if line.strip() and not line.startswith("#")]
        return np.array(rows, dtype=float).reshape(-1, 3)

    @functools.cached_property
    def gt(self):
        """(N, 4) ground truth X_WR of the teaching drive (None: a log without reference)."""
        return _optional(self.path / "gt.tum", _retrace.read_tum)

    @functools.cached_property
    def odom(self):
        """(N, 4) odometry X_OR of the teaching drive."""
        return _optional(self.path / "odom.tum", _retrace.read_tum)

    def __repr__(self):
        return f"Teach('{self.path}')"


class Run:
    """One playback run (<mode>/runs/<i>)."""

    def __init__(self, folder):
        self.path = pathlib.Path(folder)
        self.index = int(self.path.name)

    @functools.cached_property
    def est(self):
        """(N, 4) the estimate carried into the world frame (est.tum)."""
        return _retrace.read_tum(self.path / "est.tum")

    @functools.cached_property
    def gt(self):
        """(N, 4) ground truth X_WR at every control tick (gt.tum)."""
        return _retrace.read_tum(self.path / "gt.tum")

    @functools.cached_property
    def odom(self):
        """(N, 4) wheel odometry X_OR (odom.tum)."""
        return _retrace.read_tum(self.path / "odom.tum")

    @functools.cached_property
    def errors(self):
        """errors.csv: time, map, arc_length_m, lateral_offset_m, tracking_error_m,
        localization_error_m, localization_error_rad (one entry per control tick)."""
        return _retrace.read_csv(self.path / "errors.csv")

    @functools.cached_property
    def est_map(self):
        """est_map.csv: time, map, x, y, theta (the estimate in its own map)."""
        return _retrace.read_csv(self.path / "est_map.csv")

    @functools.cached_property
    def events(self):
        """events.csv: time, event, detail (map switches, collisions, the outcome)."""
        return _retrace.read_csv(self.path / "events.csv")

    @functools.cached_property
    def snapshot(self):
        """snapshot.json: the localizer update with the most pedestrian beams."""
        return _optional(self.path / "snapshot.json", _retrace.read_json)

    def __repr__(self):
        return f"Run('{self.path}')"


class Mode:
    """One map mode's folder of a run, teach, playback or log-teach (<out>/<mode>)."""

    def __init__(self, folder):
        self.path = pathlib.Path(folder)
        self.name = self.path.name

    @functools.cached_property
    def metrics(self):
        """metrics.json ({"mode", "aggregate", "runs"}), None when no run was played back."""
        return _optional(self.path / "metrics.json", _retrace.read_json)

    @functools.cached_property
    def runs(self):
        """[Run] in run order (empty: taught only)."""
        folder = self.path / "runs"
        if not folder.is_dir():
            return []
        found = [p for p in folder.iterdir() if p.is_dir() and p.name.isdigit()]
        return [Run(p) for p in sorted(found, key=lambda p: int(p.name))]

    @functools.cached_property
    def teach(self):
        """The mode's Teach (None: a playback of a teach folder written elsewhere)."""
        folder = self.path / "teach"
        return Teach(folder) if folder.is_dir() else None

    @property
    def manifest(self):
        """The path of manifest.yaml: command, seed, revision, the effective config."""
        return self.path / "manifest.yaml"

    def __repr__(self):
        return f"Mode('{self.name}', {len(self.runs)} runs)"


class Results:
    """A folder of map modes: `retrace run`, `teach`, `playback` or `log-teach` output."""

    kind = "modes"

    def __init__(self, folder, modes):
        self.path = pathlib.Path(folder)
        self.modes = {name: Mode(self.path / name) for name in modes}

    @functools.cached_property
    def comparison(self):
        """comparison.json: every mode's aggregate metrics (None: one mode ran)."""
        return _optional(self.path / "comparison.json", _retrace.read_json)

    def __repr__(self):
        return f"Results('{self.path}', modes={list(self.modes)})"


class Localization:
    """A `retrace log-localize` folder."""

    kind = "log-localize"

    def __init__(self, folder):
        self.path = pathlib.Path(folder)

    @functools.cached_property
    def metrics(self):
        """metrics.json: scans, updates, localization_error_m {mean, rms, ...}, lost_fraction..."""
        return _retrace.read_json(self.path / "metrics.json")

    @functools.cached_property
    def est(self):
        """(N, 4) the estimate carried into the reference's frame (est.tum; None: no reference)."""
        return _optional(self.path / "est.tum", _retrace.read_tum)

    @functools.cached_property
    def reference(self):
        """(N, 4) the reference at the instants of est.tum (reference.tum)."""
        return _optional(self.path / "reference.tum", _retrace.read_tum)

    @functools.cached_property
    def errors(self):
        """errors.csv: time, map, driven_m, path_distance_m, localization_error_m, _rad."""
        return _retrace.read_csv(self.path / "errors.csv")

    @functools.cached_property
    def est_map(self):
        """est_map.csv: time, map, x, y, theta (the estimate in its own map, every scan)."""
        return _retrace.read_csv(self.path / "est_map.csv")

    @functools.cached_property
    def updates(self):
        """updates.csv: beams tested and rejected, spread, cpu_ms... per measurement update."""
        return _retrace.read_csv(self.path / "updates.csv")

    @functools.cached_property
    def events(self):
        """events.csv: the map switches."""
        return _retrace.read_csv(self.path / "events.csv")

    def __repr__(self):
        return f"Localization('{self.path}')"


class Sweep:
    """A `retrace sweep` (or `merge`) folder."""

    kind = "sweep"

    def __init__(self, folder):
        self.path = pathlib.Path(folder)

    @functools.cached_property
    def sweep(self):
        """sweep.json: the plan, the command, the provenance."""
        return _retrace.read_json(self.path / "sweep.json")

    @functools.cached_property
    def results(self):
        """results.csv by column: case, combo, repeat, seed, the parameters, the metrics."""
        return _retrace.read_csv(self.path / "results.csv")

    @functools.cached_property
    def timings(self):
        """timings.csv by column: case, wall_time_s, the cpu.* metrics."""
        return _optional(self.path / "timings.csv", _retrace.read_csv)

    def __repr__(self):
        return f"Sweep('{self.path}')"


class Comparison:
    """A `retrace compare` folder."""

    kind = "compare"

    def __init__(self, folder):
        self.path = pathlib.Path(folder)

    @functools.cached_property
    def data(self):
        """comparison.json: per metric and mode the per-seed values, means and intervals."""
        return _retrace.read_json(self.path / "comparison.json")

    @functools.cached_property
    def markdown(self):
        """comparison.md, the table `retrace compare` prints."""
        return (self.path / "comparison.md").read_text()

    def __repr__(self):
        return f"Comparison('{self.path}')"


def load_results(folder):
    """The folder `folder`, as what wrote it:

    - `retrace run`, `teach`, `playback` or `log-teach` (a folder per map mode): Results
    - `retrace log-localize`: Localization
    - `retrace sweep` or `merge`: Sweep
    - `retrace compare`: Comparison
    - a teach folder (<mode>/teach): Teach

    Raises FileNotFoundError for a missing folder, ValueError for a folder retrace did not write.
    """
    path = pathlib.Path(folder)
    if not path.is_dir():
        raise FileNotFoundError(errno.ENOENT, f"{path}: no such folder", str(path))
    modes = [m for m in MODES if (path / m / "manifest.yaml").is_file()]
    if modes:
        return Results(path, modes)
    if (path / "sweep.json").is_file():
        return Sweep(path)
    if (path / "est_map.csv").is_file() and (path / "metrics.json").is_file():
        return Localization(path)
    if (path / "comparison.md").is_file() and (path / "comparison.json").is_file():
        return Comparison(path)
    if (path / "sub_map_num.txt").is_file():
        return Teach(path)
    raise ValueError(f"{path}: not a folder retrace writes (no <mode>/manifest.yaml, "
                     "sweep.json, metrics.json with est_map.csv, comparison.md or teach bundle)")
