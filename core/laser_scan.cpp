#include "core/laser_scan.hpp"

#include <cmath>

namespace retrace::core {

bool LaserScan::Valid(std::size_t i) const {
  const float r = ranges[i];
  return std::isfinite(r) && r >= range_min && r <= range_max;
}

bool LaserScan::NoReturn(std::size_t i) const {
  return std::isinf(ranges[i]) && ranges[i] > 0.0f;
}

}  // namespace retrace::core
