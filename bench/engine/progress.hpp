#pragma once
// Where long work reports how far it got: phases of units (teaching drives, playback runs) and
// the simulated time done, and what the user should be warned of. The engine and the libraries
// that run commands only report; the command line draws (bench/cli/progress.hpp).

#include <filesystem>
#include <functional>
#include <string>

#include "core/errors.hpp"

namespace retrace::bench {

class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  /// Starts a phase ("teach", "playback") with `total` units to do.
  virtual void Phase(const std::string& name, int total) = 0;
  /// Adds simulated seconds done by any thread. Thread-safe.
  virtual void AddSimTime(double seconds) = 0;
  /// One unit of the phase is done. Thread-safe.
  virtual void UnitDone() = 0;
  /// Starts a phase counted down to its end (a sweep's cases): `done` of the `total` units are
  /// done already (resumed). By default a phase like any other.
  virtual void CountdownPhase(const std::string& name, int total, int done) {
    (void)done;
    Phase(name, total);
  }
  /// Something the user should know that is not an error (a scenario's warning, a figure that
  /// could not be rendered): one line, without "warning: ". By default dropped. Thread-safe.
  virtual void Warning(const std::string& text) { (void)text; }
  /// Whether the caller asked the work to stop (the Python module on Ctrl-C). Checked from any
  /// thread every 10 s of simulated time of every episode (SimTimeReporter), which then throws
  /// core::Interrupted; results folders are staged, so none is left half-written. By default
  /// never. Thread-safe.
  virtual bool Cancelled() const { return false; }
};

/// sink->Warning(text) when there is a sink.
inline void Warn(ProgressSink* sink, const std::string& text) {
  if (sink != nullptr) sink->Warning(text);
}

/// Runs `step`, the optional last part of a command (figures, the report page): a core::Error or
/// a filesystem error becomes the warning "no <what>: <why> (the results are complete; retry
/// with `retrace <retry> <dir>`)" through `sink` instead of failing the command.
void FinishOrWarn(const char* what, const char* retry, const std::filesystem::path& dir,
                  const std::function<void()>& step, ProgressSink* sink);

/// Called now and then with the simulated time (s) of a long loop, for progress displays.
using ProgressFn = std::function<void(double sim_time_s)>;

/// A callback for a loop that reports the absolute simulated time it has reached: adds the
/// increments to `sink`, and throws core::Interrupted when the sink is Cancelled(). Empty when
/// `sink` is null. One callback per loop (it keeps the last time it was told).
inline ProgressFn SimTimeReporter(ProgressSink* sink) {
  if (sink == nullptr) return {};
  return [sink, last = 0.0](double t) mutable {
    sink->AddSimTime(t - last);
    last = t;
    if (sink->Cancelled()) throw core::Interrupted();
  };
}

/// A duration for people: "42 s", "3 min 20 s", "2 h 05 min".
std::string FormatDuration(double seconds);

}  // namespace retrace::bench
