#pragma once
// The parts of the Python module `retrace._retrace` (docs/PYTHON.md), one per area of the
// library calls; python/module.cpp calls each once.

#include <pybind11/pybind11.h>

namespace retrace::python {

/// The translation of retrace's errors into Python exceptions (python/errors.hpp).
void BindErrors(pybind11::module_& m);
/// Progress, RetraceWarning (python/progress_sink.hpp).
void BindProgress(pybind11::module_& m);
/// run, teach, playback and their RunResult.
void BindRun(pybind11::module_& m);
/// sweep and its SweepResult.
void BindSweep(pybind11::module_& m);
/// compare and its ComparisonResult.
void BindCompare(pybind11::module_& m);
/// log_teach, log_localize, log_simulate and their LogResult.
void BindLogs(pybind11::module_& m);
/// log_info and its LogInfo.
void BindLogInfo(pybind11::module_& m);
/// Teaching, Episode and their parts: runs stepped from Python.
void BindEpisodes(pybind11::module_& m);
/// register_stack, registered_stacks: Python stacks in every command.
void BindStacks(pybind11::module_& m);
/// The readers of results files (read_json, read_tum, read_csv, read_map, read_path), render and
/// report.
void BindResults(pybind11::module_& m);

}  // namespace retrace::python
