#pragma once
// Progress of a long command on a terminal: one line on stderr, rewritten in place, with the
// phase, runs done, simulated time and the real-time factor. Off a terminal (CI logs, pipes) it
// prints nothing, so that only the final summary appears. Thread-safe.

#include <chrono>
#include <mutex>
#include <string>

namespace retrace::bench {

class ProgressLine {
 public:
  /// Enabled when stderr is a terminal.
  ProgressLine();
  ~ProgressLine();

  /// Starts a phase ("teach", "playback") with `total` units (runs) to do.
  void Phase(const std::string& name, int total);
  /// Adds simulated seconds done by any thread, and redraws at most a few times per second.
  void AddSimTime(double seconds);
  /// One unit of the phase is done.
  void UnitDone();
  /// Clears the line (before the summary is printed).
  void Clear();

 private:
  void Draw(bool force);
  bool enabled_ = false;
  std::mutex mutex_;
  std::string phase_;
  int total_ = 0;
  int done_ = 0;
  double sim_time_ = 0.0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  bool drawn_ = false;
};

}  // namespace retrace::bench
