#pragma once
// The settings of the log commands (`retrace log-teach`, `log-localize`): `--config FILE` and
// `--set key=value`, with the keys of a scenario file wherever the setting is the same one
// (docs/FORMATS.md), so that a scenario's nav section works on a log unchanged:
//
//   seed                 the synthetic odometry's noise and the localizer's particles
//   modes                log-teach: the map modes to build (default: partial and scan_matched,
//                        and consistent when the log has a reference)
//   route.switch_points  `online` (default), `auto` (from the driven path) or arc lengths (m)
//                        along the driven path from --from; route.revisit_radius, switch_window,
//                        online_drift as in a scenario; route.file and route.points do not apply
//   sim.odometry         the odometry error model of --synthetic-odometry
//   sim.lidar.noise      log-simulate: the simulated LiDAR's noise (the geometry is the log's)
//   sim.unknown_free_path  log-simulate: what the map's unknown cells hold (a world's maps entry)
//   clutter              log-simulate: unmapped clutter beside the log's reference (a scenario's)
//   nav                  the navigation stack (mapper, scan_matcher, localizer, follower ...)
//   playback             initial_sigma_xy, initial_sigma_yaw_deg: the localizer's start
//   metrics              the local-truth matching of the localization error
//
// The robot's geometry comes from the log: the LiDAR mount and its range limits.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "bench/engine/metrics_config.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/trace.hpp"
#include "io/config_override.hpp"
#include "sim/lidar.hpp"
#include "sim/odometry.hpp"

namespace retrace::bench {

/// `sim.lidar` for a log: only the noise applies (`retrace log-simulate`); the geometry is the
/// log's.
struct LogLidarConfig {
  sim::LidarNoiseConfig noise;

  template <class V>
  void Reflect(V& v) {
    v("noise", noise);
  }
};

struct LogSimConfig {
  sim::OdometryConfig odometry;
  LogLidarConfig lidar;
  /// log-simulate: what the world holds in the map's unknown cells, as a world file's maps
  /// entry (sim/world_file.hpp): 0 open, else the mean free path (m) of a ray through them.
  double unknown_free_path = 0.0;

  template <class V>
  void Reflect(V& v) {
    v("odometry", odometry);
    v("lidar", lidar);
    v("unknown_free_path", unknown_free_path);
  }
  void Validate() const;
};

struct LogConfig {
  std::uint64_t seed = 1;
  std::vector<MapMode> modes;  ///< empty: the default above
  RouteConfig route;
  LogSimConfig sim;
  NavConfig nav;
  PlaybackConfig playback;
  MetricsConfig metrics;
  /// log-simulate: unmapped clutter beside the log's reference, as a scenario's, except two
  /// defaults for indoor logs: kinds chair, bin and box (no bikes) and clearance 0.1 m (a
  /// recorded drive passes things closely).
  ClutterConfig clutter;

  LogConfig();

  template <class V>
  void Reflect(V& v) {
    v("seed", seed);
    v("modes", modes);
    v("route", route);
    v("sim", sim);
    v("nav", nav);
    v("playback", playback);
    v("metrics", metrics);
    v("clutter", clutter);
  }
  /// Throws core::ConfigError for a key that does not apply to logs (route.file, route.points,
  /// playback.repeats and the start offsets), a mode listed twice.
  void Validate() const;
};

/// Reads `file` (if any) with `overrides` applied. Throws core::ConfigError / IoError naming the
/// file and key.
LogConfig LoadLogConfig(const std::optional<std::filesystem::path>& file,
                        const std::vector<io::ConfigOverride>& overrides);

}  // namespace retrace::bench
