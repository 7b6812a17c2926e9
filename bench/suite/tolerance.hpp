#pragma once
// The verdict on one suite metric: its value now against the committed baseline, under the
// tolerance of the suite rule that decides it (bench/suite/suite_spec.hpp).
//
// Rules, in this order:
//   1. Timing metrics (IsTimingMetric: cpu.*) and `report: true`: verdict `report`, never gated
//      — they measure the machine, not the navigation.
//   2. Not in the baseline at all: FAIL (the baseline is stale; rerun with --update-baseline).
//   3. NaN (undefined: no samples, no switches, no pedestrian seen): NaN in both → pass; NaN
//      now but a number in the baseline → FAIL ("became undefined"); a number now but NaN in
//      the baseline → FAIL ("appeared"): either way the metric changed nature.
//   4. Bound: now < min or now > max → FAIL, whatever the baseline.
//   5. Delta: worse = now - baseline when lower is better, baseline - now when higher is better;
//      allowed = max(abs, rel · |baseline|) (the looser of the two; a missing one counts 0).
//      worse > allowed → FAIL; worse < -allowed → improved; otherwise pass. A relative
//      tolerance of a zero baseline allows nothing.
//   6. A rule with a bound and no delta that holds: verdict `bound` (checked without the
//      baseline).
//
// Direction ("better"): lower is better, except for the metrics whose last dotted part is
// success_rate, successes, success (outcomes.success), mean_progress_m, precision, recall,
// real_time_factor, min_clearance_m, min_pedestrian_gap_m or repeatability_stations_used.
// A rule's `better: higher|lower` overrides it.

#include <optional>
#include <string>
#include <string_view>

#include "core/config.hpp"

namespace retrace::bench {

enum class Better { kLower, kHigher };

/// How far a metric may move from its baseline, or where it must lie. Unset fields do not
/// apply; at least one of abs, rel, min, max or report is set (checked by the suite reader).
struct Tolerance {
  std::optional<double> abs;  ///< in the metric's unit, >= 0
  std::optional<double> rel;  ///< fraction of |baseline|, >= 0
  std::optional<double> min;  ///< bound, in the metric's unit
  std::optional<double> max;
  std::optional<Better> better;  ///< overrides DefaultBetter
  bool report = false;           ///< shown, never gated

  bool has_delta() const { return abs.has_value() || rel.has_value(); }
  bool has_bound() const { return min.has_value() || max.has_value(); }
};

enum class Verdict {
  kPass,      ///< within the delta tolerance (or undefined in both)
  kImproved,  ///< better than the baseline by more than the tolerance
  kBound,     ///< a bound-only rule that holds
  kReport,    ///< not gated
  kFail,      ///< a regression: worse than allowed, out of bounds, undefined, or unknown
};

struct MetricCheck {
  Verdict verdict = Verdict::kPass;
  std::string reason;  ///< a few words: "worse by 0.031 > 0.02", "below min 1", "appeared"
};

/// The direction of a FlatMetrics name (without the "<entry>.<mode>." prefix).
Better DefaultBetter(std::string_view metric);

/// The direction a rule judges `metric` by: the rule's `better`, else DefaultBetter.
Better EffectiveBetter(std::string_view metric, const Tolerance& tolerance);

/// The verdict for `metric` (a FlatMetrics name, for the direction and the timing rule):
/// `baseline` is nullopt when the baseline lacks the metric; NaN means undefined.
MetricCheck CheckMetric(std::string_view metric, std::optional<double> baseline, double now,
                        const Tolerance& tolerance);

/// "abs 0.02, max 0.3, higher better" — the rule as the table shows it.
std::string DescribeTolerance(const Tolerance& tolerance);

/// True for verdicts that make `retrace bench` exit 1.
inline bool IsFailure(Verdict verdict) { return verdict == Verdict::kFail; }

}  // namespace retrace::bench

template <>
struct retrace::core::EnumTraits<retrace::bench::Better> {
  static constexpr std::array<std::pair<retrace::bench::Better, std::string_view>, 2> kNames{
      {{retrace::bench::Better::kLower, "lower"}, {retrace::bench::Better::kHigher, "higher"}}};
};

template <>
struct retrace::core::EnumTraits<retrace::bench::Verdict> {
  static constexpr std::array<std::pair<retrace::bench::Verdict, std::string_view>, 5> kNames{
      {{retrace::bench::Verdict::kPass, "pass"},
       {retrace::bench::Verdict::kImproved, "improved"},
       {retrace::bench::Verdict::kBound, "bound"},
       {retrace::bench::Verdict::kReport, "report"},
       {retrace::bench::Verdict::kFail, "FAIL"}}};
};
