#pragma once
// Small statistics the metric families share: NaN-skipping minima and maxima, ratios that are
// NaN for an empty denominator, the fraction of values above a threshold, the mean of per-run
// summaries.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bench/metrics/metrics.hpp"

namespace retrace::bench::internal {

inline double FractionAbove(const std::vector<double>& values, double threshold) {
  int n = 0, above = 0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    ++n;
    if (v > threshold) ++above;
  }
  return n > 0 ? static_cast<double>(above) / n : kMetricNaN;
}

inline double Ratio(std::int64_t num, std::int64_t den) {
  return den > 0 ? static_cast<double>(num) / static_cast<double>(den) : kMetricNaN;
}

inline void FinishDynamicPoints(DynamicPointStats& d) {
  d.rejected_fraction = Ratio(d.beams_rejected, d.beams_tested);
  d.precision = Ratio(d.true_positive, d.true_positive + d.false_positive);
  d.recall = Ratio(d.true_positive, d.true_positive + d.false_negative);
}

// min that skips NaN (a NaN `a` is "no value yet").
inline double MinSkipNaN(double a, double b) {
  if (std::isnan(b)) return a;
  if (std::isnan(a)) return b;
  return std::min(a, b);
}
inline double MaxSkipNaN(double a, double b) {
  if (std::isnan(b)) return a;
  if (std::isnan(a)) return b;
  return std::max(a, b);
}

// Each statistic averaged over the summaries with samples; count = their number.
Summary MeanOfSummaries(const std::vector<const Summary*>& summaries);

}  // namespace retrace::bench::internal
