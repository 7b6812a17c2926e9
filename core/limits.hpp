#pragma once
// The largest inputs retrace accepts (docs/FORMATS.md, "Limits"). Anything larger is refused up
// front with a message that names the key and the limit, before memory is allocated for it or a
// loop runs over it.

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/pose2.hpp"

namespace retrace::core {

/// |x| and |y| of anything placed in a world, a map or a route (m). Box2D computes in float32:
/// 10 km from the origin its resolution is still 1 mm.
inline constexpr double kMaxCoordinate = 10'000.0;
/// A route's length (m).
inline constexpr double kMaxRouteLength = 100'000.0;
/// Points of a route or a taught path.
inline constexpr std::int64_t kMaxRoutePoints = 1'000'000;
/// Cells of an occupancy grid, pixels of a map image: 100 million (400 MB of float cells).
inline constexpr std::int64_t kMaxMapCells = 100'000'000;
/// Pedestrians in a world, over all groups and crossings.
inline constexpr int kMaxPedestrians = 10'000;
/// Beams of a LiDAR scan.
inline constexpr int kMaxBeams = 100'000;

/// Requires a finite coordinate within ±kMaxCoordinate; throws ConfigError(key, ...).
inline void RequireCoordinate(std::string_view key, double v) {
  if (!std::isfinite(v) || std::abs(v) > kMaxCoordinate) {
    throw ConfigError(std::string(key),
                      "must be a finite coordinate within ±" + FormatNumber(kMaxCoordinate) +
                          " m of the origin, got " + FormatNumber(v) + " (retrace's limit)");
  }
}
inline void RequirePoint(std::string_view key, const Vec2& p) {
  RequireCoordinate(key, p.x());
  RequireCoordinate(key, p.y());
}
/// Requires a finite length in (0, 2 kMaxCoordinate] (a size, radius or thickness in a world).
inline void RequireWorldLength(std::string_view key, double v) {
  RequirePositive(key, v);
  if (v > 2.0 * kMaxCoordinate) {
    throw ConfigError(std::string(key), "must be at most " + FormatNumber(2.0 * kMaxCoordinate) +
                                            " m, got " + FormatNumber(v) + " (retrace's limit)");
  }
}

}  // namespace retrace::core
