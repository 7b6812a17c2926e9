// Every shipped suite (bench/suites/*.yaml) loads, its entries' scenarios load with their
// `set`, and its committed baseline (results/baselines/<name>.json) belongs to it and passes
// its own tolerances — a baseline that fails its own bounds would fail every CI run.

#include <gtest/gtest.h>

#include <filesystem>

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

TEST(SuiteShipped, CiAndFullSuitesExist) {
  const std::vector<std::filesystem::path> files = ShippedSuites();
  EXPECT_NE(std::find(files.begin(), files.end(), kSource / "bench/suites/ci.yaml"), files.end());
  EXPECT_NE(std::find(files.begin(), files.end(), kSource / "bench/suites/full.yaml"), files.end());
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

}  // namespace
}  // namespace retrace::bench
