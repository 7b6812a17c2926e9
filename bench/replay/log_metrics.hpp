#pragma once
// The metrics of a log's localization run (`retrace log-localize`: docs/DESIGN.md §10, its
// metrics.json in docs/FORMATS.md), the log's reference standing in for ground truth:
//
//   localization_error_m / _rad  the estimate against the local truth (bench/engine/
//                                local_truth.hpp) at every scan, as for simulated runs
//   lost_fraction                of those scans, the share with an error above
//                                metrics.lost_error
//   path_distance_m              how far the log's drive was from the taught route: the
//                                reference's distance to the polyline of the teaching drive's
//                                reference (as the simulated metrics measure it); a log is not
//                                driven by the follower, so large values mean the robot was
//                                somewhere the maps were not taught
//   on_route_fraction            of the scans with a truth, the share within kOnRoute of the
//                                taught path: where teach and repeat promises to localize
//   localization_error_on_route_m  the localization error over those scans only
//   rejected_fraction            beams rejected as dynamic / beams tested, over every update
//   update_time_ms               thread CPU time of each measurement update
//   real_time_factor             log seconds per CPU second of the whole run
//
// Without a reference only the last three exist; the others are null.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/metrics/localizer_health.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/replay/log_localize.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {

/// m: a log's drive this close to the taught path is on the taught route.
inline constexpr double kOnRoute = 1.0;

/// Per scan of the run.
struct LogLocalizeSeries {
  std::vector<double> driven_m;                ///< along the reference (else the estimate's maps)
  std::vector<double> path_distance_m;         ///< m to the taught route; NaN without truth
  std::vector<double> localization_error_m;    ///< NaN without truth
  std::vector<double> localization_error_rad;  ///< NaN without truth
};

struct LogLocalizeMetrics {
  int scans = 0;
  int updates = 0;
  int switches = 0;
  int maps = 0;
  bool loop = false;
  int laps_completed = 0;
  bool has_truth = false;
  double duration_s = 0.0;  ///< of the log
  Summary localization_error_m;
  Summary localization_error_rad;
  double lost_fraction = kMetricNaN;
  Summary path_distance_m;
  double on_route_fraction = kMetricNaN;
  Summary localization_error_on_route_m;
  double rejected_fraction = kMetricNaN;
  Summary update_time_ms;
  double real_time_factor = kMetricNaN;
  LocalizerHealth localizer;  ///< over the scans, as for a simulated run
};

/// The series of `run` against the teach trace `teach` (its reference X_WR: without one, the
/// localization errors and path distances are NaN).
LogLocalizeSeries ComputeLogSeries(const LogLocalizeResult& run, const TeachTrace& teach);

/// The metrics of `run` in the maps of `bundle`, taught on the drive `teach` (its reference
/// judges the map switches: CountWrongSwitches).
LogLocalizeMetrics ComputeLogMetrics(const LogLocalizeResult& run, const LogLocalizeSeries& series,
                                     const nav::TeachBundle& bundle, const TeachTrace& teach,
                                     const MetricsConfig& config);

nlohmann::json ToJson(const LogLocalizeMetrics& metrics);

/// A warning for a run that never comes within kOnRoute of the taught route (its reference
/// against the teaching drive's): not a repeat of the taught route, so its errors, all off the
/// route, say little about the method. Empty when the run comes back onto the route somewhere,
/// or has no reference to tell.
std::string OffRouteWarning(const LogLocalizeSeries& series);

}  // namespace retrace::bench
