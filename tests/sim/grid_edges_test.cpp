#include "sim/grid_edges.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.hpp"
#include "sim/ray_caster.hpp"

namespace retrace::sim {
namespace {

OccupancyMask MaskFrom(const std::vector<std::string>& rows_top_down, double res = 0.1) {
  OccupancyMask m;
  m.height = static_cast<int>(rows_top_down.size());
  m.width = static_cast<int>(rows_top_down[0].size());
  m.resolution = res;
  m.origin = Vec2(1.0, -2.0);
  m.occupied.resize(static_cast<std::size_t>(m.width * m.height));
  for (int r = 0; r < m.height; ++r) {
    for (int x = 0; x < m.width; ++x) {
      const int y = m.height - 1 - r;
      m.occupied[static_cast<std::size_t>(y * m.width + x)] = rows_top_down[r][x] == '#';
    }
  }
  return m;
}

double TotalLength(const std::vector<Segment>& edges) {
  double s = 0;
  for (const auto& e : edges) s += (e.b - e.a).norm();
  return s;
}

TEST(GridEdges, ARectangleOfCellsBecomesFourEdges) {
  const auto edges = MergedBoundaryEdges(MaskFrom({"......", ".####.", ".####.", "......"}));
  ASSERT_EQ(edges.size(), 4u);
  EXPECT_NEAR(TotalLength(edges), 2 * (0.4 + 0.2), 1e-12);
}

TEST(GridEdges, AnLShapeBecomesSixEdgesAndTouchesTheGridBorder) {
  const auto edges = MergedBoundaryEdges(MaskFrom({"#..", "#..", "###"}));
  EXPECT_EQ(edges.size(), 6u);
  EXPECT_NEAR(TotalLength(edges), 1.2, 1e-12);
}

TEST(GridEdges, EdgesSeparateSolidFromFreeEverywhere) {
  // A random map: every boundary edge has a solid cell on exactly one side at its midpoint.
  core::Rng rng(3);
  std::vector<std::string> rows(40, std::string(60, '.'));
  for (auto& r : rows)
    for (auto& c : r) c = rng.Bernoulli(0.3) ? '#' : '.';
  const OccupancyMask mask = MaskFrom(rows);
  const auto edges = MergedBoundaryEdges(mask);
  std::size_t faces = 0;
  for (int y = 0; y <= mask.height; ++y) {
    for (int x = 0; x <= mask.width; ++x) {
      auto s = [&](int cx, int cy) {
        return cx >= 0 && cy >= 0 && cx < mask.width && cy < mask.height &&
               mask.occupied[static_cast<std::size_t>(cy * mask.width + cx)];
      };
      if (x < mask.width) faces += s(x, y - 1) != s(x, y);
      if (y < mask.height) faces += s(x - 1, y) != s(x, y);
    }
  }
  EXPECT_NEAR(TotalLength(edges), faces * mask.resolution, 1e-9);
  EXPECT_LT(edges.size(), faces);
  for (const auto& e : edges) {
    const Vec2 mid = 0.5 * (e.a + e.b);
    const Vec2 d = (e.b - e.a).normalized();
    const Vec2 n(-d.y(), d.x());
    EXPECT_NE(mask.IsOccupied(mid + 0.01 * n), mask.IsOccupied(mid - 0.01 * n));
  }
}

}  // namespace
}  // namespace retrace::sim

namespace retrace::sim::unknown_fill_test {

// An all-unknown map filled at free path l: rays from its centre in uniformly random directions
// travel l on average before they meet a solid cell (the fill's probability per cell is derived
// for exactly that), and known free and occupied cells are left as they are.
TEST(UnknownFill, RaysTravelTheFreePathOnAverage) {
  constexpr double kFreePath = 1.5;
  const core::OccupancyGrid grid(1000, 1000, 0.05, Vec2(-25.0, -25.0));  // all unknown
  OccupancyMask mask = OccupiedMask(grid, 0.65);
  FillUnknownCells(grid, 0.65, kFreePath, core::Rng(4), &mask);
  StaticGeometry geometry;
  geometry.AddEdges(MergedBoundaryEdges(mask), mask);
  const RayCaster caster(geometry);
  core::Rng rng(5);
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec2 origin(rng.Uniform(-2.0, 2.0), rng.Uniform(-2.0, 2.0));
    if (geometry.IsInside(origin)) continue;
    const double a = rng.Uniform(0.0, 2.0 * M_PI);
    const double t = caster.Cast(origin, Vec2(std::cos(a), std::sin(a)), 22.0);
    ASSERT_LT(t, 22.0);
    sum += t;
    ++n;
  }
  // The distance from a uniform point to the first solid cell's face, exponential with mean l
  // measured from the start of the cell the point is in: half a cell less on average.
  EXPECT_NEAR(sum / n, kFreePath - 0.5 * 0.05, 0.06);
}

TEST(UnknownFill, KnownCellsStayAsTheyAre) {
  core::OccupancyGrid grid(40, 40, 0.1, Vec2(0.0, 0.0));
  for (int x = 0; x < 40; ++x) {
    grid.SetProbability({x, 10}, 0.05);  // known free
    grid.SetProbability({x, 20}, 0.95);  // occupied
  }
  OccupancyMask mask = OccupiedMask(grid, 0.65);
  FillUnknownCells(grid, 0.65, 1e-4, core::Rng(1), &mask);  // every unknown cell solid
  int unknown_solid = 0;
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) {
      const bool solid = mask.occupied[static_cast<std::size_t>(y * 40 + x)] != 0;
      if (y == 10) {
        EXPECT_FALSE(solid);
      } else if (y == 20) {
        EXPECT_TRUE(solid);
      }
      if (y != 10 && y != 20 && solid) ++unknown_solid;
    }
  }
  EXPECT_EQ(unknown_solid, 38 * 40);
}

}  // namespace retrace::sim::unknown_fill_test
