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

std::size_t LaserScan::CountValid() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < ranges.size(); ++i) n += Valid(i) ? 1 : 0;
  return n;
}

}  // namespace retrace::core
