#pragma once
// Metric names of a suite and the patterns that select them. A suite metric is named
// "<entry>.<mode>.<metric>", <metric> being a FlatMetrics name (bench/metrics/flat_metrics.hpp),
// e.g. "office.partial.tracking_error_m.pooled.rms". In a pattern, `*` matches any run of
// characters inside one dotted part (so "*.*.tracking_error_m.pooled.rms" is every entry and
// mode, "*.partial.localization_error_*.pooled.rms" both units) and `**` any run of characters
// across dots ("small.**" is every metric of the entry small).

#include <string>
#include <string_view>
#include <vector>

namespace retrace::bench {

/// True when `pattern` matches the whole of `name`.
bool MatchMetricPattern(std::string_view pattern, std::string_view name);

/// Why `pattern` is malformed (empty, an empty dotted part, `***`, characters other than
/// letters, digits, '_', '-', '.', '*'), or "" when it is well formed.
std::string PatternProblem(std::string_view pattern);

/// The index of the pattern that decides `name`: the last one that matches (general rules
/// first, exceptions after), or -1 when none does.
int DecidingPattern(const std::vector<std::string>& patterns, std::string_view name);

}  // namespace retrace::bench
