#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "bench/compare/comparison_report.hpp"
#include "bench/compare/comparison_study.hpp"
#include "core/errors.hpp"
#include "io/json_writer.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using CompareCommand = retrace::testing::TempDirTest;

ComparisonRequest SmallStudy(const std::filesystem::path& out) {
  ComparisonRequest o;
  o.scenario = std::filesystem::path(RETRACE_SOURCE_DIR) / "scenarios/small.yaml";
  o.modes = {"partial", "consistent"};
  o.seeds = 2;
  o.repeats = 1;
  o.jobs = 2;
  o.out = out;
  // One U instead of two laps of the room, still with a map switch: half the work (the test
  // also runs under AddressSanitizer).
  o.overrides = {"route.points=[[1, 1], [9, 1], [9, 5], [1, 5]]", "route.switch_points=[10]"};
  return o;
}

// The whole command on the smallest scenario, shortened: 2 seeds x 1 run of partial and
// consistent.
TEST_F(CompareCommand, WritesTheStudyOfATinyRun) {
  const std::filesystem::path out = tmp_.path() / "compare";
  const ComparisonStudy study =
      RunComparisonStudy(SmallStudy(out), "retrace compare small.yaml", nullptr);
  const std::string stdout_text = ComparisonStudySummary(study);
  EXPECT_EQ(study.out, out);
  EXPECT_FALSE(std::filesystem::exists(tmp_.path() / "compare.tmp"));
  ASSERT_TRUE(std::filesystem::exists(out / "comparison.png"));
  EXPECT_GT(std::filesystem::file_size(out / "comparison.png"), 10000u);

  const nlohmann::json j = io::ReadJsonFile(out / "comparison.json");
  EXPECT_EQ(j.at("scenario"), "small");
  EXPECT_EQ(j.at("seeds"), nlohmann::json({1, 2}));  // the scenario's seed, then the next
  EXPECT_EQ(j.at("repeats"), 1);
  EXPECT_FALSE(j.at("git_revision").get<std::string>().empty());
  for (const char* mode : {"partial", "consistent"}) {
    const nlohmann::json& m = j.at("modes").at(mode);
    int runs = 0;
    for (const auto& [outcome, count] : m.at("outcomes").items()) runs += count.get<int>();
    EXPECT_EQ(runs, 2) << mode;
    for (const ComparedMetric& metric : ComparedMetrics()) {
      const nlohmann::json& v = m.at(metric.key);
      ASSERT_EQ(v.at("per_seed").size(), 2u) << mode << " " << metric.key;
      if (v.at("n").get<int>() < 2)
        continue;  // e.g. repeatability with one run, switches outside partial
      const double mean = v.at("mean").get<double>();
      EXPECT_LE(v.at("ci95").at(0).get<double>(), mean) << mode << " " << metric.key;
      EXPECT_GE(v.at("ci95").at(1).get<double>(), mean) << mode << " " << metric.key;
    }
  }
  // Measured on the runs: partial navigates, and its localization differs from consistent's.
  EXPECT_GT(j.at("modes").at("partial").at("progress_fraction").at("mean").get<double>(), 0.5);
  EXPECT_EQ(j.at("modes").at("partial").at("switch_error.max_m").at("n"), 2);
  EXPECT_TRUE(
      j.at("modes").at("partial").at("tracking_error_m.pooled.rms").contains("vs_reference"));

  const std::string md = tmp_.Read(out / "comparison.md");
  EXPECT_EQ(md, stdout_text.substr(0, md.size()));  // the summary printed is the table
  int rows = 0;
  std::istringstream lines(md);
  std::string line;
  while (std::getline(lines, line))
    rows += line.rfind("| ", 0) == 0 && line.rfind("| metric", 0) != 0;
  EXPECT_EQ(rows, static_cast<int>(ComparedMetrics().size()));
  EXPECT_NE(md.find("2 seeds × 1 playback run per mode"), std::string::npos) << md;
  EXPECT_NE(md.find("| partial − consistent |"), std::string::npos) << md;
}

TEST_F(CompareCommand, BadInputThrowsBeforeAnythingIsWritten) {
  const std::filesystem::path out = tmp_.path() / "compare";
  ComparisonRequest o = SmallStudy(out);
  o.modes = {"partial", "perfect"};
  EXPECT_THROW(RunComparisonStudy(o, "", nullptr), core::ConfigError);
  o = SmallStudy(out);
  o.modes = {"partial", "single"};  // the default reference, consistent, is not among them
  EXPECT_THROW(RunComparisonStudy(o, "", nullptr), core::ConfigError);
  o = SmallStudy(out);
  o.seeds = 1;
  EXPECT_THROW(RunComparisonStudy(o, "", nullptr), core::ConfigError);
  o = SmallStudy(out);
  o.overrides.push_back("nav.localizer.particle=100");
  EXPECT_THROW(RunComparisonStudy(o, "", nullptr), core::ConfigError);
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(tmp_.path() / "compare.tmp"));
}

}  // namespace
}  // namespace retrace::bench
