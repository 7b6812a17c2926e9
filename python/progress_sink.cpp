#include "python/progress_sink.hpp"

#include <pybind11/stl.h>

#include <cstdio>
#include <utility>

#include "python/bindings.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

using Clock = std::chrono::steady_clock;

constexpr auto kReportPeriod = std::chrono::milliseconds(250);

// retrace.RetraceWarning, made once by BindProgress (the module lives as long as the process).
PyObject* retrace_warning = nullptr;

std::string ProgressRepr(const ProgressState& s) {
  char numbers[160];
  std::snprintf(numbers, sizeof(numbers), "done=%d, total=%d, sim_time_s=%.1f, elapsed_s=%.1f",
                s.done, s.total, s.sim_time_s, s.elapsed_s);
  return "Progress(phase=" + std::string(py::repr(py::str(s.phase))) + ", " + numbers + ")";
}

}  // namespace

PythonProgress::PythonProgress(const py::object& progress) {
  if (progress.is_none()) {
    line_ = std::make_unique<ProgressLine>();
  } else if (py::isinstance<py::bool_>(progress) && !progress.cast<bool>()) {
    // quiet
  } else if (PyCallable_Check(progress.ptr())) {
    callback_ = progress;
  } else {
    throw py::type_error("progress: must be None, False or a callable taking a Progress");
  }
  phase_start_ = last_report_ = Clock::now();
}

PythonProgress::~PythonProgress() = default;

void PythonProgress::StartPhase(const std::string& name, int total, int done, bool countdown) {
  std::lock_guard lock(mutex_);
  state_ = ProgressState{name, done, total, 0.0, 0.0, countdown};
  phase_start_ = Clock::now();
  changed_ = forced_ = true;
  news_.notify_all();
}

void PythonProgress::Phase(const std::string& name, int total) {
  StartPhase(name, total, 0, false);
}

void PythonProgress::CountdownPhase(const std::string& name, int total, int done) {
  StartPhase(name, total, done, true);
}

void PythonProgress::AddSimTime(double seconds) {
  std::lock_guard lock(mutex_);
  state_.sim_time_s += seconds;
  changed_ = true;
}

void PythonProgress::UnitDone() {
  std::lock_guard lock(mutex_);
  ++state_.done;
  changed_ = forced_ = true;
  news_.notify_all();
}

void PythonProgress::Warning(const std::string& text) {
  std::lock_guard lock(mutex_);
  warnings_.push_back(text);
  news_.notify_all();
}

void PythonProgress::Finish() {
  std::lock_guard lock(mutex_);
  finished_ = true;
  news_.notify_all();
}

bool PythonProgress::Wait(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  news_.wait_for(lock, timeout, [&] { return finished_ || forced_ || !warnings_.empty(); });
  return finished_;
}

void PythonProgress::Deliver(bool final) {
  std::deque<std::string> warnings;
  ProgressState state;
  bool report = false;
  {
    std::lock_guard lock(mutex_);
    warnings.swap(warnings_);
    const Clock::time_point now = Clock::now();
    report = changed_ && (forced_ || final || now - last_report_ >= kReportPeriod);
    if (report) {
      state = state_;
      state.elapsed_s = std::chrono::duration<double>(now - phase_start_).count();
      changed_ = forced_ = false;
      last_report_ = now;
    }
  }
  for (const std::string& text : warnings) {
    if (line_) line_->Clear();
    if (PyErr_WarnEx(retrace_warning, text.c_str(), 1) != 0) throw py::error_already_set();
  }
  if (!report) return;
  if (callback_) {
    callback_(state);
  } else if (line_) {
    line_->Draw(state);
  }
}

void PythonProgress::Close() {
  if (line_) line_->Clear();
}

void BindProgress(py::module_& m) {
  retrace_warning = PyErr_NewExceptionWithDoc(
      "retrace.RetraceWarning",
      "What retrace warns of without failing: a scenario's warning, a figure or report that "
      "could not be made (the results are complete). The command line prints these as "
      "'retrace: warning: ...'.",
      PyExc_UserWarning, nullptr);
  m.add_object("RetraceWarning", py::handle(retrace_warning));
  py::class_<ProgressState>(m, "Progress",
                            "How far a long call got, as given to its progress callback.")
      .def_readonly("phase", &ProgressState::phase,
                    "'teach', 'playback' or 'sweep <name>' (a countdown of cases)")
      .def_readonly("done", &ProgressState::done, "units of the phase done (drives, runs, cases)")
      .def_readonly("total", &ProgressState::total, "units of the phase")
      .def_readonly("sim_time_s", &ProgressState::sim_time_s,
                    "simulated seconds done in the phase, by all threads")
      .def_readonly("elapsed_s", &ProgressState::elapsed_s, "wall seconds since the phase began")
      .def_readonly("countdown", &ProgressState::countdown,
                    "a phase of cases counted down (a sweep; done includes resumed cases)")
      .def("__repr__", &ProgressRepr);
}

}  // namespace retrace::python
