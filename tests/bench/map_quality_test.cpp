// Map quality against ground truth: the best rigid alignment, the distortion left after it,
// and the agreement of a map's occupied cells with the world's surfaces.

#include "bench/metrics/map_quality.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/occupancy_grid.hpp"

namespace retrace::bench {
namespace {

using core::Pose2;
using core::Vec2;

TEST(MapQuality, AlignPointsRecoversARigidTransformExactly) {
  const Pose2 T(3.0, -1.5, 0.7);
  std::vector<Vec2> a;
  std::vector<Vec2> b;
  for (int i = 0; i < 20; ++i) {
    a.emplace_back(0.3 * i, std::sin(0.5 * i));
    b.push_back(T * a.back());
  }
  const Pose2 found = AlignPoints(a, b);
  EXPECT_NEAR(found.x, T.x, 1e-9);
  EXPECT_NEAR(found.y, T.y, 1e-9);
  EXPECT_NEAR(found.theta, T.theta, 1e-9);
  EXPECT_EQ(AlignPoints({}, {}), Pose2::Identity());
  // One point: a translation only.
  const Pose2 one = AlignPoints({Vec2(1.0, 1.0)}, {Vec2(2.0, 3.0)});
  EXPECT_EQ(one, Pose2(1.0, 2.0, 0.0));
}

// A teach of one map along the wall y = 0.97 (solid below y = 1.0 … 1.2 in W), its trace in a
// map frame rotated and shifted from W, optionally bent by a drift growing along the way; its
// grid holds the wall where the (unbent) map frame puts it, shifted by `grid_shift` m.
ModeTeach WallTeach(const Pose2& X_WM, double drift_per_m, double grid_shift) {
  ModeTeach teach;
  TeachMapTrace trace;
  for (int i = 0; i <= 100; ++i) {
    const double x = 0.1 * i;
    const Pose2 X_WR(x, 0.0, 0.0);
    const Pose2 X_MR = X_WM.Inverse() * X_WR;
    trace.time.push_back(i);
    trace.X_WR.push_back(X_WR);
    trace.X_MR.emplace_back(X_MR.x, X_MR.y + drift_per_m * x * x, X_MR.theta);
  }
  teach.trace.maps.push_back(trace);
  nav::PartialMap map;
  map.grid = core::OccupancyGrid(300, 300, 0.1, Vec2(-15.0, -15.0));
  for (int i = 0; i <= 100; ++i) {
    const Vec2 p_W(0.1 * i + 0.05, 1.05 + grid_shift);
    map.grid.SetProbability(map.grid.WorldToCell(X_WM.Inverse() * p_W), 0.95);
  }
  teach.bundle.maps.push_back(map);
  return teach;
}

sim::StaticGeometry Wall() {
  sim::StaticGeometry world;
  world.AddPolygon({{-1.0, 1.0}, {12.0, 1.0}, {12.0, 1.2}, {-1.0, 1.2}});
  return world;
}

TEST(MapQuality, ARigidlyPlacedMapHasNoDistortionAndFullAgreement) {
  const MapQualityStats q =
      ComputeMapQuality(WallTeach(Pose2(0.0, 0.0, 0.0), 0.0, 0.0), Wall(), 0.65);
  ASSERT_EQ(q.maps.size(), 1u);
  EXPECT_NEAR(q.distortion_rms_m, 0.0, 1e-9);
  EXPECT_EQ(q.maps[0].samples, 101);
  EXPECT_GT(q.maps[0].occupied_cells, 90);
  EXPECT_DOUBLE_EQ(q.agreement, 1.0);
}

TEST(MapQuality, DriftIsDistortionButARigidOffsetIsNot) {
  const Pose2 X_WM(0.5, -0.2, 0.3);  // the map frame anywhere: alignment takes it out
  const MapQualityStats rigid = ComputeMapQuality(WallTeach(X_WM, 0.0, 0.0), Wall(), 0.65);
  EXPECT_NEAR(rigid.distortion_rms_m, 0.0, 1e-9);
  EXPECT_GT(rigid.agreement, 0.9);  // the cells fall on the wall in W again
  const MapQualityStats bent = ComputeMapQuality(WallTeach(X_WM, 0.01, 0.0), Wall(), 0.65);
  EXPECT_GT(bent.distortion_rms_m, 0.05);  // 1 m of drift at the end: a bow no rotation removes
  EXPECT_LT(bent.distortion_rms_m, 0.5);
  EXPECT_DOUBLE_EQ(bent.distortion_max_m, bent.maps[0].distortion_m);
}

TEST(MapQuality, CellsAwayFromEverySurfaceDisagree) {
  const MapQualityStats q = ComputeMapQuality(WallTeach(Pose2(), 0.0, 0.6), Wall(), 0.65);
  EXPECT_DOUBLE_EQ(q.agreement, 0.0);  // 0.45 m beyond the wall, in free space
  ModeTeach empty;
  EXPECT_TRUE(std::isnan(ComputeMapQuality(empty, Wall(), 0.65).agreement));
}

}  // namespace
}  // namespace retrace::bench
