#pragma once
// The ProgressSink of a library call made from Python. The library's threads record into it; the
// calling thread, holding the GIL between waits (python/interruptible.hpp), hands the news to
// Python: the progress callback (or the terminal line that the command line also draws) and the
// library's warnings, issued as RetraceWarning through Python's warnings module. Cancel() makes
// the library stop at its next report (ProgressSink::Cancelled, core::Interrupted).

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>

#include "bench/engine/progress.hpp"
#include "python/progress_line.hpp"

namespace retrace::python {

/// What the progress callback is given (retrace.Progress): how far the running phase got.
struct ProgressState {
  std::string phase;        ///< "teach", "playback", "sweep <name>"
  int done = 0;             ///< units (drives, runs, cases) done
  int total = 0;            ///< units of the phase
  double sim_time_s = 0.0;  ///< simulated time done in the phase, by all threads
  double elapsed_s = 0.0;   ///< wall time since the phase started
  bool countdown = false;   ///< a phase of cases counted down (a sweep)
};

class PythonProgress : public bench::ProgressSink {
 public:
  /// `progress`: None (the terminal line on sys.stderr when it is a terminal, as the command
  /// line draws it), False (nothing) or a callable taking a Progress. Throws
  /// pybind11::type_error for anything else. Needs the GIL.
  explicit PythonProgress(const pybind11::object& progress);
  ~PythonProgress() override;

  // What the library reports, from any thread.
  void Phase(const std::string& name, int total) override;
  void CountdownPhase(const std::string& name, int total, int done) override;
  void AddSimTime(double seconds) override;
  void UnitDone() override;
  void Warning(const std::string& text) override;
  bool Cancelled() const override { return cancelled_; }

  /// Asks the library to stop.
  void Cancel() { cancelled_ = true; }
  /// The work is over (done, failed or stopped): wakes the calling thread. Any thread.
  void Finish();
  /// Waits, without the GIL, until there is news or the work is over, at most `timeout`;
  /// returns whether the work is over.
  bool Wait(std::chrono::milliseconds timeout);
  /// With the GIL: issues the pending warnings and reports the state when it changed (a change
  /// of simulated time alone at most every 0.25 s unless `final`). Throws
  /// pybind11::error_already_set when Python raised (the callback, a warnings filter "error").
  void Deliver(bool final);
  /// With the GIL: clears the terminal line.
  void Close();

 private:
  void StartPhase(const std::string& name, int total, int done, bool countdown);

  pybind11::object callback_;           ///< None: the terminal line (when enabled)
  std::unique_ptr<ProgressLine> line_;  ///< progress=None
  std::atomic<bool> cancelled_{false};
  std::mutex mutex_;
  std::condition_variable news_;
  ProgressState state_;
  std::chrono::steady_clock::time_point phase_start_;
  std::chrono::steady_clock::time_point last_report_;
  bool changed_ = false;
  bool forced_ = false;  ///< a change to report at once: a new phase, a unit done
  bool finished_ = false;
  std::deque<std::string> warnings_;
};

}  // namespace retrace::python
