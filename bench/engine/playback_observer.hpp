#pragma once
// A look into a playback run at each control tick, for recorders that need more than the trace
// (the video). The episode calls it after the tick's command is decided; an observer may read
// everything but changes nothing, so a run is the same with or without one.

#include <vector>

#include "core/pose2.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"
#include "sim/lidar.hpp"
#include "sim/static_geometry.hpp"

namespace retrace::bench {

/// The state of the run at one control tick. References are valid during the call only.
struct PlaybackMoment {
  double time = 0.0;
  const nav::Localizer& localizer;
  const nav::MapServer& server;
  core::Pose2 X_WR;                ///< ground truth in W
  core::Pose2 X_MR_truth;          ///< local ground truth in the current map
  double speed = 0.0;              ///< commanded linear speed (m/s)
  double time_since_switch = 0.0;  ///< s since the last map switch (+inf before the first)
  const sim::LidarReading* lidar = nullptr;      ///< the latest scan, if any
  const nav::LocalizerUpdate* update = nullptr;  ///< the latest update that ran, if any
  const std::vector<sim::DynamicCircle>& pedestrians_W;
};

class PlaybackObserver {
 public:
  virtual ~PlaybackObserver() = default;
  /// Called once per control tick, in time order.
  virtual void OnTick(const PlaybackMoment& moment) = 0;
  /// Called once after the last tick (not called when the run throws).
  virtual void OnEnd() = 0;
};

}  // namespace retrace::bench
