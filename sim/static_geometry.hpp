#pragma once
// The static part of a world in frame W: everything the LiDAR sees and the robot and
// pedestrians collide with that never moves. Boxes, polygons and thick polylines are stored as
// closed solid rings; imported ROS maps as merged two-sided edges plus their occupancy mask
// (for inside tests); circles as circles. `segments` holds every boundary edge for ray casting
// and physics.

#include <cstdint>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::sim {

using core::Vec2;

struct Segment {
  Vec2 a;
  Vec2 b;
};

struct Circle {
  Vec2 center;
  double radius = 0.0;
};

/// A moving circle (a pedestrian) as seen by sensors at one instant; id >= 0.
struct DynamicCircle {
  Vec2 center;
  double radius = 0.0;
  int id = 0;
};

struct Aabb {
  Vec2 min{0.0, 0.0};
  Vec2 max{0.0, 0.0};
  bool Contains(const Vec2& p) const {
    return p.x() >= min.x() && p.y() >= min.y() && p.x() <= max.x() && p.y() <= max.y();
  }
};

/// Occupied cells of an imported grid (row 0 = lowest y), for point-inside tests.
struct OccupancyMask {
  int width = 0;
  int height = 0;
  double resolution = 0.05;
  Vec2 origin{0.0, 0.0};  ///< W position of cell (0,0)'s lower-left corner
  std::vector<std::uint8_t> occupied;
  bool IsOccupied(const Vec2& p) const;
};

class StaticGeometry {
 public:
  /// A closed solid polygon (ring of vertices, either winding; first vertex not repeated).
  void AddPolygon(std::vector<Vec2> ring);
  void AddCircle(const Circle& c);
  /// Open two-sided edges without a solid interior (e.g. merged edges of an imported map),
  /// with the mask that says which side is solid.
  void AddEdges(const std::vector<Segment>& edges, OccupancyMask mask);

  const std::vector<Segment>& segments() const { return segments_; }
  const std::vector<Circle>& circles() const { return circles_; }
  const std::vector<std::vector<Vec2>>& polygons() const { return polygons_; }
  const std::vector<OccupancyMask>& masks() const { return masks_; }
  bool empty() const { return segments_.empty() && circles_.empty(); }

  /// True if p lies inside a solid (polygon, circle or occupied imported cell).
  bool IsInside(const Vec2& p) const;
  /// Distance from p to the nearest boundary (segment or circle), brute force; 0 inside a
  /// solid. For many queries use GeometryIndex.
  double Clearance(const Vec2& p) const;
  /// Bounding box of everything (empty geometry: zero box).
  Aabb Bounds() const;

 private:
  std::vector<Segment> segments_;
  std::vector<Circle> circles_;
  std::vector<std::vector<Vec2>> polygons_;
  std::vector<OccupancyMask> masks_;
};

/// Winding-number point-in-polygon test (ring of vertices, either winding).
bool PointInPolygon(const std::vector<Vec2>& ring, const Vec2& p);
/// Whether segments p0-p1 and q0-q1 intersect (touching counts).
bool SegmentsIntersect(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1);

}  // namespace retrace::sim
