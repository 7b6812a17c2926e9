#include "bench/replay/log_recorder.hpp"

#include <cmath>
#include <string>

#include "logs/carmen_writer.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/raw_message.hpp"
#include "logs/ros1_bag_writer.hpp"
#include "logs/ros1_messages.hpp"
#include "logs/ros_messages.hpp"

namespace retrace::bench {

namespace {

constexpr const char* kOdomFrame = "odom";
constexpr const char* kBaseFrame = "base_link";
constexpr const char* kLaserFrame = "laser";
constexpr const char* kWorldFrame = "world";

}  // namespace

struct LogRecorder::Files {
  // The same ROS messages into an MCAP file (ROS 2: CDR) and a ROS 1 bag.
  class RosLogs {
   public:
    struct Topic {
      std::uint16_t mcap;
      std::uint32_t bag;
    };

    RosLogs(const std::filesystem::path& folder, const std::string& name)
        : mcap_(folder / (name + ".mcap"), logs::McapCompression::kZstd),
          bag_(folder / (name + ".bag"), logs::Ros1BagCompression::kLz4) {}

    Topic Add(const std::string& topic, const std::string& ros2_type,
              const std::string& ros1_type) {
      return {mcap_.AddChannel(topic, ros2_type), bag_.AddConnection(topic, ros1_type)};
    }
    void Scan(Topic t, std::int64_t ns, const logs::ScanMessage& m) {
      mcap_.Write(t.mcap, ns, logs::EncodeLaserScan(m));
      bag_.Write(t.bag, ns, logs::EncodeRos1LaserScan(m));
    }
    void Odometry(Topic t, std::int64_t ns, const logs::OdometryMessage& m, const core::Twist& v) {
      mcap_.Write(t.mcap, ns, logs::EncodeOdometry(m, v));
      bag_.Write(t.bag, ns, logs::EncodeRos1Odometry(m, v));
    }
    void Tf(Topic t, std::int64_t ns, const logs::TfMessage& m) {
      mcap_.Write(t.mcap, ns, logs::EncodeTfMessage(m));
      bag_.Write(t.bag, ns, logs::EncodeRos1TfMessage(m));
    }
    void Pose(Topic t, std::int64_t ns, const logs::PoseStampedMessage& m) {
      mcap_.Write(t.mcap, ns, logs::EncodePoseStamped(m));
      bag_.Write(t.bag, ns, logs::EncodeRos1PoseStamped(m));
    }
    void Close() {
      mcap_.Close();
      bag_.Close();
    }

   private:
    logs::McapWriter mcap_;
    logs::Ros1BagWriter bag_;
  };

  Files(const std::filesystem::path& folder, const std::string& name)
      : carmen(folder / (name + ".log.gz")),
        ros(folder, name),
        scan(ros.Add("/scan", "sensor_msgs/msg/LaserScan", "sensor_msgs/LaserScan")),
        odom(ros.Add("/odom", "nav_msgs/msg/Odometry", "nav_msgs/Odometry")),
        tf(ros.Add("/tf", "tf2_msgs/msg/TFMessage", "tf2_msgs/TFMessage")),
        tf_static(ros.Add("/tf_static", "tf2_msgs/msg/TFMessage", "tf2_msgs/TFMessage")),
        truth(ros.Add("/ground_truth", "geometry_msgs/msg/PoseStamped",
                      "geometry_msgs/PoseStamped")) {}

  logs::CarmenWriter carmen;
  RosLogs ros;
  RosLogs::Topic scan, odom, tf, tf_static, truth;
  bool static_written = false;
};

LogRecorder::LogRecorder(const std::filesystem::path& folder, const std::string& name,
                         const nav::RobotGeometry& robot)
    : robot_(robot) {
  std::filesystem::create_directories(folder);
  files_ = std::make_unique<Files>(folder, name);
}

LogRecorder::~LogRecorder() = default;

void LogRecorder::OnOdometry(double time, const core::Pose2& X_OR, const core::Pose2& X_WR) {
  if (last_time_ && time > *last_time_) {
    const core::Pose2 step = core::Between(last_X_OR_, X_OR);
    const double dt = time - *last_time_;
    tv_ = (step.x >= 0.0 ? 1.0 : -1.0) * std::hypot(step.x, step.y) / dt;
    rv_ = step.theta / dt;
  }
  last_time_ = time;
  last_X_OR_ = X_OR;
  Files& f = *files_;
  f.carmen.WriteOdometry(time, X_OR, tv_, rv_);
  f.carmen.WriteTruePose(time, X_WR, X_OR);

  const std::int64_t ns = logs::LogTimeNs(time);
  if (!f.static_written) {
    f.static_written = true;
    f.ros.Tf(f.tf_static, ns, {{{time, kBaseFrame, kLaserFrame, robot_.X_RL}}});
  }
  f.ros.Odometry(f.odom, ns, {time, kOdomFrame, kBaseFrame, X_OR}, core::Twist{tv_, rv_});
  f.ros.Tf(f.tf, ns, {{{time, kOdomFrame, kBaseFrame, X_OR}}});
  f.ros.Pose(f.truth, ns, {time, kWorldFrame, X_WR});
}

void LogRecorder::OnScan(const core::LaserScan& scan, const core::Pose2& X_OR, const core::Pose2&) {
  Files& f = *files_;
  f.carmen.WriteLaser(scan, X_OR, robot_.X_RL, tv_, rv_);
  f.ros.Scan(f.scan, logs::LogTimeNs(scan.stamp), {scan, kLaserFrame});
}

void LogRecorder::OnEnd() {
  files_->carmen.Close();
  files_->ros.Close();
}

}  // namespace retrace::bench
