#pragma once
// Progress of a long command on a terminal: one line on stderr, rewritten in place, with the
// phase, runs done, simulated time and the real-time factor — or, for a countdown phase
// (sweeps), a bar of the units done and the estimated time left. Off a terminal (CI logs,
// pipes) it prints nothing, so that only the final summary appears. Thread-safe.

#include <chrono>
#include <mutex>
#include <string>

#include "bench/engine/progress.hpp"

namespace retrace::bench {

class ProgressLine : public ProgressSink {
 public:
  /// Enabled when stderr is a terminal.
  ProgressLine();
  ~ProgressLine() override;

  /// Starts a phase ("teach", "playback") with `total` units (runs) to do.
  void Phase(const std::string& name, int total) override;
  /// Starts a phase shown as a bar with the time left ("sweep [####----] 12/32 cases, 3 min
  /// left"): `done` of the `total` units are done already (resumed) and do not count towards
  /// the rate the estimate uses.
  void CountdownPhase(const std::string& name, int total, int done) override;
  /// Adds simulated seconds done by any thread, and redraws at most a few times per second.
  void AddSimTime(double seconds) override;
  /// One unit of the phase is done.
  void UnitDone() override;
  /// Prints "retrace: warning: <text>" on stderr, on a line of its own (always, terminal or not).
  void Warning(const std::string& text) override;
  /// Clears the line (before the summary is printed).
  void Clear();

 private:
  void Draw(bool force);
  bool enabled_ = false;
  std::mutex mutex_;
  std::string phase_;
  bool countdown_ = false;
  int total_ = 0;
  int done_ = 0;
  int done_before_ = 0;  ///< countdown: units done before the phase started
  double sim_time_ = 0.0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  bool drawn_ = false;
};

/// A text bar `width` characters wide, filled in proportion to done / total: "[#####-----]".
std::string ProgressBar(int done, int total, int width);

}  // namespace retrace::bench
