#include "sim/pedestrian_config.hpp"

#include <cmath>
#include <string>

#include "core/errors.hpp"

namespace retrace::sim {

void PedestrianGroupConfig::Validate() const {
  if (count < 0) throw core::ConfigError("count", "must be >= 0, got " + std::to_string(count));
  if (!region_min.allFinite()) throw core::ConfigError("region_min", "must be finite");
  if (!region_max.allFinite()) throw core::ConfigError("region_max", "must be finite");
  if (!(region_min.x() < region_max.x() && region_min.y() < region_max.y())) {
    throw core::ConfigError("region_max", "must be greater than region_min in both x and y");
  }
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    if (!waypoints[i].allFinite()) {
      throw core::ConfigError("waypoints[" + std::to_string(i) + "]", "must be finite");
    }
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
