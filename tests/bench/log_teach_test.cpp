// The teaching drive of a log (`retrace log-teach`, bench/replay/log_teach.hpp).

#include "bench/replay/log_teach.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>
#include <vector>

#include "bench/replay/log_localize_run.hpp"
#include "bench/replay/log_teach_run.hpp"
#include "logs/carmen_writer.hpp"
#include "logs/sensor_log.hpp"
#include "tests/support/fake_scan.hpp"
#include "tests/support/io_error_of.hpp"
#include "tests/support/mocap_bag.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace log_teach_test {

namespace fs = std::filesystem;

// A 6 m drive along a room with a few boxes, odometry exact, a 360-degree LiDAR at 10 Hz:
// shorter than the online switcher's window, so the recorders hold every scan back until
// Finish() — as for the Neato bag's 3.6 m square.
fs::path ShortDrive(const fs::path& file) {
  const std::vector<testing::Segment> walls = {
      {{-2, -3}, {9, -3}}, {{9, -3}, {9, 3}}, {{9, 3}, {-2, 3}},    {{-2, 3}, {-2, -3}},
      {{1, 1}, {2, 1}},    {{2, 1}, {2, 2}},  {{4, -2}, {4.5, -1}}, {{6, 1.5}, {7, 2.5}}};
  testing::ScanSpec spec;
  spec.beams = 360;
  spec.fov = 2.0 * core::kPi;
  spec.range_max = 20.0;
  logs::CarmenWriter w(file);
  for (int k = 0; k <= 60; ++k) {
    const core::Pose2 X_OR(0.1 * k, 0.0, 0.0);
    core::LaserScan scan =
        testing::FakeScan(spec, X_OR, [&](const core::Vec2& o, const core::Vec2& d) {
          return testing::NearestSegment(o, d, walls);
        });
    scan.stamp = 0.1 * k;
    w.WriteLaser(scan, X_OR, core::Pose2::Identity(), 1.0, 0.0);
  }
  w.Close();
  return file;
}

// `retrace log-teach` printed "keyframes matched 0 of 0" for such a drive: the counts were read
// before Finish() matched the held scans.
TEST(LogTeach, ScanMatchedCountsIncludeTheKeyframesFinishMatches) {
  testing::TempDir tmp;
  const logs::LogIndex index = logs::IndexLog(ShortDrive(tmp.path() / "short.log"));
  ASSERT_EQ(index.problem, "");
  LogConfig config;  // online switching, the default
  config.modes = {MapMode::kScanMatched};
  const LogStreams streams = PrepareLogStreams(index, config, false, std::nullopt);
  const LogTeachResult result = RunLogTeach(index, streams, config, {});
  ASSERT_EQ(result.modes.size(), 1U);
  const std::array<int, 5>& counts = result.modes[0].match_counts;
  const int total = std::accumulate(counts.begin(), counts.end(), 0);
  // A keyframe every 0.5 m of the 6 m: 13, each with a verdict.
  EXPECT_GE(total, 12);
  EXPECT_GT(counts[0], 0);  // matched
}

// A bag recorded under motion capture (scans and a PoseStamped topic, no odometry) drives on
// its own odometry only with --synthetic-odometry: without, one line says what is missing and
// what stands in.
TEST(LogTeach, ABagWithoutOdometryIsRefusedInOneLineNamingTheFix) {
  testing::TempDir tmp;
  const fs::path bag = testing::WriteMocapBag(tmp.path() / "mocap.mcap");
  const logs::LogIndex index = logs::IndexLog(bag);
  const std::string error =
      testing::IoErrorOf([&] { PrepareLogStreams(index, LogConfig{}, false, std::nullopt); });
  EXPECT_EQ(error, bag.string() +
                       ": no odometry (no nav_msgs/msg/Odometry topic, no tf from 'odom'); its "
                       "reference '/pose' can stand in: add --synthetic-odometry");
  // Without a reference either, there is nothing to draw odometry from.
  logs::LogIndex bare = index;
  bare.reference.clear();
  bare.reference_topic.clear();
  bare.reference_source.clear();
  EXPECT_EQ(testing::IoErrorOf([&] { PrepareLogStreams(bare, LogConfig{}, true, std::nullopt); }),
            bag.string() +
                ": no odometry (no nav_msgs/msg/Odometry topic, no tf from 'odom') and no "
                "reference to draw it from: give one with --reference FILE.tum");
}

// ... and with --synthetic-odometry, log-teach teaches it and log-localize localizes it.
TEST(LogTeach, ABagWithoutOdometryTeachesAndLocalizesOnSyntheticOdometry) {
  testing::TempDir tmp;
  LogTeachRequest teach;
  teach.run.log = testing::WriteMocapBag(tmp.path() / "mocap.mcap");
  teach.run.out = tmp.path() / "taught";
  teach.run.synthetic_odometry = true;
  teach.run.figures = false;
  teach.modes = {MapMode::kPartial};
  const LogTeaching taught = TeachLog(teach);
  EXPECT_TRUE(WriteLogTeachFolder(taught, "log-teach", 0.0).empty());
  EXPECT_TRUE(fs::exists(tmp.path() / "taught/partial/teach/sub_map_num.txt"));
  EXPECT_NE(tmp.Read("taught/partial/manifest.yaml").find("synthetic, drawn from /pose"),
            std::string::npos);

  LogLocalizeRequest localize;
  localize.run = teach.run;
  localize.run.out = tmp.path() / "localized";
  localize.teach_dir = tmp.path() / "taught/partial/teach";
  const LogLocalization localized = LocalizeLog(localize);
  EXPECT_GT(localized.metrics.scans, 0);
  WriteLogLocalizeFolder(localized, "log-localize", 0.0);
  EXPECT_TRUE(fs::exists(tmp.path() / "localized/metrics.json"));
}

}  // namespace log_teach_test
}  // namespace retrace::bench
