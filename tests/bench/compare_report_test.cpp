#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "bench/compare/comparison_report.hpp"
#include "bench/metrics/flat_metrics.hpp"
#include "tests/support/temp_dir.hpp"
#include "viz/figures.hpp"
#include "viz/image.hpp"

namespace retrace::bench {
namespace {

// FlatMetrics of one mode on one seed as the study reads them: every source key, the values
// shifted by `offset` so that modes and seeds differ.
std::map<std::string, double> Flat(double offset, int runs, int successes) {
  std::map<std::string, double> f;
  f["runs"] = runs;
  f["success_rate"] = static_cast<double>(successes) / runs;
  f["outcomes.success"] = successes;
  f["outcomes.lost"] = runs - successes;
  f["outcomes.timeout"] = 0;
  f["outcomes.collision"] = 0;
  f["tracking_error_m.pooled.rms"] = 0.1 + offset;
  f["tracking_error_m.pooled.max"] = 0.4 + offset;
  f["localization_error_m.pooled.rms"] = 0.05 + offset;
  f["localization_error_m.pooled.max"] = 0.3 + offset;
  f["repeatability_m"] = 0.02 + offset;
  f["repeatability_max_spread_m"] = 0.08 + offset;
  f["switch_error.max_m"] = 0.2 + offset;  // the study reports it for partial only
  f["lost_fraction.pooled"] = 0.0;
  f["mean_progress_m"] = 40.0 - 10.0 * offset;
  f["taught_path_length_m"] = 50.0;
  f["collisions.pedestrian_incidents"] = 2.0;
  f["cpu.localizer_update_mean_ms"] = 1.5 + offset;
  return f;
}

// Three modes on three seeds: partial is 0.01 m worse than consistent on every seed; single
// is worse and loses runs; seeds differ by 0.1 m.
ComparisonInput ThreeModes() {
  ComparisonInput in;
  in.scenario_name = "synthetic";
  in.scenario_file = "synthetic.yaml";
  in.git_revision = "abc123";
  in.seeds = {4, 5, 6};
  in.repeats = 2;
  in.modes = {MapMode::kPartial, MapMode::kSingle, MapMode::kConsistent};
  in.reference = MapMode::kConsistent;
  in.flat.resize(3);
  for (int s = 0; s < 3; ++s) {
    in.flat[0].push_back(Flat(0.1 * s + 0.01, 2, 2));
    in.flat[1].push_back(Flat(0.1 * s + 0.5 + 0.05 * s * s, 2, s == 0 ? 1 : 0));
    in.flat[2].push_back(Flat(0.1 * s, 2, 2));
  }
  return in;
}

const MetricComparison& Row(const Comparison& c, const std::string& key) {
  for (const MetricComparison& row : c.metrics) {
    if (row.metric.key == key) return row;
  }
  ADD_FAILURE() << "no metric " << key;
  return c.metrics.front();
}

TEST(CompareReport, SummariesAndPairedDifferencesComeFromTheStatistics) {
  const Comparison c = Compare(ThreeModes());
  ASSERT_EQ(c.metrics.size(), ComparedMetrics().size());
  EXPECT_EQ(c.reference_index, 2u);
  const MetricComparison& tracking = Row(c, "tracking_error_m.pooled.rms");
  for (std::size_t m = 0; m < 3; ++m) {
    const MeanInterval expected = MeanConfidenceInterval(tracking.per_seed[m]);
    EXPECT_DOUBLE_EQ(tracking.summary[m].mean, expected.mean);
    EXPECT_DOUBLE_EQ(tracking.summary[m].lower, expected.lower);
    EXPECT_DOUBLE_EQ(tracking.summary[m].upper, expected.upper);
    EXPECT_LT(tracking.summary[m].lower, tracking.summary[m].mean);
    EXPECT_GT(tracking.summary[m].upper, tracking.summary[m].mean);
  }
  EXPECT_NEAR(tracking.summary[2].mean, 0.2, 1e-12);
  EXPECT_FALSE(tracking.vs_reference[2].has_value());  // the reference itself
  ASSERT_TRUE(tracking.vs_reference[0].has_value());
  // Partial is 0.01 m above consistent on every seed: a zero-width interval at 0.01.
  EXPECT_NEAR(tracking.vs_reference[0]->difference.mean, 0.01, 1e-12);
  EXPECT_TRUE(tracking.vs_reference[0]->significant);
  EXPECT_NEAR(tracking.vs_reference[0]->ratio_of_means, 0.21 / 0.2, 1e-12);
  const PairedComparison single = ComparePaired(tracking.per_seed[1], tracking.per_seed[2]);
  EXPECT_DOUBLE_EQ(tracking.vs_reference[1]->difference.lower, single.difference.lower);
  EXPECT_DOUBLE_EQ(tracking.vs_reference[1]->difference.upper, single.difference.upper);
}

TEST(CompareReport, SwitchErrorIsForPartialOnlyAndDerivedMetricsAreDivided) {
  const Comparison c = Compare(ThreeModes());
  const MetricComparison& sw = Row(c, "switch_error.max_m");
  EXPECT_EQ(sw.summary[0].n, 3);
  EXPECT_EQ(sw.summary[1].n, 0);  // present in FlatMetrics, but n/a outside partial
  EXPECT_TRUE(std::isnan(sw.per_seed[2][0]));
  EXPECT_FALSE(sw.vs_reference[0].has_value());  // the reference has no switches to compare with
  const MetricComparison& progress = Row(c, "progress_fraction");
  EXPECT_NEAR(progress.per_seed[2][1], (40.0 - 1.0) / 50.0, 1e-12);
  const MetricComparison& incidents = Row(c, "collisions.pedestrian_incidents_per_run");
  EXPECT_DOUBLE_EQ(incidents.per_seed[0][0], 1.0);  // 2 incidents over 2 runs
  // The same value on every seed and in every mode: no difference, no ratio problem.
  EXPECT_FALSE(incidents.vs_reference[0]->significant);
  EXPECT_DOUBLE_EQ(incidents.vs_reference[0]->ratio_of_means, 1.0);
  EXPECT_TRUE(Row(c, "cpu.localizer_update_mean_ms").metric.timing);
  // A missing key or a zero divisor is undefined, not 0 or inf.
  const ComparedMetric& progress_metric = progress.metric;
  EXPECT_TRUE(
      std::isnan(ComparedValue(progress_metric, MapMode::kPartial, {{"mean_progress_m", 3.0}})));
  EXPECT_TRUE(std::isnan(ComparedValue(progress_metric, MapMode::kPartial,
                                       {{"mean_progress_m", 3.0}, {"taught_path_length_m", 0.0}})));
}

TEST(CompareReport, OutcomesAreSummedOverSeeds) {
  const Comparison c = Compare(ThreeModes());
  EXPECT_EQ(c.outcomes[0][static_cast<int>(Outcome::kSuccess)], 6);
  EXPECT_EQ(c.outcomes[1][static_cast<int>(Outcome::kSuccess)], 1);
  EXPECT_EQ(c.outcomes[1][static_cast<int>(Outcome::kLost)], 5);
}

TEST(CompareReport, MarkdownHasARowPerMetricAndNamesTheSignificantDifferences) {
  const std::string md = ComparisonMarkdown(Compare(ThreeModes()));
  EXPECT_NE(md.find("3 seeds × 2 playback runs"), std::string::npos) << md;
  EXPECT_NE(md.find("Student t with 2 degrees of freedom"), std::string::npos) << md;
  EXPECT_NE(md.find("| metric | unit | partial | single | consistent | partial − consistent | "
                    "partial / consistent | "
                    "single − consistent | single / consistent |"),
            std::string::npos)
      << md;
  std::istringstream lines(md);
  std::string line;
  int table_rows = 0;
  int columns = -1;
  while (std::getline(lines, line)) {
    if (line.rfind("| ", 0) != 0 || line.rfind("| metric", 0) == 0) continue;
    ++table_rows;
    const int bars = static_cast<int>(std::count(line.begin(), line.end(), '|'));
    if (columns < 0) columns = bars;
    EXPECT_EQ(bars, columns) << line;
  }
  EXPECT_EQ(table_rows, static_cast<int>(ComparedMetrics().size()));
  EXPECT_EQ(columns, 2 + 3 + 4 + 1);
  for (const ComparedMetric& metric : ComparedMetrics()) {
    EXPECT_NE(md.find("| " + metric.label), std::string::npos) << metric.label;
  }
  EXPECT_NE(md.find("| localizer update time (timing) | ms |"), std::string::npos);
  // Partial's constant +0.01 m is significant; the switch error has no difference to show.
  EXPECT_NE(md.find("+0.01 [+0.01, +0.01] *"), std::string::npos) << md;
  EXPECT_NE(md.find("Significant differences, partial − consistent: tracking error RMS (+0.01 m)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| map-switch error max | m | 0.31 [0.0616, 0.558] | n/a | n/a | n/a | n/a | "
                    "n/a | n/a |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("single 1 success, 5 lost"), std::string::npos) << md;
}

TEST(CompareReport, JsonHoldsPerSeedValuesIntervalsAndDifferences) {
  const nlohmann::json j = nlohmann::json::parse(ComparisonJson(Compare(ThreeModes())).dump());
  EXPECT_EQ(j.at("seeds"), nlohmann::json({4, 5, 6}));
  EXPECT_EQ(j.at("repeats"), 2);
  EXPECT_EQ(j.at("reference"), "consistent");
  EXPECT_EQ(j.at("git_revision"), "abc123");
  EXPECT_EQ(j.at("metrics").size(), ComparedMetrics().size());
  const nlohmann::json& partial = j.at("modes").at("partial");
  EXPECT_EQ(partial.at("outcomes").at("success"), 6);
  const nlohmann::json& tracking = partial.at("tracking_error_m.pooled.rms");
  EXPECT_EQ(tracking.at("per_seed").size(), 3u);
  EXPECT_EQ(tracking.at("n"), 3);
  const double mean = tracking.at("mean").get<double>();
  EXPECT_LT(tracking.at("ci95").at(0).get<double>(), mean);
  EXPECT_GT(tracking.at("ci95").at(1).get<double>(), mean);
  EXPECT_NEAR(tracking.at("vs_reference").at("mean").get<double>(), 0.01, 1e-12);
  EXPECT_TRUE(tracking.at("vs_reference").at("significant").get<bool>());
  EXPECT_FALSE(j.at("modes").at("consistent").at("success_rate").contains("vs_reference"));
  // Undefined values are null, not 0.
  const nlohmann::json& single_switch = j.at("modes").at("single").at("switch_error.max_m");
  EXPECT_TRUE(single_switch.at("per_seed").at(0).is_null());
  EXPECT_TRUE(single_switch.at("mean").is_null());
  EXPECT_TRUE(single_switch.at("ci95").at(0).is_null());
}

TEST(CompareReport, FigureDrawsEachModesMeanWithItsInterval) {
  retrace::testing::TempDir tmp;
  const Comparison c = Compare(ThreeModes());
  const viz::FigureInfo info =
      viz::RenderComparisonFigure(ComparisonFigure(c), tmp.path() / "comparison.png");
  ASSERT_EQ(info.panels.size(), ComparedMetrics().size());
  const viz::Image img = viz::ReadPng(info.path);
  const viz::PanelInfo& panel = info.Panel("tracking error max (m)");
  const MeanInterval& single = Row(c, "tracking_error_m.pooled.max").summary[1];
  auto pixel = [&](double x, double y) {
    const viz::Vec2 p = panel.ToFigurePixel(viz::Vec2(x, y));
    return img.At(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  };
  auto dark = [](viz::Rgba p) { return p.r < 80 && p.g < 80 && p.b < 80; };
  auto light = [](viz::Rgba p) {
    return p.r > 200 && p.g > 200 && p.b > 200;
  };  // background or grid
  // Single's bar (x in [1, 2]) up to its mean, its whisker above the bar up to the upper bound,
  // and nothing beside the whisker.
  EXPECT_EQ(pixel(1.3, 0.5 * single.mean), viz::ModeColor("single", 1));
  EXPECT_TRUE(dark(pixel(1.5, 0.5 * (single.mean + single.upper))));
  EXPECT_TRUE(light(pixel(1.3, 0.5 * (single.mean + single.upper))));
}

}  // namespace
}  // namespace retrace::bench
