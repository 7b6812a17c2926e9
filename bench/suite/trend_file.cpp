#include "bench/suite/trend_file.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "bench/suite/suite_spec.hpp"

namespace retrace::bench {

std::string_view TrendMeasure(Better better) {
  return better == Better::kHigher ? "higher-is-better" : "lower-is-better";
}

nlohmann::ordered_json TrendJson(const SuiteReport& report, const SuiteResults& results) {
  nlohmann::ordered_json trend = nlohmann::ordered_json::object();
  for (const ReportRow& row : report.rows) {
    if (!row.now || !std::isfinite(*row.now)) continue;
    nlohmann::ordered_json metric = {{"value", *row.now}};
    // The seeds' spread, where the run has the per-seed values (a baseline-only row has none).
    if (const auto it = results.metrics.find(row.name); it != results.metrics.end()) {
      bool any = false;
      double lo = 0.0;
      double hi = 0.0;
      for (double v : it->second.per_seed) {
        if (!std::isfinite(v)) continue;
        lo = any ? std::min(lo, v) : v;
        hi = any ? std::max(hi, v) : v;
        any = true;
      }
      if (any) {
        metric["lower_value"] = lo;
        metric["upper_value"] = hi;
      }
    }
    const Better better = EffectiveBetter(SplitSuiteMetricName(row.name).metric, row.tolerance);
    trend[row.name] = {{std::string(TrendMeasure(better)), std::move(metric)}};
  }
  return trend;
}

}  // namespace retrace::bench
