#include "bench/replay/log_recorder.hpp"

#include <cmath>
#include <string>

#include "logs/carmen_writer.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/raw_message.hpp"
#include "logs/ros_messages.hpp"

namespace retrace::bench {

namespace {

constexpr const char* kOdomFrame = "odom";
constexpr const char* kBaseFrame = "base_link";
constexpr const char* kLaserFrame = "laser";
constexpr const char* kWorldFrame = "world";

}  // namespace

struct LogRecorder::Files {
  Files(const std::filesystem::path& folder, const std::string& name)
      : carmen(folder / (name + ".log.gz")),
        mcap(folder / (name + ".mcap"), logs::McapCompression::kZstd),
        scan(mcap.AddChannel("/scan", "sensor_msgs/msg/LaserScan")),
        odom(mcap.AddChannel("/odom", "nav_msgs/msg/Odometry")),
        tf(mcap.AddChannel("/tf", "tf2_msgs/msg/TFMessage")),
        tf_static(mcap.AddChannel("/tf_static", "tf2_msgs/msg/TFMessage")),
        truth(mcap.AddChannel("/ground_truth", "geometry_msgs/msg/PoseStamped")) {}

  logs::CarmenWriter carmen;
  logs::McapWriter mcap;
  std::uint16_t scan, odom, tf, tf_static, truth;
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
    logs::TfMessage mount{{{time, kBaseFrame, kLaserFrame, robot_.X_RL}}};
    f.mcap.Write(f.tf_static, ns, logs::EncodeTfMessage(mount));
  }
  f.mcap.Write(f.odom, ns,
               logs::EncodeOdometry({time, kOdomFrame, kBaseFrame, X_OR}, core::Twist{tv_, rv_}));
  f.mcap.Write(f.tf, ns, logs::EncodeTfMessage({{{time, kOdomFrame, kBaseFrame, X_OR}}}));
  f.mcap.Write(f.truth, ns, logs::EncodePoseStamped({time, kWorldFrame, X_WR}));
}

void LogRecorder::OnScan(const core::LaserScan& scan, const core::Pose2& X_OR, const core::Pose2&) {
  Files& f = *files_;
  f.carmen.WriteLaser(scan, X_OR, robot_.X_RL, tv_, rv_);
  f.mcap.Write(f.scan, logs::LogTimeNs(scan.stamp), logs::EncodeLaserScan({scan, kLaserFrame}));
}

void LogRecorder::OnEnd() {
  files_->carmen.Close();
  files_->mcap.Close();
}

}  // namespace retrace::bench
