#include "bench/sweep/sweep_plan.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

using retrace::testing::kSource;
const std::filesystem::path kFixture =
    std::filesystem::path(RETRACE_SOURCE_DIR) / "tests/data/sweep_small.yaml";

using SweepPlanTest = retrace::testing::TempDirTest;

TEST(SweepShard, ParsesIOfN) {
  const SweepShard shard = ParseShard("2/3");
  EXPECT_EQ(shard.index, 2);
  EXPECT_EQ(shard.count, 3);
  EXPECT_EQ(shard.ToString(), "2/3");
  EXPECT_TRUE(shard.Contains(1));
  EXPECT_TRUE(shard.Contains(4));
  EXPECT_FALSE(shard.Contains(2));
  for (const char* bad : {"0/3", "4/3", "1/0", "3", "a/b", "1/3x", "-1/3", "", "1/", "/3"}) {
    EXPECT_THROW(ParseShard(bad), core::ConfigError) << bad;
  }
}

TEST(SweepShard, ShardsPartitionTheCases) {
  for (int count : {1, 2, 3, 7}) {
    for (std::size_t total : {0u, 1u, 5u, 8u, 23u}) {
      std::size_t sum = 0;
      for (int index = 1; index <= count; ++index) {
        const SweepShard shard{index, count};
        std::size_t members = 0;
        for (std::size_t id = 0; id < total; ++id) members += shard.Contains(id) ? 1 : 0;
        EXPECT_EQ(shard.CaseCount(total), members);
        sum += members;
      }
      EXPECT_EQ(sum, total);
    }
  }
}

TEST(SweepPlan, GivesEachRepeatItsSeedAndOnePlaybackRun) {
  const SweepPlan plan = PlanSweep(LoadSweepSpec(kFixture), 2);
  ASSERT_EQ(plan.spec.case_count(), 8u);
  ASSERT_EQ(plan.base_seeds.size(), 4u);
  for (std::size_t id = 0; id < 8; ++id) {
    EXPECT_EQ(plan.combination(id), id / 2);
    EXPECT_EQ(plan.seed(id), 1u + id % 2);  // scenarios/small.yaml has seed 1
  }
  const auto overrides = plan.CaseOverrides(5);
  ASSERT_GE(overrides.size(), 2u);
  EXPECT_EQ(overrides[overrides.size() - 2].key_path, "seed");
  EXPECT_EQ(overrides[overrides.size() - 2].value, "2");
  EXPECT_EQ(overrides.back().key_path, "playback.repeats");
  EXPECT_EQ(overrides.back().value, "1");
}

TEST(SweepPlan, IdentityIsStableAndChangesWithTheCases) {
  const SweepPlan a = PlanSweep(LoadSweepSpec(kFixture), 1);
  const SweepPlan b = PlanSweep(LoadSweepSpec(kFixture), 2);
  EXPECT_EQ(a.identity.size(), 16u);
  EXPECT_EQ(a.identity, b.identity);
  const SweepPlan c = PlanSweep(LoadSweepSpec(kFixture, {{"limits.stall_time", "30"}}), 2);
  EXPECT_NE(a.identity, c.identity);
  const SweepPlan d = PlanSweep(LoadSweepSpec(kFixture, {{"seed", "5"}}), 2);
  EXPECT_NE(a.identity, d.identity);
  EXPECT_EQ(d.seed(1), 6u);
}

TEST_F(SweepPlanTest, ABadKeyIsReportedAtItsLineInTheSweepFile) {
  const std::string scenario = (kSource / "scenarios/small.yaml").string();
  const auto file =
      tmp_.Write("s.yaml", "scenario: " + scenario +
                               "\nrepeats: 2\ngrid:\n  nav.localizer.partcles: [100, 200]\n");
  try {
    PlanSweep(LoadSweepSpec(file), 2);
    FAIL();
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(),
                HasSubstr(file.string() +
                          ":4: nav.localizer.partcles: unknown key; did you mean 'particles'?"));
    EXPECT_THAT(e.what(), HasSubstr("scenario " + scenario));
    EXPECT_THAT(e.what(), Not(HasSubstr("--set")));  // the key came from the sweep file
  }
}

TEST_F(SweepPlanTest, ABadValueIsReportedAtItsLine) {
  const std::string scenario = (kSource / "scenarios/small.yaml").string();
  const auto file =
      tmp_.Write("s.yaml", "scenario: " + scenario + "\nset: {limits.stall_time: -1}\n");
  try {
    PlanSweep(LoadSweepSpec(file), 1);
    FAIL();
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string() + ":2: limits.stall_time: must be > 0"));
  }
}

TEST_F(SweepPlanTest, ACombinationThatCannotLoadIsNamed) {
  const std::string scenario = (kSource / "scenarios/small.yaml").string();
  const auto file =
      tmp_.Write("s.yaml", "scenario: " + scenario + "\ngrid: {sim.robot.radius: [0.3, 2.5]}\n");
  try {
    PlanSweep(LoadSweepSpec(file), 2);
    FAIL();
  } catch (const core::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("combination 1"));
    EXPECT_THAT(e.what(), HasSubstr("sim.robot.radius=2.5"));
    EXPECT_THAT(e.what(), HasSubstr("not drivable"));
  }
}

// Every shipped sweep file (bench/sweeps/) loads, and every one of its combinations loads its
// scenario.
TEST(SweepPlan, ShippedSweepsAreValid) {
  int count = 0;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "bench/sweeps")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  }
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    const SweepPlan plan = PlanSweep(LoadSweepSpec(file), 2);
    EXPECT_GE(plan.spec.combinations.size(), 2u);
    EXPECT_LE(plan.spec.case_count(), 32u);  // minutes on 2 cores, not hours
    EXPECT_EQ(plan.spec.name, file.stem().string());
    ++count;
  }
  EXPECT_GE(count, 4);
}

}  // namespace
}  // namespace retrace::bench
