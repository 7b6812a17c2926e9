#include "sim/geometry_index.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"
#include "core/segment.hpp"

namespace retrace::sim {

namespace {

// Buckets of the index at most: a world of 20 km (core::kMaxCoordinate both ways) gets 20 m
// cells, not 400 million of 1 m.
constexpr double kMaxCells = 1 << 20;

}  // namespace

GeometryIndex::GeometryIndex(const StaticGeometry& geometry, double cell_size)
    : geometry_(geometry), cell_size_(cell_size) {
  RETRACE_CHECK(cell_size > 0.0);
  const Aabb box = geometry.Bounds();
  // World files and maps are checked against core::kMaxCoordinate; this keeps the index finite
  // for geometry built any other way.
  RETRACE_CHECK(box.min.allFinite() && box.max.allFinite());
  const double area =
      (box.max.x() - box.min.x() + 2.0 * cell_size) * (box.max.y() - box.min.y() + 2.0 * cell_size);
  cell_size_ = cell_size = std::max(cell_size, std::sqrt(area / kMaxCells));
  origin_ = box.min - Vec2(cell_size, cell_size);
  nx_ = std::max(1, static_cast<int>(std::ceil((box.max.x() - origin_.x()) / cell_size)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((box.max.y() - origin_.y()) / cell_size)) + 1);
  const auto& segs = geometry.segments();
  const auto& circles = geometry.circles();
  const std::size_t n_cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  std::vector<std::vector<std::uint32_t>> buckets(n_cells);
  auto add_box = [&](std::uint32_t id, Vec2 lo, Vec2 hi) {
    const int x0 =
        std::clamp(static_cast<int>(std::floor((lo.x() - origin_.x()) / cell_size)), 0, nx_ - 1);
    const int y0 =
        std::clamp(static_cast<int>(std::floor((lo.y() - origin_.y()) / cell_size)), 0, ny_ - 1);
    const int x1 =
        std::clamp(static_cast<int>(std::floor((hi.x() - origin_.x()) / cell_size)), 0, nx_ - 1);
    const int y1 =
        std::clamp(static_cast<int>(std::floor((hi.y() - origin_.y()) / cell_size)), 0, ny_ - 1);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) buckets[static_cast<std::size_t>(y) * nx_ + x].push_back(id);
    }
  };
  for (std::uint32_t i = 0; i < segs.size(); ++i) {
    // Long diagonal segments are rare in worlds; their bounding box is a fine superset.
    add_box(i, segs[i].a.cwiseMin(segs[i].b), segs[i].a.cwiseMax(segs[i].b));
  }
  for (std::uint32_t i = 0; i < circles.size(); ++i) {
    const Vec2 r(circles[i].radius, circles[i].radius);
    add_box(static_cast<std::uint32_t>(segs.size()) + i, circles[i].center - r,
            circles[i].center + r);
  }
  cell_start_.resize(n_cells + 1, 0);
  for (std::size_t c = 0; c < n_cells; ++c) {
    cell_start_[c + 1] = cell_start_[c] + static_cast<std::uint32_t>(buckets[c].size());
  }
  ids_.reserve(cell_start_.back());
  for (auto& b : buckets) ids_.insert(ids_.end(), b.begin(), b.end());
}

void GeometryIndex::Candidates(const Vec2& p, double radius,
                               std::vector<std::uint32_t>* ids) const {
  const int x0 = std::clamp(
      static_cast<int>(std::floor((p.x() - radius - origin_.x()) / cell_size_)), 0, nx_ - 1);
  const int y0 = std::clamp(
      static_cast<int>(std::floor((p.y() - radius - origin_.y()) / cell_size_)), 0, ny_ - 1);
  const int x1 = std::clamp(
      static_cast<int>(std::floor((p.x() + radius - origin_.x()) / cell_size_)), 0, nx_ - 1);
  const int y1 = std::clamp(
      static_cast<int>(std::floor((p.y() + radius - origin_.y()) / cell_size_)), 0, ny_ - 1);
  ids->clear();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
      ids->insert(ids->end(), ids_.begin() + cell_start_[c], ids_.begin() + cell_start_[c + 1]);
    }
  }
  std::sort(ids->begin(), ids->end());
  ids->erase(std::unique(ids->begin(), ids->end()), ids->end());
}

void GeometryIndex::NearbyClosestPoints(const Vec2& p, double radius,
                                        std::vector<Vec2>* out) const {
  thread_local std::vector<std::uint32_t> ids;
  Candidates(p, radius, &ids);
  const auto& segs = geometry_.segments();
  const auto& circles = geometry_.circles();
  for (std::uint32_t id : ids) {
    if (id < segs.size()) {
      const Vec2 q = core::ClosestPointOnSegment(p, segs[id].a, segs[id].b);
      if ((q - p).squaredNorm() < radius * radius) out->push_back(q);
    } else {
      const Circle& c = circles[id - segs.size()];
      const Vec2 d = p - c.center;
      const double n = d.norm();
      if (n - c.radius < radius) {
        out->push_back(n > 0.0 ? Vec2(c.center + d * (c.radius / n))
                               : Vec2(c.center + Vec2(c.radius, 0.0)));
      }
    }
  }
}

double GeometryIndex::Clearance(const Vec2& p, double max_distance) const {
  if (geometry_.IsInside(p)) return 0.0;
  thread_local std::vector<Vec2> points;
  points.clear();
  NearbyClosestPoints(p, max_distance, &points);
  double best = max_distance;
  for (const Vec2& q : points) best = std::min(best, (q - p).norm());
  return best;
}

}  // namespace retrace::sim
