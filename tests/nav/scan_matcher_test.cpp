// The teaching drive's scan matcher: it recovers a known pose offset against a map of scans
// taken at exact poses, keeps the prediction where the scan does not constrain the pose (along
// a featureless corridor, on an empty map, against another place), and validates its config.
// Scans are fake (tests/support/fake_scan.hpp): no simulator.

#include "nav/scan_matcher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/angle.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/fake_scan.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;
using core::Vec2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;
using testing::Segment;

// Faces of an L-shaped room with a pillar and an alcove: every direction is constrained.
// Coordinates lie off the 0.1 m cell borders, as in mapper_test.cpp.
std::vector<Segment> RoomFaces() {
  const std::vector<Vec2> outline = {{-4.03, -3.07}, {7.96, -3.07}, {7.96, 1.04},  {3.04, 1.04},
                                     {3.04, 5.04},   {-4.03, 5.04}, {-4.03, -3.07}};
  std::vector<Segment> faces;
  for (std::size_t i = 0; i + 1 < outline.size(); ++i)
    faces.push_back({outline[i], outline[i + 1]});
  const std::vector<Vec2> pillar = {{0.53, 0.04}, {1.54, 0.04}, {1.54, 0.86}, {0.53, 0.86}};
  for (std::size_t i = 0; i < pillar.size(); ++i)
    faces.push_back({pillar[i], pillar[(i + 1) % pillar.size()]});
  faces.push_back({{-2.03, 5.04}, {-2.03, 4.04}});  // a fin on the north wall
  return faces;
}

// Two parallel walls 2 m apart, 100 m long: nothing fixes the position along x.
std::vector<Segment> CorridorFaces() {
  return {{{-50.03, -1.03}, {50.03, -1.03}}, {{-50.03, 0.97}, {50.03, 0.97}}};
}

core::LaserScan ScanAt(const std::vector<Segment>& faces, const Pose2& X_MR) {
  return testing::FakeScan(testing::ScanSpec{}, X_MR, [&](const Vec2& o, const Vec2& d) {
    return testing::NearestSegment(o, d, faces);
  });
}

// A matcher whose map holds the scans of `faces` from exact keyframe poses (the LiDAR at the
// robot's centre).
ScanMatcher MatcherWithMap(const std::vector<Segment>& faces, const std::vector<Pose2>& poses) {
  ScanMatcher matcher(ScanMatcherConfig{}, RobotGeometry{});
  for (const Pose2& X : poses) matcher.AddScan(ScanAt(faces, X), X);
  return matcher;
}

TEST(ScanMatcher, RecoversAKnownOffsetInTranslationAndRotation) {
  const std::vector<Segment> faces = RoomFaces();
  ScanMatcher matcher =
      MatcherWithMap(faces, {{-1.0, -1.5, 0.0}, {1.0, -1.8, 0.3}, {5.0, -1.0, 2.0}});
  const Pose2 truth(2.2, -1.2, 0.4);
  const core::LaserScan scan = ScanAt(faces, truth);
  for (const Pose2& offset : {Pose2(0.12, -0.08, core::DegToRad(2.0)),
                              Pose2(-0.15, 0.1, core::DegToRad(-2.5)), Pose2(0.0, 0.0, 0.0)}) {
    SCOPED_TRACE(::testing::Message()
                 << "offset " << offset.x << " " << offset.y << " " << offset.theta);
    const Pose2 predicted(truth.x + offset.x, truth.y + offset.y, truth.theta + offset.theta);
    const ScanMatch m = matcher.Match(scan, predicted);
    EXPECT_EQ(m.verdict, MatchVerdict::kMatched);
    EXPECT_NEAR(m.X_MR.x, truth.x, 0.005);
    EXPECT_NEAR(m.X_MR.y, truth.y, 0.005);
    EXPECT_NEAR(core::AngleDiff(m.X_MR.theta, truth.theta), 0.0, core::DegToRad(0.1));
    EXPECT_GT(m.inliers, 0.9 * m.paired);
    EXPECT_GT(m.min_constraint, ScanMatcherConfig{}.min_constraint);
  }
}

