#pragma once
// Taking the localization snapshot of a run (bench/engine/snapshot.hpp) from a localizer update
// and the LiDAR reading it ran on.

#include <cstdint>
#include <vector>

#include "bench/engine/snapshot.hpp"
#include "core/pose2.hpp"
#include "nav/localizer.hpp"
#include "sim/lidar.hpp"

namespace retrace::bench {

/// Counts the tested beams of `update` that hit a pedestrian.
int PedestrianBeams(const nav::LocalizerUpdate& update, const sim::LidarReading& reading);

/// Takes the snapshot of an update that ran on `scan`; `X_MR_truth` is the local truth at that
/// moment (a log without reference: the estimate), `pedestrian` marks the beams that hit a
/// pedestrian (empty: unknown, as in a log). The likelihood slice spans ±half_width m around the
/// truth.
LocalizationSnapshot CaptureSnapshot(const nav::Localizer& localizer,
                                     const nav::LocalizerUpdate& update,
                                     const core::LaserScan& scan,
                                     const std::vector<std::uint8_t>& pedestrian, double time,
                                     int map_index, const core::Pose2& X_WR,
                                     const core::Pose2& X_MR_truth,
                                     std::vector<sim::DynamicCircle> pedestrians_W,
                                     double half_width = 2.0, double resolution = 0.05);

/// The same for a simulated reading, whose beams know what they hit.
LocalizationSnapshot CaptureSnapshot(const nav::Localizer& localizer,
                                     const nav::LocalizerUpdate& update,
                                     const sim::LidarReading& reading, double time, int map_index,
                                     const core::Pose2& X_WR, const core::Pose2& X_MR_truth,
                                     std::vector<sim::DynamicCircle> pedestrians_W,
                                     double half_width = 2.0, double resolution = 0.05);

}  // namespace retrace::bench
