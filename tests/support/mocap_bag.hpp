#pragma once
// A bag as a robot driven under motion capture records it: its LiDAR's scans
// (sensor_msgs/msg/LaserScan on /scan), the motion capture's pose of the robot
// (geometry_msgs/msg/PoseStamped on /pose) and tf_static hanging the LiDAR 0.1 m ahead of
// base_link — and no odometry at all: no nav_msgs/msg/Odometry topic, no tf odom -> base.
// The robot drives 6 m along x at 1 m/s through a walled room with a few boxes; scans of 360
// beams over 360 degrees at 10 Hz, poses at 50 Hz.
//
//   const std::filesystem::path bag = testing::WriteMocapBag(tmp.path() / "mocap.mcap");

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/angle.hpp"
#include "core/pose2.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/ros_messages.hpp"
#include "tests/support/fake_scan.hpp"

namespace retrace::testing {

/// The LiDAR's mount X_RL in the bag's tf_static.
inline const core::Pose2 kMocapMount(0.1, 0.0, 0.0);

/// The robot's pose X_WR at `t` s, as the bag's /pose gives it.
inline core::Pose2 MocapPose(double t) { return {t, 0.0, 0.0}; }

/// Writes the bag to `file` (MCAP) and returns `file`.
inline std::filesystem::path WriteMocapBag(const std::filesystem::path& file) {
  const std::vector<Segment> walls = {{{-2, -3}, {9, -3}},  {{9, -3}, {9, 3}},   {{9, 3}, {-2, 3}},
                                      {{-2, 3}, {-2, -3}},  {{1, 1}, {2, 1}},    {{2, 1}, {2, 2}},
                                      {{4, -2}, {4.5, -1}}, {{6, 1.5}, {7, 2.5}}};
  ScanSpec spec;
  spec.beams = 360;
  spec.fov = 2.0 * core::kPi;
  spec.range_max = 20.0;
  logs::McapWriter w(file, logs::McapCompression::kNone);
  const std::uint16_t scans = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
  const std::uint16_t poses = w.AddChannel("/pose", "geometry_msgs/msg/PoseStamped");
  const std::uint16_t tf_static = w.AddChannel("/tf_static", "tf2_msgs/msg/TFMessage");
  w.Write(tf_static, 0, logs::EncodeTfMessage({{{0.0, "base_link", "laser", kMocapMount}}}));
  for (int k = 0; k <= 300; ++k) {
    const double t = 0.02 * k;
    const auto ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    w.Write(poses, ns, logs::EncodePoseStamped({t, "world", MocapPose(t)}));
    if (k % 5 != 0) continue;
    core::LaserScan scan = FakeScan(
        spec, MocapPose(t) * kMocapMount,
        [&](const core::Vec2& o, const core::Vec2& d) { return NearestSegment(o, d, walls); });
    scan.stamp = t;
    w.Write(scans, ns, logs::EncodeLaserScan({scan, "laser"}));
  }
  w.Close();
  return file;
}

}  // namespace retrace::testing
