// The localizer's evidence accounting (docs/METHOD.md, "Reliability"): beams through a mapped
// wall are never dynamic, and a belief the scans do not support says so.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nav/localizer.hpp"
#include "tests/nav/localizer_room.hpp"

namespace retrace::nav {
namespace {

using namespace testing_room;

// The map holds walls the world does not: a box x in [3.2, 8.8], y in [1.3, 7.7] around the
// robot's circle, so that most beams that reach the room's walls see through one of them.
constexpr double kX0 = 3.2, kX1 = 8.8, kY0 = 1.3, kY1 = 7.7;

std::vector<Rect> WithPhantomBox(std::vector<Rect> rects) {
  rects.push_back({kX0 - 0.05, kY0, kX0 + 0.05, kY1});
  rects.push_back({kX1 - 0.05, kY0, kX1 + 0.05, kY1});
  rects.push_back({kX0, kY0 - 0.05, kX1, kY0 + 0.05});
  rects.push_back({kX0, kY1 - 0.05, kX1, kY1 + 0.05});
  return rects;
}

// Whether the beam of `scan` at index i, taken from X_WL inside the box, ends more than 0.4 m
// outside it.
bool Crosses(const core::LaserScan& scan, std::size_t i, const Pose2& X_WL) {
  const double r = scan.ranges[i];
  const double a = X_WL.theta + scan.Angle(i);
  const double x = X_WL.x + r * std::cos(a), y = X_WL.y + r * std::sin(a);
  return x < kX0 - 0.4 || x > kX1 + 0.4 || y < kY0 - 0.4 || y > kY1 + 0.4;
}

class ThroughWall : public ::testing::TestWithParam<MeasurementModel> {};

TEST_P(ThroughWall, ABeamThroughAMappedWallIsNeverDynamic) {
  // Most beams see through the phantom box. Those beams are contradictions, never dynamic
  // points, whatever eq. (9) (paper) or the unknown class (class_conditional) finds of them over
  // a belief spread 1 m; and a localizer that sees through its map's walls does not count itself
  // found.
  Drive drive(11);
  LocalizerConfig config = TestConfig();
  config.measurement = GetParam();
  Localizer loc(config, TestRobot(), core::Rng(11));
  loc.SetMap(Rasterise(WithPhantomBox(drive.rects)));
  loc.Initialize(drive.X_WR, 1.0, 0.2);
  int crossing = 0, updates = 0, through_wall = 0, contradicted = 0, unreliable = 0;
  for (int tick = 0; updates < 40 && tick < 10000; ++tick) {
    loc.Predict(drive.Step());
    if (tick % 2 != 0) continue;
    const Pose2 X_WL = drive.X_WR * TestRobot().X_RL;
    const core::LaserScan scan = MakeScan(drive.rects, {}, X_WL, drive.rng);
    const LocalizerUpdate u = loc.Update(scan);
    if (!u.ran) continue;
    ++updates;
    through_wall += u.evidence.through_wall;
    const int evidence = u.evidence.explained + u.evidence.through_wall;
    if (u.evidence.through_wall * 3 >= evidence) {  // a third or more sees through the map
      ++contradicted;
      unreliable += u.lost;
    }
    for (std::size_t i = 0; i < u.beams.size(); ++i) {
      if (u.beams[i] == BeamUse::kUnused || !Crosses(scan, i, X_WL)) continue;
      ++crossing;
      EXPECT_NE(u.beams[i], BeamUse::kRejected) << "update " << updates << " beam " << i;
    }
  }
  EXPECT_GT(crossing, 200);
  EXPECT_GT(through_wall, 200);
  EXPECT_GT(contradicted, 10);
  EXPECT_GE(unreliable, 0.8 * contradicted);
}

INSTANTIATE_TEST_SUITE_P(BothModels, ThroughWall,
                         ::testing::Values(MeasurementModel::kPaper,
                                         MeasurementModel::kClassConditional),
                         [](const ::testing::TestParamInfo<MeasurementModel>& p) {
                           return p.param == MeasurementModel::kPaper ? "Paper"
                                                                         : "ClassConditional";
                         });

TEST(LocalizerEvidence, AMapThatExplainsTheScansHoldsItsReliability) {
  Drive drive(12);
  Localizer loc(TestConfig(), TestRobot(), core::Rng(12));
  loc.SetMap(drive.map);
  loc.Initialize(drive.X_WR, 0.1, 0.05);
  int unreliable = 0;
  for (int tick = 0; tick < 800; ++tick) {  // 20 m of driving, walkers in the way
    loc.Predict(drive.Step());
    if (tick % 2 != 0) continue;
    const Pose2 X_WL = drive.X_WR * TestRobot().X_RL;
    const LocalizerUpdate u = loc.Update(MakeScan(drive.rects, drive.Walkers(), X_WL, drive.rng));
    if (u.ran && u.reliability < TestConfig().reliability.threshold) ++unreliable;
  }
  EXPECT_EQ(unreliable, 0);
  EXPECT_FALSE(loc.lost());
  EXPECT_GT(loc.reliability(), 0.9);
}

TEST(LocalizerEvidence, ABeliefWithoutEvidenceSaysSoWithinFiveMetres) {
  // Every beam ends where the map never looked (its walls unobserved: the robot drove into a
  // room the teaching never saw), or no beam is valid at all: no evidence for the pose either
  // way. The localizer must not stay "found" on odometry.
  for (const bool blind : {false, true}) {
    Drive drive(13);
    Localizer loc(TestConfig(), TestRobot(), core::Rng(13));
    loc.SetMap(drive.map);
    loc.Initialize(drive.X_WR, 0.05, 0.02);
    for (int tick = 0; tick < 40; ++tick) {  // 1 m in the mapped room first
      loc.Predict(drive.Step());
      const Pose2 X_WL = drive.X_WR * TestRobot().X_RL;
      if (tick % 2 == 0) loc.Update(MakeScan(drive.rects, {}, X_WL, drive.rng));
    }
    ASSERT_FALSE(loc.lost());
    core::OccupancyGrid unseen = drive.map;  // the walls never observed
    for (int y = 0; y < unseen.height(); ++y) {
      for (int x = 0; x < unseen.width(); ++x) {
        if (unseen.Probability({x, y}) > 0.5) unseen.SetProbability({x, y}, 0.5);
      }
    }
    Localizer other(TestConfig(), TestRobot(), core::Rng(14));
    Localizer& l = blind ? loc : other;
    if (!blind) {
      other.SetMap(unseen);
      other.Initialize(loc.Estimate(), 0.05, 0.02);
    }
    double driven = 0.0;
    while (!l.lost() && driven < 20.0) {
      l.Predict(drive.Step());
      driven += 0.025;
      core::LaserScan scan = MakeScan(drive.rects, {}, drive.X_WR * TestRobot().X_RL, drive.rng);
      if (blind) {
        for (float& r : scan.ranges) r = std::numeric_limits<float>::infinity();
      }
      l.Update(scan);
    }
    EXPECT_TRUE(l.lost()) << (blind ? "no valid beam" : "unobserved walls");
    EXPECT_LE(driven, 5.0) << (blind ? "no valid beam" : "unobserved walls");
  }
}

}  // namespace
}  // namespace retrace::nav
