#include "bench/suite/tolerance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "bench/metrics/flat_metrics.hpp"
#include "core/format.hpp"

namespace retrace::bench {
namespace {

// The metrics where more is better: success, progress, detection quality, speed of the
// simulation, distance and time kept from things, efficiency, pedestrians passing freely.
// Everything else is an error, a count of bad events or a cost, where less is better.
constexpr std::array<std::string_view, 16> kHigherIsBetter = {"success_rate",
                                                              "successes",
                                                              "success",
                                                              "mean_progress_m",
                                                              "precision",
                                                              "recall",
                                                              "real_time_factor",
                                                              "min_clearance_m",
                                                              "min_pedestrian_gap_m",
                                                              "repeatability_stations_used",
                                                              "agreement",
                                                              "matched",
                                                              "min_ttc_s",
                                                              "path_efficiency",
                                                              "time_efficiency",
                                                              "passed"};

// Four significant digits: enough to see a change in a table, short enough to read.
std::string Short(double v) { return core::Printf("%.4g", v); }

}  // namespace

Better DefaultBetter(std::string_view metric) {
  const std::size_t dot = metric.rfind('.');
  const std::string_view leaf = dot == std::string_view::npos ? metric : metric.substr(dot + 1);
  return std::find(kHigherIsBetter.begin(), kHigherIsBetter.end(), leaf) != kHigherIsBetter.end()
             ? Better::kHigher
             : Better::kLower;
}

Better EffectiveBetter(std::string_view metric, const Tolerance& tolerance) {
  return tolerance.better.value_or(DefaultBetter(metric));
}

MetricCheck CheckMetric(std::string_view metric, std::optional<double> baseline, double now,
                        const Tolerance& tolerance) {
  if (tolerance.report) return {Verdict::kReport, ""};
  if (IsTimingMetric(std::string(metric))) return {Verdict::kReport, "timing, not gated"};
  if (!baseline) return {Verdict::kFail, "not in the baseline"};
  const double base = *baseline;
  if (std::isnan(now) && std::isnan(base)) return {Verdict::kPass, "undefined in both"};
  if (std::isnan(now)) return {Verdict::kFail, "became undefined"};
  if (std::isnan(base)) return {Verdict::kFail, "appeared (undefined in the baseline)"};

  if (tolerance.min && now < *tolerance.min)
    return {Verdict::kFail, "below min " + Short(*tolerance.min)};
  if (tolerance.max && now > *tolerance.max)
    return {Verdict::kFail, "above max " + Short(*tolerance.max)};
  if (!tolerance.has_delta()) return {Verdict::kBound, ""};

  const double worse =
      EffectiveBetter(metric, tolerance) == Better::kLower ? now - base : base - now;
  const double allowed =
      std::max(tolerance.abs.value_or(0.0), tolerance.rel.value_or(0.0) * std::abs(base));
  if (worse > allowed) return {Verdict::kFail, "worse by " + Short(worse) + " > " + Short(allowed)};
  if (worse < -allowed) return {Verdict::kImproved, "better by " + Short(-worse)};
  return {Verdict::kPass, ""};
}

std::string DescribeTolerance(const Tolerance& tolerance) {
  if (tolerance.report) return "report";
  std::string text;
  auto add = [&text](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  if (tolerance.abs) add("abs " + Short(*tolerance.abs));
  if (tolerance.rel) add("rel " + Short(*tolerance.rel * 100.0) + " %");
  if (tolerance.min) add("min " + Short(*tolerance.min));
  if (tolerance.max) add("max " + Short(*tolerance.max));
  if (tolerance.better) add(std::string(core::EnumName(*tolerance.better)) + " better");
  return text;
}

}  // namespace retrace::bench
