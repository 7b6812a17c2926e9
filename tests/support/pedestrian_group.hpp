#pragma once
// A pedestrian group config in one line, for the sim tests.

#include <utility>
#include <vector>

#include "sim/pedestrian_config.hpp"

namespace retrace::testing {

inline sim::PedestrianGroupConfig Group(int count, core::Vec2 lo, core::Vec2 hi,
                                        sim::PedestrianMode mode = sim::PedestrianMode::kWander,
                                        std::vector<core::Vec2> waypoints = {}) {
  sim::PedestrianGroupConfig g;
  g.count = count;
  g.region_min = lo;
  g.region_max = hi;
  g.mode = mode;
  g.waypoints = std::move(waypoints);
  return g;
}

}  // namespace retrace::testing
