// The one projection onto a path within a window of arc length (core/path_projection.hpp) that
// the teacher, the path follower, the scripted events, the switch points, the metrics and the
// local truth use.

#include "core/path_projection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace retrace::core {
namespace {

// Twice round a 50 m square, counter-clockwise from the origin: every place is passed twice,
// 200 m of arc length apart.
std::vector<Vec2> DoubleSquare() {
  return {{0, 0}, {50, 0}, {50, 50}, {0, 50}, {0, 0}, {50, 0}, {50, 50}, {0, 50}, {0, 0}};
}

PathProjection Project(const std::vector<Vec2>& path, const Vec2& p, double lo, double hi) {
  const std::vector<double> arc = CumulativeArcLength(path);
  return ProjectOntoPath(path, arc, p, lo, hi);
}

TEST(CumulativeArcLength, SumsTheSegments) {
  EXPECT_EQ(CumulativeArcLength(DoubleSquare()),
            (std::vector<double>{0, 50, 100, 150, 200, 250, 300, 350, 400}));
  EXPECT_EQ(CumulativeArcLength(std::vector<Vec2>{}), std::vector<double>{});
}

TEST(ProjectOntoPath, FindsTheClosestPointOnTheSegmentsInsideTheWindowOnly) {
  const auto path = DoubleSquare();
  // Just below the first leg: the first pass, or the second one when the window says so.
  PathProjection p = Project(path, {10, -1}, 0, 100);
  EXPECT_NEAR(p.s, 10.0, 1e-12);
  EXPECT_NEAR(p.distance, 1.0, 1e-12);
  EXPECT_EQ(p.segment, 0u);
  p = Project(path, {10, -1}, 100, 400);
  EXPECT_NEAR(p.s, 210.0, 1e-12);
  EXPECT_EQ(p.segment, 4u);
  // Between segment ends: the projection lies inside a segment, not at a vertex.
  p = Project(path, {51, 20}, 0, 400);
  EXPECT_NEAR(p.s, 70.0, 1e-12);
  EXPECT_NEAR(p.distance, 1.0, 1e-12);
}

TEST(ProjectOntoPath, ClampsToTheWindowAndKeepsTheEarlierPointOnTies) {
  const auto path = DoubleSquare();
  // The closest point of the whole path (s = 10 or 210) lies outside [20, 30]: the window's
  // nearest end.
  PathProjection p = Project(path, {10, 0}, 20, 30);
  EXPECT_NEAR(p.s, 20.0, 1e-12);
  EXPECT_NEAR(p.distance, 10.0, 1e-12);
  // Equally close to both passes: the earlier one.
  p = Project(path, {10, 0}, 0, 400);
  EXPECT_NEAR(p.s, 10.0, 1e-12);
  // A window past the end ends at the last point.
  p = Project(path, {0, 0}, 390, 1000);
  EXPECT_NEAR(p.s, 400.0, 1e-12);
}

TEST(ProjectOntoPath, SkipsZeroLengthSegmentsAndNeedsTwoPoints) {
  const std::vector<Vec2> stutter{{0, 0}, {0, 0}, {10, 0}, {10, 0}, {10, 10}};
  const PathProjection p = Project(stutter, {10.5, 5}, 0, 100);
  EXPECT_EQ(p.segment, 3u);
  EXPECT_NEAR(p.s, 15.0, 1e-12);
  for (const std::vector<Vec2>& degenerate :
       {std::vector<Vec2>{}, std::vector<Vec2>{{1, 1}}, std::vector<Vec2>{{1, 1}, {1, 1}}}) {
    const PathProjection none = Project(degenerate, {0, 0}, 3, 5);
    EXPECT_TRUE(std::isinf(none.distance));
    EXPECT_EQ(none.s, 3.0);
  }
}

TEST(ForwardProgress, MovesOnlyForwardAndNoFurtherThanTheWindow) {
  const auto path = DoubleSquare();
  const std::vector<double> arc = CumulativeArcLength(path);
  ForwardProgress progress;
  EXPECT_EQ(progress.value(), 0.0);
  EXPECT_NEAR(progress.Advance(path, arc, {10, 1}, 5.0), 5.0, 1e-12);  // capped at s_hi
  EXPECT_NEAR(progress.Advance(path, arc, {10, 1}, 20.0), 10.0, 1e-12);
  EXPECT_NEAR(progress.Advance(path, arc, {2, 0}, 20.0), 10.0, 1e-12);  // never back
  // Near the start again, after a lap: the second pass, never the first.
  progress.MoveTo(190.0);
  EXPECT_NEAR(progress.Advance(path, arc, {0, -0.5}, 215.0), 200.0, 1e-12);
  EXPECT_NEAR(progress.Advance(path, arc, {10, -0.5}, 215.0), 210.0, 1e-12);
  progress.MoveTo(100.0);  // a stop behind the progress is no step back
  EXPECT_NEAR(progress.value(), 210.0, 1e-12);
  EXPECT_NEAR(progress.Advance(path, arc, {10, -0.5}, 100.0), 210.0, 1e-12);  // s_hi behind
}

}  // namespace
}  // namespace retrace::core
