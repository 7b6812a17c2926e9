#include "sim/world_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "sim/pedestrians.hpp"
#include "sim/physics_world.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::sim {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

using retrace::testing::kSource;

class WorldFileTest : public ::testing::Test {
 protected:
  template <class E>
  std::string ErrorOf(const std::string& text) {
    try {
      LoadWorld(tmp_.Write("w.yaml", text));
    } catch (const E& e) {
      return e.what();
    }
    return "no error";
  }
  retrace::testing::TempDir tmp_;
};

TEST_F(WorldFileTest, EveryShippedWorldLoadsAndHasGeometry) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "worlds")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const World world = LoadWorld(entry.path());
    EXPECT_FALSE(world.geometry.empty());
    EXPECT_FALSE(world.config.name.empty());
    // Its pedestrian groups can be placed, and their loops are walkable.
    PhysicsWorld physics(world.geometry);
    const Pedestrians crowd(world.config.pedestrians, CrowdConfig{}, world.geometry, core::Rng(1),
                            {}, physics);
    int expected = 0;
    for (const auto& g : world.config.pedestrians) expected += g.count;
    EXPECT_EQ(crowd.size(), expected);
    ++n;
  }
  EXPECT_GE(n, 2);
}

TEST_F(WorldFileTest, BuildsSolidsFromBoxesWallsPolygonsAndCircles) {
  const World w = LoadWorld(tmp_.Write("w.yaml",
                                       "name: t\n"
                                       "boxes: [{center: [5, 5], size: [2, 1], yaw: 1.5707963267948966}]\n"
                                       "walls: [{points: [[0, 0], [10, 0], [10, 10]], thickness: 0.2}]\n"
                                       "polygons: [{points: [[20, 0], [22, 0], [21, 2]]}]\n"
                                       "circles: [{center: [-3, 0], radius: 0.5}]\n"));
  const auto& g = w.geometry;
  EXPECT_EQ(g.polygons().size(), 4u);  // box + two wall pieces + triangle
  EXPECT_EQ(g.circles().size(), 1u);
  EXPECT_TRUE(g.IsInside({5.0, 5.9}));   // rotated box: long side along y
  EXPECT_FALSE(g.IsInside({5.9, 5.0}));
  EXPECT_TRUE(g.IsInside({5.0, 0.05}));
  EXPECT_TRUE(g.IsInside({10.05, 0.05}));  // the corner is closed
  EXPECT_TRUE(g.IsInside({10.0, 5.0}));
  EXPECT_TRUE(g.IsInside({21.0, 1.0}));
  EXPECT_TRUE(g.IsInside({-3.2, 0.2}));
  EXPECT_FALSE(g.IsInside({5.0, 3.0}));
  EXPECT_NEAR(g.Clearance({5.0, 3.0}), 1.0, 1e-12);
}

TEST_F(WorldFileTest, BadInputGivesOneClearMessage) {
  EXPECT_THROW(LoadWorld(tmp_.path() / "missing.yaml"), core::IoError);
  EXPECT_THAT(ErrorOf<core::ConfigError>("name: x\nboxes: [{center: [1, 2}\n"), HasSubstr("invalid YAML"));
  EXPECT_THAT(ErrorOf<core::ConfigError>("name: x\ncircles:\n  - {center: [0, 0], radius: 1}\n  - {centre: [1, 1]}\n"),
              AllOf(HasSubstr("w.yaml:4:"), HasSubstr("circles[1].centre"), HasSubstr("did you mean 'center'")));
  EXPECT_THAT(ErrorOf<core::ConfigError>("name: x\ncircles: [{center: [0, .nan], radius: 1}]\n"),
              AllOf(HasSubstr("w.yaml:2:"), HasSubstr("circles[0].center[1]"), HasSubstr("finite")));
  EXPECT_THAT(ErrorOf<core::ConfigError>("name: x\ncircles: [{center: [0, 0], radius: -1}]\n"),
              AllOf(HasSubstr("circles[0].radius"), HasSubstr("> 0")));
  EXPECT_THAT(ErrorOf<core::ConfigError>("name: x\nwalls: [{points: [[0, 0]]}]\n"),
              HasSubstr("at least 2 points"));
  EXPECT_THAT(ErrorOf<core::WorldError>("name: empty\n"), HasSubstr("no static geometry"));
  EXPECT_THAT(ErrorOf<core::WorldError>("name: empty\nboxes: []\n"), HasSubstr("no static geometry"));
}

TEST_F(WorldFileTest, ImportsARosMapAsMergedEdges) {
  // A 20 x 10 cell map, 0.1 m cells, with a 1-cell border wall and a 2x2 block.
  std::string pgm = "P5\n20 10\n255\n";
  for (int r = 0; r < 10; ++r) {
    for (int c = 0; c < 20; ++c) {
      const bool wall = r == 0 || r == 9 || c == 0 || c == 19 || (r >= 4 && r <= 5 && c >= 8 && c <= 9);
      pgm.push_back(static_cast<char>(wall ? 0 : 254));
    }
  }
  tmp_.Write("m.pgm", pgm);
  tmp_.Write("m.yaml", "image: m.pgm\nresolution: 0.1\norigin: [-1.0, 2.0, 0.0]\nnegate: 0\n"
                       "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const World w = LoadWorld(tmp_.Write("w.yaml", "name: imported\nmaps: [{file: m.yaml}]\n"));
  // Outer border: 4 outside + 4 inside faces; the block: 4.
  EXPECT_EQ(w.geometry.segments().size(), 12u);
  EXPECT_TRUE(w.geometry.IsInside({-0.95, 2.05}));
  EXPECT_FALSE(w.geometry.IsInside({-0.5, 2.5}));
  EXPECT_TRUE(w.geometry.IsInside({-1.0 + 0.85, 2.0 + 0.45}));
}

}  // namespace
}  // namespace retrace::sim