TEST(ScanMatcher, RefusesToMoveAlongAFeaturelessCorridor) {
  const std::vector<Segment> faces = CorridorFaces();
  std::vector<Pose2> poses;
  for (double x = -10.0; x <= 10.0; x += 0.5) poses.emplace_back(x, 0.0, 0.0);
  ScanMatcher matcher = MatcherWithMap(faces, poses);
  const Pose2 truth(3.0, 0.1, 0.05);
  const Pose2 predicted(3.15, 0.1, 0.05);  // off along the corridor's axis only
  const ScanMatch m = matcher.Match(ScanAt(faces, truth), predicted);
  EXPECT_EQ(m.verdict, MatchVerdict::kDegenerate);
  EXPECT_EQ(m.X_MR, predicted);        // the caller keeps odometry
  EXPECT_GT(m.max_constraint, 100.0);  // across the corridor it is well constrained ...
  EXPECT_LT(m.min_constraint, 0.02 * m.max_constraint);  // ... along it hardly at all
}

TEST(ScanMatcher, AnEmptyMapOrAnEmptyScanKeepsThePrediction) {
  ScanMatcher matcher(ScanMatcherConfig{}, RobotGeometry{});
  const Pose2 predicted(0.3, -0.2, 0.1);
  const ScanMatch first = matcher.Match(ScanAt(RoomFaces(), predicted), predicted);
  EXPECT_EQ(first.verdict, MatchVerdict::kEmptyMap);
  EXPECT_EQ(first.X_MR, predicted);

  matcher.AddScan(ScanAt(RoomFaces(), {0.0, -1.5, 0.0}), {0.0, -1.5, 0.0});
  EXPECT_GT(matcher.size(), 100u);
  const ScanMatch none = matcher.Match(ScanAt({}, predicted), predicted);  // no returns at all
  EXPECT_EQ(none.verdict, MatchVerdict::kFewPoints);
  EXPECT_EQ(none.points, 0);
  EXPECT_EQ(none.X_MR, predicted);

  matcher.Clear();  // a new partial map
  EXPECT_EQ(matcher.size(), 0u);
  EXPECT_EQ(matcher.Match(ScanAt(RoomFaces(), predicted), predicted).verdict,
            MatchVerdict::kEmptyMap);
}

TEST(ScanMatcher, AScanOfAnotherPlaceIsAPoorFitNotAMatch) {
  // The map holds the room; the scan is of the corridor, predicted in the room's middle.
  ScanMatcher matcher = MatcherWithMap(RoomFaces(), {{-1.0, -1.5, 0.0}, {1.0, -1.8, 0.3}});
  const Pose2 predicted(-1.0, 2.0, 0.0);
  const ScanMatch m = matcher.Match(ScanAt(CorridorFaces(), Pose2(0.0, 0.0, 0.0)), predicted);
  EXPECT_FALSE(m.accepted());
  EXPECT_EQ(m.X_MR, predicted);
}

TEST(ScanMatcher, ConfigIsValidatedByKey) {
  EXPECT_EQ(ValidationErrorKey(ScanMatcherConfig{}), kValid);
  auto key = [](auto edit) {
    ScanMatcherConfig c;
    edit(c);
    return ValidationErrorKey(c);
  };
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.match_range = 0.0; }), "match_range");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.voxel_size = -0.1; }), "voxel_size");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.point_spacing = -0.1; }), "point_spacing");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.max_distance = 0.0; }), "max_distance");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.sigma = 0.0; }), "sigma");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.max_iterations = 0; }), "max_iterations");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.min_points = 2; }), "min_points");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.min_inlier_fraction = 1.5; }), "min_inlier_fraction");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.min_constraint = -1.0; }), "min_constraint");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.max_correction = 0.0; }), "max_correction");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.max_correction_deg = 90.0; }), "max_correction_deg");
  EXPECT_EQ(key([](ScanMatcherConfig& c) { c.match_range = std::nan(""); }), "match_range");
}

}  // namespace
}  // namespace retrace::nav
