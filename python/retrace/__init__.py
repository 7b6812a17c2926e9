"""retrace for Python: teaching-playback navigation without a consistent map, simulated.

The library calls of the ``retrace`` program, one function per command, and ``load_results``,
which reads a results folder into Python values (dicts, NumPy arrays). docs/PYTHON.md is the
reference; every function has a docstring (``help(retrace.run)``).

Import it from a build tree with ``PYTHONPATH=<build>/python``.
"""

from ._retrace import (  # noqa: F401  (the extension: docs/PYTHON.md)
    ComparisonResult,
    Episode,
    LogInfo,
    LogResult,
    ModeResult,
    NativeStack,
    Observation,
    Progress,
    Recording,
    RetraceWarning,
    RunResult,
    Scan,
    SweepResult,
    TaughtMap,
    Teaching,
    __version__,
    compare,
    integrate_odometry,
    log_info,
    log_localize,
    log_simulate,
    log_teach,
    playback,
    read_csv,
    read_json,
    read_map,
    read_path,
    read_tum,
    register_stack,
    registered_stacks,
    render,
    report,
    run,
    sweep,
    teach,
)
from .results import (  # noqa: F401
    Comparison,
    Localization,
    Mode,
    Results,
    Run,
    Sweep,
    Teach,
    load_results,
)

__all__ = [
    "run", "teach", "playback", "sweep", "compare",
    "log_info", "log_teach", "log_localize", "log_simulate",
    "load_results", "render", "report", "register_stack", "registered_stacks",
    "integrate_odometry", "NativeStack",
    "read_json", "read_tum", "read_path", "read_csv", "read_map",
    "RunResult", "ModeResult", "SweepResult", "ComparisonResult", "LogResult", "LogInfo",
    "Progress", "RetraceWarning",
    "Teaching", "Episode", "Observation", "Recording", "TaughtMap", "Scan",
    "Results", "Mode", "Run", "Teach", "Localization", "Sweep", "Comparison",
]
