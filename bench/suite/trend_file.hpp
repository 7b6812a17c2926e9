#pragma once
// A suite run's metrics as a trend file (`retrace bench --trend`), for a service that charts them
// across commits, in the Bencher Metric Format (BMF: bencher.dev/docs/reference/
// bencher-metric-format; `bencher run --adapter json --file trend.json` reads it):
//
//   {
//     "office.partial.success_rate": {
//       "higher-is-better": {"value": 0.9375, "lower_value": 0.5, "upper_value": 1}
//     },
//     "office.partial.tracking_error_m.pooled.rms": {
//       "lower-is-better": {"value": 0.0812, "lower_value": 0.071, "upper_value": 0.093}
//     },
//     …
//   }
//
// One benchmark per row of the report (every metric a rule of the suite gates or reports), named
// by its suite metric name, in the report's order; value: the mean over the seeds (what the
// baseline is compared with), lower_value and upper_value: the smallest and the largest seed's.
// A metric undefined in this run (NaN) is left out: BMF values are numbers.
//
// The measure carries the direction that is better. BMF has no field for it: Bencher keeps it in
// a measure's threshold (an upper boundary where a larger value is a regression, a lower one
// where a smaller value is), so the metrics are put into two measures by the direction of the
// rule that decides them (EffectiveBetter, bench/suite/tolerance.hpp), and two thresholds cover
// them all. docs/CI.md feeds the same file to github-action-benchmark, one direction at a time.

#include <nlohmann/json.hpp>
#include <string_view>

#include "bench/suite/suite_report.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/tolerance.hpp"

namespace retrace::bench {

/// "lower-is-better" or "higher-is-better": the trend file's measure for a direction.
std::string_view TrendMeasure(Better better);

/// The trend file of a run: `report`'s rows, with their seeds' values from `results`.
nlohmann::ordered_json TrendJson(const SuiteReport& report, const SuiteResults& results);

}  // namespace retrace::bench
