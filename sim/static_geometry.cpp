#include "sim/static_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.hpp"
#include "core/segment.hpp"

namespace retrace::sim {

bool OccupancyMask::IsOccupied(const Vec2& p) const {
  const int cx = static_cast<int>(std::floor((p.x() - origin.x()) / resolution));
  const int cy = static_cast<int>(std::floor((p.y() - origin.y()) / resolution));
  if (cx < 0 || cy < 0 || cx >= width || cy >= height) return false;
  return occupied[static_cast<std::size_t>(cy) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(cx)] != 0;
}

void StaticGeometry::AddPolygon(std::vector<Vec2> ring) {
  RETRACE_CHECK(ring.size() >= 3);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    segments_.push_back({ring[i], ring[(i + 1) % ring.size()]});
  }
  polygons_.push_back(std::move(ring));
}

void StaticGeometry::AddCircle(const Circle& c) {
  RETRACE_CHECK(c.radius > 0.0);
  circles_.push_back(c);
}

void StaticGeometry::AddEdges(const std::vector<Segment>& edges, OccupancyMask mask) {
  segments_.insert(segments_.end(), edges.begin(), edges.end());
  masks_.push_back(std::move(mask));
}

bool StaticGeometry::IsInside(const Vec2& p) const {
  for (const auto& c : circles_) {
    if ((p - c.center).squaredNorm() < c.radius * c.radius) return true;
  }
  for (const auto& ring : polygons_) {
    if (PointInPolygon(ring, p)) return true;
  }
  for (const auto& m : masks_) {
    if (m.IsOccupied(p)) return true;
  }
  return false;
}

double StaticGeometry::Clearance(const Vec2& p) const {
  if (IsInside(p)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : segments_) best = std::min(best, core::SegmentDistance(p, s.a, s.b));
  for (const auto& c : circles_) best = std::min(best, (p - c.center).norm() - c.radius);
  return best;
}

Aabb StaticGeometry::Bounds() const {
  if (empty()) return {};
  Aabb box{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()},
           {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}};
  auto grow = [&](const Vec2& p) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  };
  for (const auto& s : segments_) {
    grow(s.a);
    grow(s.b);
  }
  for (const auto& c : circles_) {
    grow(c.center - Vec2(c.radius, c.radius));
    grow(c.center + Vec2(c.radius, c.radius));
  }
  return box;
}

bool PointInPolygon(const std::vector<Vec2>& ring, const Vec2& p) {
  int winding = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2& a = ring[i];
    const Vec2& b = ring[(i + 1) % ring.size()];
    const double cross = (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && cross > 0.0) ++winding;
    } else {
      if (b.y() <= p.y() && cross < 0.0) --winding;
    }
  }
  return winding != 0;
}

bool SegmentsIntersect(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  auto orient = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    const double v = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    return (v > 0.0) - (v < 0.0);
  };
  auto on_segment = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
           std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
  };
  const int o1 = orient(p0, p1, q0), o2 = orient(p0, p1, q1);
  const int o3 = orient(q0, q1, p0), o4 = orient(q0, q1, p1);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && on_segment(p0, p1, q0)) return true;
  if (o2 == 0 && on_segment(p0, p1, q1)) return true;
  if (o3 == 0 && on_segment(q0, q1, p0)) return true;
  if (o4 == 0 && on_segment(q0, q1, p1)) return true;
  return false;
}

}  // namespace retrace::sim
