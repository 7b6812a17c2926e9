#pragma once
// The scenario's `metrics` section: how the metrics measure a run (bench/metrics/). The engine
// uses the match settings too: its `lost` end condition compares the estimate with the same
// local truth (bench/engine/local_truth.hpp) that the localization metrics use.

#include "core/config.hpp"

namespace retrace::bench {

/// Parameters of the metrics. Lengths in m, times in s.
struct MetricsConfig {
  double station_spacing = 0.5;           ///< m, repeatability stations along the taught path
  double lost_error = 0.5;                ///< m, lost_fraction counts errors above this
  double collision_merge_time = 1.0;      ///< s, same-kind contacts closer than this: one incident
  double collision_driving_speed = 0.05;  ///< m/s towards the contact: the robot drove into it
  double collision_speed_window = 0.2;    ///< s of ground truth the contact speed is taken over
  double match_window = 10.0;            ///< m of arc length behind and ahead of the previous match
  double match_fallback_distance = 3.0;  ///< m, windowed match farther than this: global search
  /// m between the bodies' edges: Hall's intimate and personal zones, and the social metrics'
  /// time to collision counted up to ttc_horizon s (farther in time is no collision course)
  double intimate_zone = 0.45;
  double personal_zone = 1.2;
  double ttc_horizon = 10.0;

  template <class V>
  void Reflect(V& v) {
    v("station_spacing", station_spacing);
    v("lost_error", lost_error);
    v("collision_merge_time", collision_merge_time);
    v("collision_driving_speed", collision_driving_speed);
    v("collision_speed_window", collision_speed_window);
    v("match_window", match_window);
    v("match_fallback_distance", match_fallback_distance);
    v("intimate_zone", intimate_zone);
    v("personal_zone", personal_zone);
    v("ttc_horizon", ttc_horizon);
  }
  /// Throws core::ConfigError naming the key: station_spacing, lost_error, match_window and
  /// match_fallback_distance and collision_speed_window must be > 0, collision_merge_time and
  /// collision_driving_speed >= 0; 0 < intimate_zone < personal_zone <= 5 m (the range of the
  /// pedestrians recorded near the robot), ttc_horizon > 0.
  void Validate() const;
};

}  // namespace retrace::bench
