"""What the tests of the Python module share (docs/PYTHON.md, docs/DESIGN.md §9).

Run them against a build tree (ctest runs them as python.pytest, label python):

    PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python

RETRACE_BINARY names the `retrace` program to compare with (default: the one of the build tree
the module was imported from, <build>/retrace).
"""

import json
import os
import pathlib
import subprocess

import pytest

import retrace

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
SMALL = SOURCE_DIR / "scenarios" / "small.yaml"
# The small scenario's teaching drive, shortened to 12 m (as tests/cli/lib.sh's short_teach).
SHORT_ROUTE = ["route.points=[[1, 1], [9, 1], [9, 5]]", "route.switch_points=[6]"]
# Keys whose values measure the machine, not the navigation: never equal between two runs.
TIMING_KEYS = {"cpu", "update_time_ms", "real_time_factor", "wall_time_s"}


@pytest.fixture(scope="session")
def retrace_binary():
    binary = os.environ.get("RETRACE_BINARY") or \
        pathlib.Path(retrace.__file__).resolve().parents[2] / "retrace"
    binary = pathlib.Path(binary)
    assert binary.is_file(), f"no retrace program at {binary} (set RETRACE_BINARY)"
    return binary


def run_cli(binary, *args, cwd=None):
    """`retrace <args>`: the completed process (text output)."""
    return subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=600)


def without_timing(value):
    """A JSON value with its timing entries removed, recursively."""
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value


def read_json(path):
    return json.loads(pathlib.Path(path).read_text())


@pytest.fixture(scope="session")
def small_runs(tmp_path_factory, retrace_binary):
    """The small scenario in partial and consistent maps, one run each, by the command line and
    by retrace.run with the same arguments (and a progress callback that records what it saw)."""
    tmp = tmp_path_factory.mktemp("small")
    args = ["--mode", "partial,consistent", "--repeats", "1", "--seed", "3", "--jobs", "2",
            "--no-figures", "--no-report"]
    cli = run_cli(retrace_binary, "run", SMALL, *args, "--out", tmp / "cli")
    assert cli.returncode == 0, cli.stderr
    seen = []
    result = retrace.run(SMALL, modes="partial,consistent", repeats=1, seed=3, jobs=2,
                         figures=False, report=False, out=tmp / "py", progress=seen.append)
    return {"cli": tmp / "cli", "py": tmp / "py", "result": result, "progress": seen}
