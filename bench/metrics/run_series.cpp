#include "bench/metrics/internal/run_series.hpp"

#include <limits>

#include "bench/metrics/localizer_health.hpp"

namespace retrace::bench {
namespace internal {

RunSeries Series(TeachIndex& index, const RunTrace& run, const MetricsConfig& config,
                 bool with_localization) {
  const std::size_t n = run.samples.size();
  RunSeries out;
  out.tracking_error_m.assign(n, kMetricNaN);
  out.progress_m.assign(n, kMetricNaN);
  out.lateral_offset_m.assign(n, kMetricNaN);
  if (with_localization) {
    out.localization_error_m.assign(n, kMetricNaN);
    out.localization_error_rad.assign(n, kMetricNaN);
    out.error_increase_m.assign(n, kMetricNaN);
  }
  PathTracker tracker(index.path, config);
  int current_map = std::numeric_limits<int>::min();
  for (std::size_t i = 0; i < n; ++i) {
    const PlaybackSample& sample = run.samples[i];
    const Vec2 p = sample.X_WR.translation();
    if (!index.path.empty()) {
      if (with_localization) out.tracking_error_m[i] = index.path.Distance(p);
      const Projection proj = tracker.Track(p);
      out.progress_m[i] = proj.s;
      out.lateral_offset_m[i] = proj.lateral;
    }
    if (!with_localization) continue;
    LocalTruth* matcher = index.Matcher(sample.map_index);
    const bool same_map = sample.map_index == current_map;
    if (!same_map) {
      current_map = sample.map_index;
      if (matcher != nullptr) matcher->Reset();
    }
    if (matcher == nullptr) continue;
    const core::Pose2 truth = matcher->InMap(sample.X_WR);
    const PoseError e = Compare(sample.X_MR, truth);
    out.localization_error_m[i] = e.distance;
    out.localization_error_rad[i] = e.angle;
    if (same_map && i > 0) {
      const PlaybackSample& prev = run.samples[i - 1];
      out.error_increase_m[i] =
          ErrorIncrease(prev.X_MR, sample.X_MR, prev.X_WR, sample.X_WR, truth);
    }
  }
  return out;
}

}  // namespace internal

RunSeries ComputeRunSeries(const TeachTrace& teach, const RunTrace& run,
                           const MetricsConfig& config) {
  internal::TeachIndex index(teach, config);
  return internal::Series(index, run, config, /*with_localization=*/true);
}

}  // namespace retrace::bench
