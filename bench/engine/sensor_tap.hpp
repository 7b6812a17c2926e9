#pragma once
// A copy of a drive's sensor stream as it happens, for recorders that turn a simulated drive into
// a log (`retrace run --record-log`): every odometry tick and every scan, with the odometry pose
// and the ground truth at that instant. The stepper (bench/engine/stepper.hpp), which both the
// teaching drive and the playback runs step through, feeds it; a tap only reads, so a drive is
// the same with or without one.

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"

namespace retrace::bench {

class SensorTap {
 public:
  virtual ~SensorTap() = default;
  /// An odometry tick at `time` (s since the drive started): the odometry pose X_OR after it and
  /// the ground truth X_WR.
  virtual void OnOdometry(double time, const core::Pose2& X_OR, const core::Pose2& X_WR) = 0;
  /// A scan (scan.stamp is its time), with the latest odometry pose and the ground truth.
  virtual void OnScan(const core::LaserScan& scan, const core::Pose2& X_OR,
                      const core::Pose2& X_WR) = 0;
  /// The drive ended normally (not called when it throws): finish the recording.
  virtual void OnEnd() = 0;
};

}  // namespace retrace::bench
