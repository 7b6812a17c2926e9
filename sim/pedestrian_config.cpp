#include "sim/pedestrian_config.hpp"

#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "core/limits.hpp"

namespace retrace::sim {

void PedestrianGroupConfig::Validate() const {
  core::RequireIntInRange("count", count, 0, core::kMaxPedestrians);
  core::RequirePoint("region_min", region_min);
  core::RequirePoint("region_max", region_max);
  if (!(region_min.x() < region_max.x() && region_min.y() < region_max.y())) {
    throw core::ConfigError("region_max", "must be greater than region_min in both x and y");
  }
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    core::RequirePoint("waypoints[" + std::to_string(i) + "]", waypoints[i]);
  }
  if (mode == PedestrianMode::kLoop && waypoints.size() < 2) {
    throw core::ConfigError("waypoints", "mode 'loop' needs at least 2 waypoints, got " +
                                             std::to_string(waypoints.size()));
  }
  core::RequirePositive("speed_mean", speed_mean);
  core::RequireNonNegative("speed_std", speed_std);
  core::RequirePositive("radius", radius);
}

}  // namespace retrace::sim
