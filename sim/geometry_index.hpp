#pragma once
// A uniform bucket grid over the static geometry for proximity queries (pedestrian wall
// repulsion, clearance checks). Ray casting has its own structure in the LiDAR.

#include <cstdint>
#include <vector>

#include "sim/static_geometry.hpp"

namespace retrace::sim {

class GeometryIndex {
 public:
  /// Keeps a reference to `geometry`, which must outlive the index. cell_size in m.
  explicit GeometryIndex(const StaticGeometry& geometry, double cell_size = 1.0);

  /// Appends to `out` the closest point of every segment and circle whose distance to p is
  /// below `radius` (m). Each primitive contributes at most one point.
  void NearbyClosestPoints(const Vec2& p, double radius, std::vector<Vec2>* out) const;
  /// Distance from p to the nearest boundary, capped at max_distance; 0 inside a solid.
  double Clearance(const Vec2& p, double max_distance) const;
  const StaticGeometry& geometry() const { return geometry_; }

 private:
  // Primitive ids: [0, segments) are segments, [segments, segments + circles) are circles.
  void Candidates(const Vec2& p, double radius, std::vector<std::uint32_t>* ids) const;

  const StaticGeometry& geometry_;
  double cell_size_;
  Vec2 origin_;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<std::uint32_t> cell_start_;  // CSR layout: ids of cell c in [start[c], start[c+1])
  std::vector<std::uint32_t> ids_;
};

}  // namespace retrace::sim
