#include "bench/replay/log_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <utility>

#include "bench/engine/local_truth.hpp"
#include "bench/metrics/metrics_json.hpp"
#include "core/nearest_grid.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {

LogLocalizeSeries ComputeLogSeries(const LogLocalizeResult& run, const TeachTrace& teach) {
  LogLocalizeSeries series;
  std::vector<core::Vec2> taught;
  for (const core::Pose2& X_WR : teach.X_WR) taught.push_back(X_WR.translation());
  // The taught trajectory as a polyline, as the simulated metrics measure it.
  const core::PolylineDistance to_taught(taught);
  double driven = 0.0;
  std::optional<core::Vec2> previous;
  int map = -1;
  for (const LogLocalizeSample& s : run.samples) {
    // Along the reference, which is continuous; without one along the estimate, which jumps
    // into the next map's frame at a switch.
    const core::Vec2 p = s.X_WR ? s.X_WR->translation() : s.X_MR.translation();
    if (previous && (s.X_WR || s.map == map)) driven += (p - *previous).norm();
    previous = p;
    map = s.map;
    series.driven_m.push_back(driven);
    if (!s.X_MR_truth || !s.X_WR) {
      series.path_distance_m.push_back(kMetricNaN);
      series.localization_error_m.push_back(kMetricNaN);
      series.localization_error_rad.push_back(kMetricNaN);
      continue;
    }
    const PoseError e = Compare(s.X_MR, *s.X_MR_truth);
    series.localization_error_m.push_back(e.distance);
    series.localization_error_rad.push_back(e.angle);
    // Where the robot was, not where it believed it was: the reference against the taught
    // trajectory, both in the reference's frame.
    series.path_distance_m.push_back(taught.empty() ? kMetricNaN
                                                    : to_taught(s.X_WR->translation()));
  }
  return series;
}

LogLocalizeMetrics ComputeLogMetrics(const LogLocalizeResult& run, const LogLocalizeSeries& series,
                                     const nav::TeachBundle& bundle, const TeachTrace& teach,
                                     const MetricsConfig& config) {
  LogLocalizeMetrics m;
  std::vector<EstimateSample> track;
  track.reserve(run.samples.size());
  for (std::size_t i = 0; i < run.samples.size(); ++i) {
    const LogLocalizeSample& s = run.samples[i];
    track.push_back({s.time, s.map, s.X_MR, s.X_OR, s.lost});
    track.back().off_map = s.off_map;
    track.back().error = series.localization_error_m[i];
    if (i == 0) continue;
    const LogLocalizeSample& prev = run.samples[i - 1];
    if (prev.map == s.map && s.X_MR_truth && s.X_WR && prev.X_WR) {
      track.back().error_increase =
          ErrorIncrease(prev.X_MR, s.X_MR, *prev.X_WR, *s.X_WR, *s.X_MR_truth);
    }
  }
  m.localizer = ComputeLocalizerHealth(track, run.updates);
  const bool reference = std::any_of(run.samples.begin(), run.samples.end(),
                                     [](const LogLocalizeSample& s) { return s.X_WR.has_value(); });
  if (reference) m.localizer.wrong_switches = CountWrongSwitches(run.switches, teach);
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
    std::vector<double> on_route;
    for (std::size_t i = 0; i < series.localization_error_m.size(); ++i) {
      if (std::isfinite(series.localization_error_m[i]) && series.path_distance_m[i] <= kOnRoute)
        on_route.push_back(series.localization_error_m[i]);
    }
    m.on_route_fraction = static_cast<double>(on_route.size()) / m.localization_error_m.count;
    m.localization_error_on_route_m = Summarize(on_route);
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
          {"on_route_fraction", io::JsonNumber(m.on_route_fraction)},
          {"localization_error_on_route_m", ToJson(m.localization_error_on_route_m)},
          {"rejected_fraction", io::JsonNumber(m.rejected_fraction)},
          {"update_time_ms", ToJson(m.update_time_ms)},
          {"real_time_factor", io::JsonNumber(m.real_time_factor)},
          {"localizer", ToJson(m.localizer)}};
}

std::string OffRouteWarning(const LogLocalizeSeries& series) {
  double nearest = std::numeric_limits<double>::infinity();
  for (double d : series.path_distance_m) {
    if (std::isfinite(d)) nearest = std::min(nearest, d);
  }
  if (!std::isfinite(nearest) || nearest <= kOnRoute) return {};
  char text[320];
  std::snprintf(text, sizeof text,
                "the localized window never comes within %.1f m of the taught route (at the "
                "nearest %.1f m): it does not repeat the taught drive, and errors off the route "
                "say little about the method; localize a part of the log that drives the taught "
                "route again",
                kOnRoute, nearest);
  return text;
}

}  // namespace retrace::bench
