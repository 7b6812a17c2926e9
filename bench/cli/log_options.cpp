#include "bench/cli/log_options.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "core/errors.hpp"

namespace retrace::bench {

void AddLogArgument(CLI::App* cmd, std::filesystem::path* log) {
  cmd->add_option("log", *log,
                  "The log: a CARMEN .log/.clf (gzipped or not), an .mcap or .db3 file, a "
                  "rosbag2 folder or a ROS 1 .bag")
      ->required();
}

void AddWindowOptions(CLI::App* cmd, LogWindow* window) {
  cmd->add_option("--from", window->from_s,
                  "Start of the part to use: s since the log's first message (default 0)");
  cmd->add_option("--to", window->to_s,
                  "End of the part to use: s since the log's first message (default: the end)");
}

void AddReferenceOption(CLI::App* cmd, std::optional<std::filesystem::path>* reference) {
  cmd->add_option("--reference", *reference,
                  "TUM file with a reference trajectory on the log's clock");
}

void AddStreamOptions(CLI::App* cmd, logs::StreamChoice* choice) {
  cmd->add_option("--scan-topic", choice->scan_topic,
                  "LaserScan topic (ROS 1: also MultiEchoLaserScan; CARMEN: FLASER, ROBOTLASER1, "
                  "RAWLASER1, RLASER); needed when the log has several");
  cmd->add_option("--odometry-topic", choice->odometry_topic,
                  "Odometry topic (CARMEN: ODOM or a laser message name); default: the only "
                  "nav_msgs/msg/Odometry (ROS 1: nav_msgs/Odometry) topic, else tf from "
                  "--odom-frame");
  cmd->add_option("--reference-topic", choice->reference_topic,
                  "PoseStamped topic with a reference trajectory (ROS 1: also "
                  "PoseWithCovarianceStamped; CARMEN: TRUEPOS)");
  cmd->add_option("--odom-frame", choice->odom_frame,
                  "Odometry frame of the tf transforms used when there is no odometry topic")
      ->default_str("odom");
  cmd->add_option("--base-frame", choice->base_frame,
                  "The robot's frame in tf (default: the only frame tf moves in the odom frame)");
  cmd->add_option("--scan-rate", choice->scan_rate_hz,
                  "For a log without time stamps: stamp scan k at k / HZ s and every other "
                  "message at the last scan's (the log's own stamps are not used)")
      ->check(CLI::PositiveNumber)
      ->type_name("HZ");
}

}  // namespace retrace::bench
