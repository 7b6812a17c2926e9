#include "sim/route_check.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "io/route_file.hpp"
#include "sim/world_file.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::kSource;

TEST(RouteCheck, ShippedOfficeRouteIsDrivable) {
  const World world = LoadWorld(kSource / "worlds/office.yaml");
  EXPECT_NO_THROW(CheckRouteIsDrivable(world.geometry,
                                       io::ReadRouteFile(kSource / "worlds/routes/office_loop.txt"), 0.3));
}

TEST(RouteCheck, ARouteThroughABuildingIsRejectedWithItsLocation) {
  StaticGeometry g;
  g.AddPolygon({{4, -1}, {6, -1}, {6, 1}, {4, 1}});
  try {
    CheckRouteIsDrivable(g, {{0, 0}, {2, 0}, {10, 0}}, 0.3);
    FAIL() << "expected a WorldError";
  } catch (const core::WorldError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("route segment 1"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("(3.7"));
  }
  // Passing 0.2 m from a wall is too close for a 0.3 m robot, 0.4 m is fine.
  EXPECT_THROW(CheckRouteIsDrivable(g, {{0, 1.2}, {10, 1.2}}, 0.3), core::WorldError);
  EXPECT_NO_THROW(CheckRouteIsDrivable(g, {{0, 1.4}, {10, 1.4}}, 0.3));
  EXPECT_THROW(CheckRouteIsDrivable(g, {{0, 1.4}}, 0.3), core::WorldError);
}

}  // namespace
}  // namespace retrace::sim
