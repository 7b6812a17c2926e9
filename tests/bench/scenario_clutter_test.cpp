// A scenario's clutter block: drawn when the scenario loads, in the playback world only (objects
// as playback-only objects, people as standing pedestrian groups), the same for the same seed,
// off by default, bad values one error naming the key; generate-tour writes the block.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/worldgen/tour_folder.hpp"
#include "bench/engine/scenario.hpp"
#include "core/errors.hpp"
#include "io/config_override.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::bench::scenario_clutter_test {

using retrace::testing::kSource;

Scenario SmallWith(const std::vector<std::string>& overrides) {
  std::vector<io::ConfigOverride> parsed;
  for (const std::string& o : overrides) parsed.push_back(io::ParseOverride(o));
  return LoadScenario(kSource / "scenarios/small.yaml", parsed);
}

int Standing(const sim::World& world) {
  int n = 0;
  for (const auto& g : world.config.pedestrians) n += g.mode == sim::PedestrianMode::kStand;
  return n;
}

const std::vector<std::string> kCluttered = {"clutter.density=0.05",
                                             "clutter.standing_density=0.02", "clutter.band=2.0"};

TEST(ScenarioClutter, PlaybackWorldHoldsItTheTeachWorldDoesNot) {
  const Scenario s = SmallWith(kCluttered);
  ASSERT_FALSE(s.clutter.boxes.empty() && s.clutter.circles.empty());
  ASSERT_FALSE(s.clutter.standing.empty());
  EXPECT_EQ(s.playback_world.config.boxes.size(),
            s.teach_world.config.boxes.size() + s.clutter.boxes.size());
  EXPECT_EQ(s.playback_world.config.circles.size(),
            s.teach_world.config.circles.size() + s.clutter.circles.size());
  EXPECT_EQ(Standing(s.playback_world), static_cast<int>(s.clutter.standing.size()));
  EXPECT_EQ(Standing(s.teach_world), 0);
  EXPECT_EQ(s.playback_world.config.pedestrians.size(),
            s.teach_world.config.pedestrians.size() + s.clutter.standing.size());
  EXPECT_TRUE(s.playback_blocked.empty());  // the corridor keeps the route drivable
  // The config is kept as written: the objects are not copied into playback_only.
  EXPECT_TRUE(s.config.playback_only.empty());
}

TEST(ScenarioClutter, SameSeedSameClutterOtherSeedOther) {
  const Scenario a = SmallWith(kCluttered);
  const Scenario b = SmallWith(kCluttered);
  std::vector<std::string> other = kCluttered;
  other.push_back("seed=2");
  const Scenario c = SmallWith(other);
  EXPECT_EQ(a.clutter.standing, b.clutter.standing);
  ASSERT_EQ(a.clutter.boxes.size(), b.clutter.boxes.size());
  for (std::size_t i = 0; i < a.clutter.boxes.size(); ++i)
    EXPECT_EQ(a.clutter.boxes[i].center, b.clutter.boxes[i].center);
  EXPECT_NE(a.clutter.standing, c.clutter.standing);
}

TEST(ScenarioClutter, OffByDefault) {
  const Scenario s = SmallWith({});
  EXPECT_FALSE(s.config.clutter.enabled());
  EXPECT_TRUE(s.clutter.boxes.empty() && s.clutter.circles.empty() && s.clutter.standing.empty());
  EXPECT_EQ(s.playback_world.config.boxes.size(), s.teach_world.config.boxes.size());
  EXPECT_EQ(s.playback_world.config.pedestrians.size(), s.teach_world.config.pedestrians.size());
}

void ExpectError(const std::vector<std::string>& overrides, const std::string& key,
                 const std::string& text) {
  try {
    SmallWith(overrides);
    FAIL() << "no error for " << key;
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr(key));
    EXPECT_THAT(e.what(), ::testing::HasSubstr(text));
  }
}

TEST(ScenarioClutter, BadValuesAreOneErrorNamingTheKey) {
  ExpectError({"clutter.density=-0.1"}, "clutter.density", "must be in [0, 1]");
  ExpectError({"clutter.density=0.1", "clutter.band=0.5"}, "clutter.band",
              "wider than the corridor");
  ExpectError({"clutter.density=1"}, "clutter.density", "fit beside the route");
  ExpectError({"clutter.density=0.1", "clutter.kinds=[bin, bin]"}, "clutter.kinds", "twice");
}

TEST(ScenarioClutter, GenerateTourWritesTheBlock) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "retrace_scenario_clutter_test_tour";
  std::filesystem::remove_all(out);
  GenerateTourOptions options;
  options.out = out;
  options.seed = 3;
  options.overrides = {"length=300"};
  options.pedestrians = 0;
  options.clutter = {0.02, 0.005};
  GenerateTourFolder(options);
  const Scenario s = LoadScenario(out / "scenario.yaml");
  EXPECT_DOUBLE_EQ(s.config.clutter.density, 0.02);
  EXPECT_DOUBLE_EQ(s.config.clutter.standing_density, 0.005);
  EXPECT_FALSE(s.clutter.boxes.empty() && s.clutter.circles.empty());
  std::filesystem::remove_all(out);
}

}  // namespace retrace::bench::scenario_clutter_test
