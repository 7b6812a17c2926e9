"""Long calls stop on Ctrl-C (KeyboardInterrupt) or when the progress callback raises, and leave
no results folder behind (a sweep keeps its finished rows and resumes)."""

import os
import pathlib
import signal
import subprocess
import sys
import textwrap

import pytest

import retrace
from conftest import SMALL, SOURCE_DIR

CHILD = textwrap.dedent("""
    import signal, sys
    import retrace
    # A shell's background job starts with SIGINT ignored, and Python then installs no
    # KeyboardInterrupt for it: give the child the interactive Ctrl-C whoever started the tests.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    started = []
    def progress(p):
        if not started:
            started.append(p)
            print("started", p.phase, flush=True)
    try:
        retrace.run(sys.argv[1], modes="partial,consistent", repeats=5, jobs=2, figures=False,
                    out=sys.argv[2], progress=progress)
        print("finished", flush=True)
    except KeyboardInterrupt:
        print("interrupted", flush=True)
""")


def test_ctrl_c_stops_a_run_and_leaves_no_results_folder(tmp_path):
    out = tmp_path / "new" / "campus"  # neither folder exists yet
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(SOURCE_DIR / "scenarios/campus.yaml"),
                              str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=env)
    try:
        first = child.stdout.readline()
        assert first == "started teach\n", first + child.stderr.read()
        child.send_signal(signal.SIGINT)
        # The campus run takes minutes; stopped, it ends at its next report (10 s simulated).
        stdout, stderr = child.communicate(timeout=120)
    finally:
        child.kill()
    assert child.returncode == 0, stderr
    assert stdout == "interrupted\n", stdout + stderr
    assert list(tmp_path.iterdir()) == [], list(tmp_path.rglob("*"))


def test_an_exception_in_the_progress_callback_stops_the_run(tmp_path):
    def stop(progress):
        raise RuntimeError(f"stop at {progress.phase}")
    with pytest.raises(RuntimeError, match="stop at teach"):
        retrace.run(SMALL, out=tmp_path / "out", progress=stop)
    assert list(tmp_path.iterdir()) == []


def test_a_stopped_sweep_keeps_its_rows_and_resumes(tmp_path):
    sweep_file = SOURCE_DIR / "tests/data/sweep_small.yaml"
    reports = []

    def stop_after_a_case(progress):
        reports.append(progress)
        if progress.done >= 1:
            raise RuntimeError("enough")
    with pytest.raises(RuntimeError, match="enough"):
        retrace.sweep(sweep_file, out=tmp_path / "s", jobs=2, plot=False, report=False,
                      progress=stop_after_a_case)
    assert reports[0].countdown and reports[0].total == 8
    rows = (tmp_path / "s" / "results.csv").read_text().splitlines()[1:]
    assert 1 <= len(rows) < 8  # stopped with cases left to run
    resumed = retrace.sweep(sweep_file, out=tmp_path / "s", jobs=2, plot=False, report=False,
                            progress=False)
    assert resumed.cases == 8 and resumed.cases_run == 8 - len(rows)
    assert len(resumed.results["case"]) == 8
