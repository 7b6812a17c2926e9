#include "core/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include "core/errors.hpp"

namespace retrace::core {
namespace {

TEST(OccupancyGrid, WorldToCellAndBackAreConsistent) {
  const OccupancyGrid grid(100, 50, 0.1, Vec2(-5.0, 2.0));
  EXPECT_EQ(grid.WorldToCell({-5.0, 2.0}), (CellIndex{0, 0}));
  EXPECT_EQ(grid.WorldToCell({-4.95, 2.05}), (CellIndex{0, 0}));
  EXPECT_EQ(grid.WorldToCell({-5.01, 2.0}), (CellIndex{-1, 0}));
  EXPECT_EQ(grid.WorldToCell({4.99, 6.99}), (CellIndex{99, 49}));
  const Vec2 c = grid.CellToWorld({10, 20});
  EXPECT_NEAR(c.x(), -3.95, 1e-12);
  EXPECT_NEAR(c.y(), 4.05, 1e-12);
  EXPECT_EQ(grid.WorldToCell(c), (CellIndex{10, 20}));
  EXPECT_FALSE(grid.Contains({100, 0}));
  EXPECT_TRUE(grid.Contains({99, 49}));
}

TEST(OccupancyGrid, StartsUnknownAndStoresLogOdds) {
  OccupancyGrid grid(4, 4, 0.5, Vec2::Zero());
  EXPECT_DOUBLE_EQ(grid.Probability({1, 1}), 0.5);
  grid.SetLogOdds({1, 1}, 3.5f);
  EXPECT_FLOAT_EQ(grid.LogOdds({1, 1}), 3.5f);
  grid.SetProbability({2, 2}, 0.2);
  EXPECT_NEAR(grid.Probability({2, 2}), 0.2, 1e-6);
}

TEST(OccupancyGrid, GrowKeepsContentAtTheSameWorldPosition) {
  OccupancyGrid grid(10, 10, 0.1, Vec2::Zero());
  const Vec2 p(0.55, 0.35);
  grid.SetLogOdds(grid.WorldToCell(p), 2.0f);
  grid.GrowToInclude({-3.0, 5.0}, 2);
  EXPECT_TRUE(grid.Contains(grid.WorldToCell({-3.0, 5.0})));
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.WorldToCell(p)), 2.0f);
  const CellIndex c = grid.WorldToCell({-3.0, 5.0});
  EXPECT_GE(c.x, 2);
  EXPECT_LE(c.y, grid.height() - 3);
  int marked = 0;
  for (float l : grid.log_odds()) marked += l != 0.0f;
  EXPECT_EQ(marked, 1);
}

TEST(OccupancyGrid, RejectsBadResolution) {
  EXPECT_THROW(OccupancyGrid(1, 1, 0.0, Vec2::Zero()), ConfigError);
  EXPECT_THROW(OccupancyGrid(1, 1, -0.1, Vec2::Zero()), ConfigError);
}

}  // namespace
}  // namespace retrace::core
