#pragma once

#include <cstddef>
#include <vector>

namespace retrace::core {

/// One planar LiDAR sweep in the sensor frame L. Beam i points at
/// angle_min + i * angle_increment (rad, counter-clockwise, 0 along L's x axis).
/// A beam with no return reads +inf (REP-117); a range outside [range_min, range_max] or a NaN
/// is invalid.
struct LaserScan {
  double stamp = 0.0;            ///< acquisition time (s)
  double angle_min = 0.0;        ///< rad
  double angle_increment = 0.0;  ///< rad
  double range_min = 0.0;        ///< m
  double range_max = 0.0;        ///< m
  std::vector<float> ranges;     ///< m, +inf for no return

  std::size_t size() const { return ranges.size(); }
  double Angle(std::size_t i) const { return angle_min + static_cast<double>(i) * angle_increment; }
  /// True if beam i returned a usable range inside [range_min, range_max].
  bool Valid(std::size_t i) const;
  /// True if beam i reported no return (+inf): free space up to range_max along it.
  bool NoReturn(std::size_t i) const;
};

}  // namespace retrace::core
