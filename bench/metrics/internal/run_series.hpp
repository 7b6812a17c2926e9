#pragma once
// Per-sample series of a run against the teaching drive (tracking error, progress, lateral
// offset, localization error), from which the run metrics, the aggregate and the
// repeatability are computed.

#include <optional>
#include <vector>

#include "bench/engine/local_truth.hpp"
#include "bench/engine/metrics_config.hpp"
#include "bench/engine/trace.hpp"
#include "bench/metrics/internal/taught_path.hpp"
#include "bench/metrics/metrics.hpp"

namespace retrace::bench::internal {

// What one run's metrics need from the teach trace, built once per run.
struct TeachIndex {
  TeachIndex(const TeachTrace& teach, const MetricsConfig& config) : path(teach.X_WR) {
    matchers.reserve(teach.maps.size());
    for (const TeachMapTrace& map : teach.maps) {
      if (map.X_WR.empty() || map.X_WR.size() != map.X_MR.size()) {
        matchers.emplace_back();  // no reference: its samples are left out
      } else {
        matchers.emplace_back(std::in_place, map, config.match_window,
                              config.match_fallback_distance);
      }
    }
  }
  LocalTruth* Matcher(int k) {
    if (k < 0 || static_cast<std::size_t>(k) >= matchers.size()) return nullptr;
    std::optional<LocalTruth>& m = matchers[static_cast<std::size_t>(k)];
    return m ? &*m : nullptr;
  }
  TaughtPath path;
  std::vector<std::optional<LocalTruth>> matchers;
};

// The series of `run`; the localization error only when `with_localization`.
RunSeries Series(TeachIndex& index, const RunTrace& run, const MetricsConfig& config,
                 bool with_localization);

// The lateral offsets of the runs (their series) at the stations along a taught path of
// `path_length` m (part of Aggregate).
Repeatability RepeatabilityFromSeries(double path_length, bool path_empty,
                                      const std::vector<int>& run_ids,
                                      const std::vector<RunSeries>& series,
                                      const MetricsConfig& config);

}  // namespace retrace::bench::internal
