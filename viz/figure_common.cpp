// Pieces of figures.hpp and figure_data.hpp that belong to no single figure.

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "viz/gl_canvas.hpp"
#include "viz/figure_data.hpp"
#include "viz/figures.hpp"

namespace retrace::viz {

Box2 WorldShapes::Bounds() const {
  Box2 b;
  for (const auto& ring : polygons) {
    for (const Vec2& p : ring) b.Extend(p);
  }
  for (const Circle& c : circles) b.Extend(c.center, c.radius);
  for (const auto& [a, c] : segments) {
    b.Extend(a);
    b.Extend(c);
  }
  return b;
}

void FigureOptions::Validate() const {
  if (width < 400 || width > 8000) {
    throw core::ConfigError("width", "figure width must be 400..8000 px, got " + std::to_string(width));
  }
  if (supersample < 1 || supersample > 4) {
    throw core::ConfigError("supersample", "must be 1..4, got " + std::to_string(supersample));
  }
  if (width * supersample > kMaxCanvasSide) {
    throw core::ConfigError("supersample", "width x supersample must not exceed " +
                                               std::to_string(kMaxCanvasSide) + " px");
  }
}

const PanelInfo& FigureInfo::Panel(std::string_view name) const {
  for (const PanelInfo& p : panels) {
    if (p.name == name) return p;
  }
  RETRACE_CHECK(false && "no panel of that name");
  return panels.front();
}

namespace {

// Positions of one run bucketed in square cells, for nearest-point queries within a radius.
class PointBuckets {
 public:
  PointBuckets(const std::vector<core::Pose2>& poses, double cell) : cell_(cell) {
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const Vec2 p = poses[i].translation();
      if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
      buckets_[Key(Cell(p.x()), Cell(p.y()))].push_back(p);
    }
  }

  // The nearest point within `radius` (<= cell) of q, if any.
  bool Nearest(const Vec2& q, double radius, Vec2* out) const {
    double best = radius * radius;
    bool found = false;
    const long long cx = Cell(q.x());
    const long long cy = Cell(q.y());
    for (long long dy = -1; dy <= 1; ++dy) {
      for (long long dx = -1; dx <= 1; ++dx) {
        const auto it = buckets_.find(Key(cx + dx, cy + dy));
        if (it == buckets_.end()) continue;
        for (const Vec2& p : it->second) {
          const double d2 = (p - q).squaredNorm();
          if (d2 <= best) {
            best = d2;
            *out = p;
            found = true;
          }
        }
      }
    }
    return found;
  }

 private:
  long long Cell(double v) const { return static_cast<long long>(std::floor(v / cell_)); }
  static long long Key(long long x, long long y) { return x * 73856093LL ^ y * 19349663LL; }

  double cell_;
  std::unordered_map<long long, std::vector<Vec2>> buckets_;
};

}  // namespace

WidestSpread FindWidestSpread(const std::vector<core::Pose2>& target,
                              const std::vector<Trajectory>& runs, double spacing,
                              double max_offset) {
  WidestSpread best;
  if (target.size() < 2 || runs.size() < 2 || !(spacing > 0.0) || !(max_offset > 0.0)) return best;
  std::vector<PointBuckets> buckets;
  buckets.reserve(runs.size());
  for (const auto& r : runs) buckets.emplace_back(r.poses, max_offset);
  double s_next = 0.0;
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < target.size(); ++i) {
    const Vec2 a = target[i].translation();
    const Vec2 b = target[i + 1].translation();
    const double len = (b - a).norm();
    if (!(len > 1e-9)) continue;
    const Vec2 u = (b - a) / len;
    while (s_next <= s + len) {
      const Vec2 station = a + (s_next - s) * u;
      double lo = std::numeric_limits<double>::infinity();
      double hi = -std::numeric_limits<double>::infinity();
      int seen = 0;
      for (const auto& bk : buckets) {
        Vec2 q;
        if (!bk.Nearest(station, max_offset, &q)) continue;
        const Vec2 d = q - station;
        const double lateral = u.x() * d.y() - u.y() * d.x();  // > 0 left of the path
        lo = std::min(lo, lateral);
        hi = std::max(hi, lateral);
        ++seen;
      }
      if (seen >= 2 && hi - lo > best.spread) {
        best.found = true;
        best.point = station;
        best.arc_length = s_next;
        best.spread = hi - lo;
      }
      s_next += spacing;
    }
    s += len;
  }
  return best;
}

}  // namespace retrace::viz
