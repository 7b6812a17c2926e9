// `retrace log-info` describes a log whole, whatever the other log commands would need chosen.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "bench/cli/log_info_command.hpp"  // the exit code of log-info itself
#include "bench/replay/log_description.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/ros_messages.hpp"
#include "logs/sensor_log.hpp"
#include "tests/support/mocap_bag.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace log_info_test {

namespace fs = std::filesystem;

core::LaserScan Scan(double t, int beams, double range_max) {
  core::LaserScan scan;
  scan.stamp = t;
  scan.angle_min = -core::kPi;
  scan.angle_increment = 2.0 * core::kPi / beams;
  scan.range_min = 0.02;
  scan.range_max = range_max;
  scan.ranges.assign(static_cast<std::size_t>(beams), 2.0f);
  return scan;
}

// A bag as the Neato's driver records it: /scan and /stable_scan, both LaserScan, and /odom.
fs::path TwoScanTopicBag(const fs::path& file) {
  logs::McapWriter w(file, logs::McapCompression::kNone);
  const std::uint16_t scan = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
  const std::uint16_t stable = w.AddChannel("/stable_scan", "sensor_msgs/msg/LaserScan");
  const std::uint16_t odom = w.AddChannel("/odom", "nav_msgs/msg/Odometry");
  for (int k = 0; k < 20; ++k) {
    const double t = 0.2 * k;
    const auto ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    w.Write(odom, ns, logs::EncodeOdometry({t, "odom", "base_footprint", core::Pose2(t, 0, 0)}));
    w.Write(scan, ns, logs::EncodeLaserScan({Scan(t, 361, 5.0), "base_laser_link"}));
    w.Write(stable, ns + 1000, logs::EncodeLaserScan({Scan(t, 180, 8.0), "base_laser_link"}));
  }
  w.Close();
  return file;
}

TEST(LogInfo, DescribesEveryScanTopicAndNamesTheChoiceTheOtherCommandsNeed) {
  testing::TempDir tmp;
  const logs::LogIndex index = logs::IndexLog(TwoScanTopicBag(tmp.path() / "neato.mcap"));
  EXPECT_TRUE(index.needs_choice);
  const std::string text = DescribeLog(index);
  EXPECT_NE(text.find("scans:      /scan: 20 scans of 361 beams"), std::string::npos) << text;
  EXPECT_NE(text.find("ranges 0.02 to 5.00 m"), std::string::npos) << text;
  EXPECT_NE(text.find("scans:      /stable_scan: 20 scans of 180 beams"), std::string::npos)
      << text;
  EXPECT_NE(text.find("odometry:   /odom (nav_msgs/msg/Odometry): 20 poses"), std::string::npos)
      << text;
  EXPECT_NE(text.find("choose:     several topics hold laser scans (sensor_msgs/msg/LaserScan) "
                      "(/scan, /stable_scan); choose one with --scan-topic"),
            std::string::npos)
      << text;
  // log-info exits 0: the log is described, not refused.
  LogInfoOptions options;
  options.log = tmp.path() / "neato.mcap";
  EXPECT_EQ(RunLogInfoCommand(options), 0);
  // With the choice made, the scan topic used is marked and nothing is left to choose.
  logs::StreamChoice choice;
  choice.scan_topic = "/stable_scan";
  const std::string chosen = DescribeLog(logs::IndexLog(tmp.path() / "neato.mcap", choice));
  EXPECT_NE(chosen.find("scans:      /stable_scan (used): 20 scans"), std::string::npos) << chosen;
  EXPECT_EQ(chosen.find("choose:"), std::string::npos) << chosen;
}

// A bag recorded under motion capture has no odometry: log-info describes it as any other and
// names what stands in, instead of ending with "no odometry".
TEST(LogInfo, DescribesABagWithoutOdometryAndNamesWhatWouldDrawIt) {
  testing::TempDir tmp;
  const fs::path bag = testing::WriteMocapBag(tmp.path() / "mocap.mcap");
  const std::string text = DescribeLog(logs::IndexLog(bag));
  EXPECT_NE(text.find("  /scan       sensor_msgs/msg/LaserScan             61       0.00       "
                      "6.00    10.00"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  /pose       geometry_msgs/msg/PoseStamped        301       0.00       "
                      "6.00    50.00"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("scans:      /scan: 61 scans of 360 beams"), std::string::npos) << text;
  EXPECT_NE(text.find("\nodometry:   none (no nav_msgs/msg/Odometry topic, no tf from 'odom'): "
                      "log-teach and log-localize draw it from the reference '/pose' with "
                      "--synthetic-odometry\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("mount:      X_RL (0.100 m, 0.000 m, 0.0 deg) from tf_static base_link -> "
                      "laser"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("reference:  /pose (geometry_msgs/msg/PoseStamped): 301 poses, 6.0 m"),
            std::string::npos)
      << text;
  LogInfoOptions options;
  options.log = bag;
  EXPECT_EQ(RunLogInfoCommand(options), 0);
}

}  // namespace log_info_test
}  // namespace retrace::bench
