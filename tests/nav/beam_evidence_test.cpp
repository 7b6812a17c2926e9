#include "nav/beam_evidence.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "core/angle.hpp"

namespace retrace::nav {
namespace {

// A 10 m x 10 m grid: a wall along x = 5 (cells 100 and 101 of 0.05 m), free cells up to it,
// the rest (x > 5.1) never observed.
core::OccupancyGrid HalfSeen() {
  core::OccupancyGrid grid(200, 200, 0.05, core::Vec2(0.0, 0.0));
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 102; ++x) grid.SetProbability({x, y}, x >= 100 ? 0.95 : 0.05);
  }
  return grid;
}

TEST(BeamEvidence, SortsBeamsByWhatTheMapSaysOfThem) {
  const core::OccupancyGrid grid = HalfSeen();
  const LikelihoodField field(grid, LikelihoodFieldConfig{}, 30.0);
  const GridRayCaster caster(field);
  const core::Pose2 X_ML(1.0, 5.0, 0.0);
  // Along +x: the wall 4 m ahead (explained), a person 2 m ahead (shorter), through the wall
  // to 6 m (a contradiction: no person makes a beam longer). Along +y, 1 m past the grid's
  // known part is impossible here; a beam to a point outside the grid is unknown.
  const std::vector<double> xs{4.0, 2.0, 6.5, 3.0};
  const std::vector<double> ys{0.0, 0.0, 0.0, 8.0};
  const BeamEvidence e = ClassifyBeams(field, caster, X_ML, xs, ys);
  EXPECT_EQ(e.explained, 1);
  EXPECT_EQ(e.shorter, 1);
  EXPECT_EQ(e.through_wall, 1);
  EXPECT_EQ(e.unknown, 1);
  EXPECT_DOUBLE_EQ(e.Coverage(), 0.75);
  EXPECT_DOUBLE_EQ(e.Contradicted(), 0.25);
  // Coverage by the grid alone: the end point beyond the wall (6.5 m ahead, x = 7.5) and the
  // one outside the grid were never observed.
  EXPECT_DOUBLE_EQ(GridCoverage(grid, X_ML, xs, ys), 0.5);
}

TEST(BeamEvidence, ARayThatGrazesAWallDoesNotContradict) {
  // A beam that meets the wall at x = 5 at 10° from its surface and ends 0.6 m beyond its first
  // wall cell clips the wall's corner cells (a pose a few centimetres off does that along any
  // corridor): it says nothing of the pose. The same beam meeting the wall squarely sees through.
  const core::OccupancyGrid grid = HalfSeen();
  const LikelihoodField field(grid, LikelihoodFieldConfig{}, 30.0);
  const GridRayCaster caster(field);
  const double a = core::DegToRad(10.0);
  const core::Pose2 grazing(4.8, 1.0, 0.5 * core::kPi - a);  // 10° off the wall's direction
  const std::vector<double> xs{1.0 / std::sin(a) + 3.5}, ys{0.0};
  EXPECT_EQ(ClassifyBeams(field, caster, grazing, xs, ys).through_wall, 0);
  const core::Pose2 square(4.0, 5.0, 0.0);
  const std::vector<double> through{2.0}, zero{0.0};
  EXPECT_EQ(ClassifyBeams(field, caster, square, through, zero).through_wall, 1);
}

}  // namespace
}  // namespace retrace::nav
