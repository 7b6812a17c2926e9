#pragma once
// Records one playback run for the metrics (bench/engine/trace.hpp): a sample at every control
// tick, every localizer update scored against the LiDAR's own knowledge of which beams hit a
// pedestrian, the localization snapshot worth a figure, the map switches and the scripted
// events. It also keeps the local truth — ground truth expressed in the current partial map —
// that the end conditions compare the estimate with. Ground truth stays here, in the engine:
// the navigation stack never sees it.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/local_truth.hpp"
#include "bench/engine/metrics_config.hpp"
#include "bench/engine/trace.hpp"
#include "bench/stack/navigation_stack.hpp"
#include "core/pose2.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"
#include "sim/lidar.hpp"
#include "sim/simulator.hpp"

namespace retrace::bench {

class RunRecorder {
 public:
  /// Run `run` (seeded with `seed`), measured against `teach`, which must outlive the recorder.
  RunRecorder(int run, std::uint64_t seed, const TeachTrace& teach, const MetricsConfig& metrics,
              double robot_radius);

  /// A localizer update that ran on `lidar` at time t, in map `map_index`, costing cpu_s.
  void OnUpdate(const nav::Localizer& localizer, const nav::LocalizerUpdate& update,
                const sim::LidarReading& lidar, double t, double cpu_s, std::size_t map_index,
                const sim::Simulator& simulator);
  /// A map switch at time t, the robot at X_WR; the local truth moves into the new map.
  void OnSwitch(double t, const MapChange& map_change, const core::Pose2& X_WR);
  /// A control tick: the robot at X_WR, the estimate X_MR in map `map_index`, whether the
  /// localizer deems itself lost, the command sent. Returns the local truth of the robot in that
  /// map.
  core::Pose2 OnControlTick(double t, std::size_t map_index, const core::Pose2& X_WR,
                            const core::Pose2& X_MR, bool lost, bool off_map,
                            const DriveCommand& command, const sim::Simulator& simulator);
  /// Scripted events that fired at time t.
  void OnEvents(double t, const std::vector<std::string>& names);

  /// The trace of the run that ended with `outcome`.
  /// The run so far (its samples up to the last control tick).
  const RunTrace& trace() const { return trace_; }
  RunTrace Finish(Outcome outcome, const std::vector<sim::CollisionEvent>& collisions,
                  double sim_time_s, double cpu_time_s);

 private:
  MetricsConfig metrics_;
  double robot_radius_;
  RunTrace trace_;
  LocalTruthAcrossMaps local_truth_;
};

}  // namespace retrace::bench
