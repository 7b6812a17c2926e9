// Every shipped suite (bench/suites/*.yaml) loads, its entries' scenarios load with their
// `set`, and its committed baseline (results/baselines/<name>.json) belongs to it and passes
// its own tolerances — a baseline that fails its own bounds would fail every CI run.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "bench/suite/baseline.hpp"
#include "bench/suite/suite_report.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/suite_spec.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::bench {
namespace {

using retrace::testing::kSource;

std::vector<std::filesystem::path> ShippedSuites() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "bench/suites")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(SuiteShipped, CiGatesThePaperMethodAndFullHoldsEveryCiEntry) {
  // What CI runs (scripts/test.sh) is the ci suite; it gates the success of partial maps in
  // every entry; the full suite runs every scenario of the ci suite as well.
  std::ifstream script(kSource / "scripts/test.sh");
  const std::string test_sh((std::istreambuf_iterator<char>(script)), {});
  EXPECT_NE(test_sh.find("retrace bench bench/suites/ci.yaml"), std::string::npos);
  const SuiteSpec ci = LoadSuiteSpec(kSource / "bench/suites/ci.yaml");
  const SuiteSpec full = LoadSuiteSpec(kSource / "bench/suites/full.yaml");
  const Baseline baseline = ReadBaseline(kSource / "results/baselines/ci.json");
  SuiteResults same;
  for (const auto& [name, value] : baseline.metrics) same.metrics[name] = {value, {value}};
  const SuiteReport report = CompareWithBaseline(ci, same, &baseline);
  ASSERT_FALSE(ci.entries.empty());
  for (const SuiteEntry& entry : ci.entries) {
    SCOPED_TRACE(entry.name);
    const std::string success = entry.name + ".partial.success_rate";
    const auto row = std::find_if(report.rows.begin(), report.rows.end(),
                                  [&](const ReportRow& r) { return r.name == success; });
    ASSERT_NE(row, report.rows.end());
    EXPECT_FALSE(row->tolerance.report) << "gated by " << row->pattern;
    EXPECT_TRUE(row->tolerance.has_delta() || row->tolerance.has_bound());
    const bool in_full = std::any_of(full.entries.begin(), full.entries.end(),
                                     [&](const SuiteEntry& f) { return f.scenario == entry.scenario; });
    EXPECT_TRUE(in_full) << entry.scenario;
  }
}

TEST(SuiteShipped, EverySuiteLoadsWithItsScenariosAndMatchesItsBaseline) {
  for (const std::filesystem::path& file : ShippedSuites()) {
    SCOPED_TRACE(file.string());
    const SuiteSpec spec = LoadSuiteSpec(file);
    EXPECT_EQ(spec.name, file.stem().string()) << "a suite is named after its file";

    // The scenarios with each entry's `set`, for the first seed (the others differ only in it).
    SuiteSpec first_seeds = spec;
    for (SuiteEntry& entry : first_seeds.entries) entry.seeds.resize(1);
    EXPECT_NO_THROW(LoadSuiteScenarios(first_seeds, {}));

    const std::filesystem::path baseline_file =
        kSource / "results/baselines" / (spec.name + ".json");
    const Baseline baseline = ReadBaseline(baseline_file);
    EXPECT_NO_THROW(CheckBaselineMatches(baseline, spec, baseline_file));

    // Results equal to the baseline: nothing may fail (every gated metric is recorded, and the
    // baseline lies within its own bounds).
    SuiteResults same;
    for (const auto* table : {&baseline.metrics, &baseline.timing}) {
      for (const auto& [name, value] : *table) same.metrics[name] = {value, {value}};
    }
    const SuiteReport report = CompareWithBaseline(spec, same, &baseline);
    EXPECT_EQ(report.failures, 0) << ReportTable(report);
    EXPECT_GT(report.checked, 0);
  }
}

// The tiny suite of tests/cli/bench_ci_files_test.sh, shipped with the tests.
TEST(SuiteShipped, TheTestsTinySuiteLoadsWithItsScenario) {
  const SuiteSpec tiny = LoadSuiteSpec(kSource / "tests/data/suite_tiny.yaml");
  EXPECT_EQ(tiny.name, "suite_tiny");
  ASSERT_EQ(tiny.entries.size(), 1u);
  EXPECT_EQ(tiny.entries[0].seeds.size(), 1u);  // one seed, one run: a second
  EXPECT_EQ(tiny.entries[0].repeats, 1);
  EXPECT_EQ(LoadSuiteScenarios(tiny, {}, 1).scenarios.at(0).size(), 1u);
}

}  // namespace
}  // namespace retrace::bench
