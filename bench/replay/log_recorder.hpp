#pragma once
// `retrace run --record-log DIR`: a simulated drive written as the logs a real robot leaves, so
// that ROS users can open it in their tools and the log commands can be checked end to end on
// logs whose truth is known (docs/FORMATS.md):
//
//   <name>.log.gz   CARMEN: PARAM (laser geometry), ODOM and TRUEPOS at every odometry tick,
//                   ROBOTLASER1 for every scan (laser and robot pose in the odometry frame)
//   <name>.mcap     ROS 2 (CDR, zstd chunks): /scan sensor_msgs/msg/LaserScan (frame laser),
//                   /odom nav_msgs/msg/Odometry (odom -> base_link), /tf tf2_msgs/msg/TFMessage
//                   (odom -> base_link), /tf_static (base_link -> laser), /ground_truth
//                   geometry_msgs/msg/PoseStamped (frame world)
//   <name>.bag      ROS 1 (lz4 chunks): the same topics and messages in their ROS 1 types
//                   (sensor_msgs/LaserScan, nav_msgs/Odometry, tf2_msgs/TFMessage,
//                   geometry_msgs/PoseStamped), for rosbag, rqt_bag and ROS 1 nodes
//
// Times are the drive's simulated seconds (stamps and log times alike).

#include <filesystem>
#include <memory>
#include <optional>

#include "bench/engine/sensor_tap.hpp"
#include "nav/robot_geometry.hpp"

namespace retrace::bench {

class LogRecorder final : public SensorTap {
 public:
  /// Creates `<folder>/<name>.log.gz`, `<name>.mcap` and `<name>.bag` (the folder is created).
  /// Throws core::IoError if they cannot be created.
  LogRecorder(const std::filesystem::path& folder, const std::string& name,
              const nav::RobotGeometry& robot);
  ~LogRecorder() override;

  void OnOdometry(double time, const core::Pose2& X_OR, const core::Pose2& X_WR) override;
  void OnScan(const core::LaserScan& scan, const core::Pose2& X_OR,
              const core::Pose2& X_WR) override;
  /// Closes the files (complete only now). Throws core::IoError if writing failed.
  void OnEnd() override;

 private:
  struct Files;
  std::unique_ptr<Files> files_;
  nav::RobotGeometry robot_;
  std::optional<double> last_time_;
  core::Pose2 last_X_OR_;
  double tv_ = 0.0;  // m/s, from the last two odometry poses
  double rv_ = 0.0;  // rad/s
};

}  // namespace retrace::bench
