#include "bench/engine/metrics_config.hpp"

#include "bench/engine/trace.hpp"

namespace retrace::bench {

void MetricsConfig::Validate() const {
  core::RequirePositive("station_spacing", station_spacing);
  core::RequirePositive("lost_error", lost_error);
  core::RequireNonNegative("collision_merge_time", collision_merge_time);
  core::RequireNonNegative("collision_driving_speed", collision_driving_speed);
  core::RequirePositive("collision_speed_window", collision_speed_window);
  core::RequirePositive("match_window", match_window);
  core::RequirePositive("match_fallback_distance", match_fallback_distance);
  core::RequirePositive("intimate_zone", intimate_zone);
  core::RequireGreater("personal_zone", personal_zone, "intimate_zone", intimate_zone);
  core::RequireInRange("personal_zone", personal_zone, 0.0, NearbyPedestrian::kNearbyRange);
  core::RequirePositive("ttc_horizon", ttc_horizon);
}

}  // namespace retrace::bench
