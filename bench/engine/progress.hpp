#pragma once
// Where long work reports how far it got: phases of units (teaching drives, playback runs) and
// the simulated time done. The engine only reports; the command line draws
// (bench/cli/progress.hpp).

#include <functional>
#include <string>

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
};

/// Called now and then with the simulated time (s) of a long loop, for progress displays.
using ProgressFn = std::function<void(double sim_time_s)>;

/// A callback for a loop that reports the absolute simulated time it has reached: adds the
/// increments to `sink`. Empty when `sink` is null. One callback per loop (it keeps the last
/// time it was told).
inline ProgressFn SimTimeReporter(ProgressSink* sink) {
  if (sink == nullptr) return {};
  return [sink, last = 0.0](double t) mutable {
    sink->AddSimTime(t - last);
    last = t;
  };
}

}  // namespace retrace::bench
