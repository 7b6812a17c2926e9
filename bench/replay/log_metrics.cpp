#include "bench/replay/log_metrics.hpp"

#include <cmath>
#include <optional>

#include "bench/engine/local_truth.hpp"
#include "bench/metrics/metrics_json.hpp"
#include "core/path_projection.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {

LogLocalizeSeries ComputeLogSeries(const LogLocalizeResult& run, const nav::TeachBundle& bundle,
                                   const MetricsConfig& config) {
  LogLocalizeSeries series;
  double driven = 0.0;
  std::optional<core::Vec2> previous;
  int map = -1;
  core::ForwardProgress progress;
  for (const LogLocalizeSample& s : run.samples) {
    // Along the reference, which is continuous; without one along the estimate, which jumps
    // into the next map's frame at a switch.
    const core::Vec2 p = s.X_WR ? s.X_WR->translation() : s.X_MR.translation();
    if (previous && (s.X_WR || s.map == map)) driven += (p - *previous).norm();
    previous = p;
    series.driven_m.push_back(driven);
    if (s.map != map) {
      map = s.map;
      progress = core::ForwardProgress();
    }
    if (!s.X_MR_truth) {
      series.path_distance_m.push_back(kMetricNaN);
      series.localization_error_m.push_back(kMetricNaN);
      series.localization_error_rad.push_back(kMetricNaN);
      continue;
    }
    const PoseError e = Compare(s.X_MR, *s.X_MR_truth);
    series.localization_error_m.push_back(e.distance);
    series.localization_error_rad.push_back(e.angle);
    const core::Path& path = bundle.maps.at(static_cast<std::size_t>(s.map)).path;
    const core::Vec2 q = s.X_MR_truth->translation();
    progress.Advance(path.positions(), path.arc_lengths(), q,
                     progress.value() + config.match_window);
    const core::PathProjection here = core::ProjectOntoPath(path.positions(), path.arc_lengths(), q,
                                                            progress.value() - config.match_window,
                                                            progress.value() + config.match_window);
    series.path_distance_m.push_back(here.distance);
  }
  return series;
}

LogLocalizeMetrics ComputeLogMetrics(const LogLocalizeResult& run, const LogLocalizeSeries& series,
                                     const nav::TeachBundle& bundle, const MetricsConfig& config) {
  LogLocalizeMetrics m;
  m.scans = static_cast<int>(run.samples.size());
  m.updates = static_cast<int>(run.updates.size());
  m.switches = static_cast<int>(run.switches.size());
  m.maps = static_cast<int>(bundle.maps.size());
  m.loop = run.loop;
  m.laps_completed = run.laps_completed;
  m.duration_s = run.last_s - run.first_s;
  m.localization_error_m = Summarize(series.localization_error_m);
  m.localization_error_rad = Summarize(series.localization_error_rad);
  m.path_distance_m = Summarize(series.path_distance_m);
  m.has_truth = m.localization_error_m.count > 0;
  if (m.has_truth) {
    int lost = 0;
    for (double e : series.localization_error_m) lost += std::isfinite(e) && e > config.lost_error;
    m.lost_fraction = static_cast<double>(lost) / m.localization_error_m.count;
  }
  long tested = 0, rejected = 0;
  std::vector<double> times_ms;
  for (const LocalizerSample& u : run.updates) {
    tested += u.beams_tested;
    rejected += u.beams_rejected;
    times_ms.push_back(u.cpu_s * 1e3);
  }
  if (tested > 0) m.rejected_fraction = static_cast<double>(rejected) / static_cast<double>(tested);
  m.update_time_ms = Summarize(times_ms);
  if (run.cpu_time_s > 0.0) m.real_time_factor = m.duration_s / run.cpu_time_s;
  return m;
}

nlohmann::json ToJson(const LogLocalizeMetrics& m) {
  return {{"scans", m.scans},
          {"updates", m.updates},
          {"maps", m.maps},
          {"switches", m.switches},
          {"loop", m.loop},
          {"laps_completed", m.laps_completed},
          {"duration_s", io::JsonNumber(m.duration_s)},
          {"localization_error_m", ToJson(m.localization_error_m)},
          {"localization_error_rad", ToJson(m.localization_error_rad)},
          {"lost_fraction", io::JsonNumber(m.lost_fraction)},
          {"path_distance_m", ToJson(m.path_distance_m)},
          {"rejected_fraction", io::JsonNumber(m.rejected_fraction)},
          {"update_time_ms", ToJson(m.update_time_ms)},
          {"real_time_factor", io::JsonNumber(m.real_time_factor)}};
}

}  // namespace retrace::bench
