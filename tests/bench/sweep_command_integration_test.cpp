// `retrace sweep` in process (bench::RunSweep), on shards of the tiny test sweep
// (tests/data/sweep_small.yaml, 8 cases of well under a second) so that each test runs only a
// few cases. The command line tests (tests/cli/sweep_*_test.sh) cover kill -9, whole sweeps and
// `retrace merge`.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "bench/sweep/sweep_run.hpp"
#include "core/errors.hpp"
#include "io/json_writer.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const std::filesystem::path kFixture =
    std::filesystem::path(RETRACE_SOURCE_DIR) / "tests/data/sweep_small.yaml";

using SweepCommandTest = retrace::testing::TempDirTest;

SweepRequest Options(const std::filesystem::path& out, const std::string& shard, int jobs) {
  SweepRequest options;
  options.file = kFixture;
  options.out = out;
  options.shard = shard;
  options.jobs = jobs;
  options.plot = false;
  return options;
}

int LineCount(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST_F(SweepCommandTest, ResultsDoNotDependOnTheNumberOfJobs) {
  RunSweep(Options(tmp_.path() / "one", "1/2", 1), "test", nullptr);
  RunSweep(Options(tmp_.path() / "two", "1/2", 2), "test", nullptr);
  const std::string one = tmp_.Read("one/results.csv");
  EXPECT_EQ(LineCount(one), 1 + 4);  // header + cases 0, 2, 4, 6
  EXPECT_EQ(one, tmp_.Read("two/results.csv"));
  EXPECT_THAT(one, HasSubstr("\n0,0,0,1,60,true,"));
  EXPECT_THAT(one, HasSubstr("\n6,3,0,1,120,false,"));
  // No timing in results.csv: the cpu metric of the sweep file went to timings.csv.
  EXPECT_THAT(one.substr(0, one.find('\n')), Not(HasSubstr("cpu.")));
  EXPECT_THAT(tmp_.Read("one/timings.csv"), HasSubstr("case,wall_time_s,cpu.real_time_factor\n"));
  const auto record = io::ReadJsonFile(tmp_.path() / "one/sweep.json");
  EXPECT_EQ(record["complete"], true);
  EXPECT_EQ(record["shard"], "1/2");
  EXPECT_EQ(record["cases"], 8);
  EXPECT_EQ(record["shard_cases"], 4);
}

TEST_F(SweepCommandTest, AHalfWrittenRowIsRunAgainAndTheFinalFileIsTheSame) {
  const auto out = tmp_.path() / "s";
  RunSweep(Options(out, "2/4", 1), "test", nullptr);  // cases 1 and 5
  const std::string complete = tmp_.Read("s/results.csv");
  ASSERT_EQ(LineCount(complete), 3);
  // As if killed while appending case 5: its row is cut short, with no line break.
  const std::size_t second_row = complete.find('\n', complete.find('\n') + 1) + 1;
  tmp_.Write("s/results.csv", complete.substr(0, second_row + 12));
  RunSweep(Options(out, "2/4", 1), "test", nullptr);
  EXPECT_EQ(tmp_.Read("s/results.csv"), complete);
  EXPECT_EQ(io::ReadJsonFile(out / "sweep.json")["cases_run"], 1);  // case 1 was not run again
  // Done: a third start runs nothing and changes nothing.
  RunSweep(Options(out, "2/4", 1), "test", nullptr);
  EXPECT_EQ(tmp_.Read("s/results.csv"), complete);
  EXPECT_EQ(io::ReadJsonFile(out / "sweep.json")["cases_run"], 0);
}

TEST_F(SweepCommandTest, AFolderOfAnotherSweepIsLeftAlone) {
  const auto out = tmp_.path() / "s";
  RunSweep(Options(out, "4/4", 1), "test", nullptr);  // cases 3 and 7
  const std::string results = tmp_.Read("s/results.csv");
  const std::string record = tmp_.Read("s/sweep.json");
  try {
    RunSweep(Options(out, "3/4", 1), "test", nullptr);
    FAIL();
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(
        e.what(),
        HasSubstr(out.string() + " holds results of another sweep (shard 4/4; this is shard 3/4)"));
  }
  SweepRequest changed = Options(out, "4/4", 1);
  changed.overrides = {"limits.stall_time=30"};
  try {
    RunSweep(changed, "test", nullptr);
    FAIL();
  } catch (const core::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("holds results of another sweep"));
    EXPECT_THAT(e.what(), HasSubstr("use another --out or remove it"));
  }
  EXPECT_EQ(tmp_.Read("s/results.csv"), results);
  EXPECT_EQ(tmp_.Read("s/sweep.json"), record);
}

TEST_F(SweepCommandTest, ARowThatIsNotThisSweepsIsAnError) {
  const auto out = tmp_.path() / "s";
  RunSweep(Options(out, "4/4", 1), "test", nullptr);
  std::string results = tmp_.Read("s/results.csv");
  const std::size_t at = results.find("\n3,1,1,2,60,false,");
  ASSERT_NE(at, std::string::npos);
  results.replace(at, 18, "\n3,1,1,2,61,false,");
  tmp_.Write("s/results.csv", results);
  try {
    RunSweep(Options(out, "4/4", 1), "test", nullptr);
    FAIL();
  } catch (const core::IoError& e) {
    EXPECT_THAT(
        e.what(),
        HasSubstr("results.csv:2: case 3: nav.localizer.particles is '61', this sweep has '60'"));
  }
}

}  // namespace
}  // namespace retrace::bench
