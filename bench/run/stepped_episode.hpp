#pragma once
// Playback runs stepped by their caller (docs/PYTHON.md, "Your own stack in the loop"): the
// scenario's teaching drive is run once and recorded (scans, odometry, reference poses) so that
// the caller can build its own maps; then, in each run, each step hands out the sensor data since
// the last control tick and takes the caller's command and estimate. The loop is the one `retrace
// run` drives (bench/engine/playback_episode.hpp), so the run is measured exactly as `retrace
// run`'s; with `builtin`, retrace's own stack (playback.stack) answers and the caller only watches.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/progress.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/engine/trace.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/stack/navigation_stack.hpp"
#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/twist.hpp"

namespace retrace::bench {

/// What to teach for stepped runs: the scenario, one map mode, the seed and overrides.
struct TeachingRequest {
  std::filesystem::path scenario;
  std::string mode = "partial";        ///< the map mode whose maps and paths are taught
  std::optional<std::uint64_t> seed;   ///< the scenario's seed unless given
  std::vector<std::string> overrides;  ///< a.b.c=value
};

/// An odometry reading: the wheel odometry's pose X_OR (its own frame O) at time t, as a log
/// records it.
struct OdometryReading {
  double time = 0.0;
  core::Pose2 X_OR;
};

/// An odometry increment at time t, as every stack is given odometry (NavigationStack::OnOdometry).
struct OdometryIncrement {
  double time = 0.0;
  core::OdometryDelta delta;
};

/// The teaching drive, as a stack that builds its own maps sees it: every scan and odometry
/// reading, and the reference (ground truth in W) at each odometry reading. The taught maps
/// and paths retrace built for the mode (frames: map k starts at the odometry pose where the
/// drive began it) are in `teach.bundle`.
struct TeachRecording {
  std::vector<core::LaserScan> scans;
  std::vector<OdometryReading> odometry;
  std::vector<core::Pose2> X_WR;  ///< the reference at each odometry reading
};

/// A scenario taught once, for any number of stepped runs (each run's seed: PlaybackRng).
struct SteppedTeaching {
  Scenario scenario;
  ModeTeach teach;
  TeachRecording recording;
  double duration_s = 0.0;  ///< the teaching drive's (sets the playback timeout)
};

/// Loads the scenario, runs and records the teaching drive, reporting to `progress` (may be
/// null). Throws core::ConfigError / core::IoError like `retrace run`, core::WorldError when the
/// route cannot be driven, core::Interrupted when `progress` is Cancelled().
std::shared_ptr<const SteppedTeaching> TeachForStepping(const TeachingRequest& request,
                                                        ProgressSink* progress = nullptr);

/// The metrics of the runs of one teaching, as `retrace run` writes them in <mode>/metrics.json
/// (the aggregate, with repeatability across the runs and the taught maps' quality).
AggregateMetrics AggregateSteppedRuns(const SteppedTeaching& teaching,
                                      const std::vector<const RunTrace*>& runs);

/// What the sensors gave between two control ticks.
struct Observation {
  double time = 0.0;  ///< s since the run started: the control tick's
  std::vector<OdometryIncrement> odometry;
  std::vector<core::LaserScan> scans;
  /// An operator drove the robot (a scripted takeover, ignoring the answers meanwhile) and
  /// handed it back at the last tick: where the stack is on the route is its to find again.
  bool handed_back = false;
};

class SteppedEpisode {
 public:
  /// Playback run `run` (>= 0) of `teaching`; with `builtin`, retrace's own stack
  /// (playback.stack) answers each step and the caller only watches.
  SteppedEpisode(std::shared_ptr<const SteppedTeaching> teaching, int run, bool builtin);
  ~SteppedEpisode();
  SteppedEpisode(const SteppedEpisode&) = delete;
  SteppedEpisode& operator=(const SteppedEpisode&) = delete;

  const SteppedTeaching& teaching() const;
  int run() const;
  /// The number of maps of the taught route (the answer's map is below it).
  std::size_t maps() const;

  /// Steps the world to the next control tick; the sensor data on the way. Throws
  /// core::ConfigError("step") when the run is done, or when Act was not called since.
  const Observation& Observe();
  /// The control tick with the caller's answer, as any stack answers (ignored with `builtin`:
  /// pass nullopt). An answer in another map than the one before that names no map_change
  /// changed maps from the estimate before (MapChangeTracker). Throws core::ConfigError("answer")
  /// for an answer without a builtin stack missing, a map index out of range, a map_change that
  /// does not end in the answer's map or a non-finite value; ("step") before Observe. Returns
  /// done().
  bool Act(const std::optional<StackOutput>& answer);
  bool done() const;
  /// The run's trace and metrics (as `retrace run` computes them), once done(); throws
  /// core::ConfigError("step") before.
  const RunTrace& trace();
  RunMetrics Metrics();
  /// The last control tick as the harness recorded it (ground truth included: for a learning
  /// agent's reward, never for a stack), and the collisions so far; nullptr before the first
  /// Act and once the trace was taken.
  const PlaybackSample* LastSample() const;
  std::size_t Collisions() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace retrace::bench
