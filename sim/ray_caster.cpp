#include "sim/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.hpp"
#include "sim/ray_hits.hpp"

namespace retrace::sim {

using ray_hits::CircleHit;
using ray_hits::SegmentHit;

namespace {

constexpr double kInf = ray_hits::kMiss;

struct CellSpan {
  int lo;
  int hi;
};

// The margin (m) within which a primitive goes into a cell of size h (m) of a grid over `box`.
// It dwarfs the rounding of the walk's cell boundaries (relative 1e-16 per step), so the walk
// never misses a primitive the exact ray meets; it only costs a rare extra test.
double RayCasterCellMargin(const Aabb& box, double h) {
  double magnitude = 0.0;
  for (const Vec2& p : {box.min, box.max}) {
    magnitude = std::max({magnitude, std::abs(p.x()), std::abs(p.y())});
  }
  return 1e-6 * h + 1e-9 * magnitude;
}

// The cells of the grid (nx x ny cells of size h from grid_min) that a primitive goes into:
// every cell its geometry comes within `margin` (m) of, row by row.
struct RayCasterCover {
  Vec2 grid_min;
  double h, inv_cell_size, margin;
  int nx, ny;

  int Col(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - grid_min.x()) * inv_cell_size)), 0, nx - 1);
  }
  int Row(double y) const {
    return std::clamp(static_cast<int>(std::floor((y - grid_min.y()) * inv_cell_size)), 0, ny - 1);
  }
  // The extent [*lo, *hi] (m) of row iy, widened by the margin.
  void RowBand(int iy, double* lo, double* hi) const {
    *lo = grid_min.y() + iy * h - margin;
    *hi = grid_min.y() + (iy + 1) * h + margin;
  }
  // Calls fn(iy, CellSpan) for each row the segment crosses, with the columns it touches.
  template <class Fn>
  void ForSegment(const Segment& s, Fn&& fn) const {
    const double ylo_all = std::min(s.a.y(), s.b.y()) - margin;
    const double yhi_all = std::max(s.a.y(), s.b.y()) + margin;
    const double dy = s.b.y() - s.a.y();
    for (int iy = Row(ylo_all); iy <= Row(yhi_all); ++iy) {
      double lo = 0.0, hi = 0.0;
      RowBand(iy, &lo, &hi);
      double s0 = 0.0, s1 = 1.0;
      if (dy != 0.0) {
        const double sa = (lo - s.a.y()) / dy;
        const double sb = (hi - s.a.y()) / dy;
        s0 = std::max(0.0, std::min(sa, sb));
        s1 = std::min(1.0, std::max(sa, sb));
        if (s0 > s1) continue;
      }
      const double xa = s.a.x() + s0 * (s.b.x() - s.a.x());
      const double xb = s.a.x() + s1 * (s.b.x() - s.a.x());
      fn(iy, CellSpan{Col(std::min(xa, xb) - margin), Col(std::max(xa, xb) + margin)});
    }
  }
  // Calls fn(iy, CellSpan) for each row the circle (widened by the margin) meets, with the
  // columns it touches.
  template <class Fn>
  void ForCircle(const Circle& c, Fn&& fn) const {
    const double r = c.radius + margin;
    for (int iy = Row(c.center.y() - r); iy <= Row(c.center.y() + r); ++iy) {
      double lo = 0.0, hi = 0.0;
      RowBand(iy, &lo, &hi);
      const double gap = c.center.y() < lo   ? lo - c.center.y()
                         : c.center.y() > hi ? c.center.y() - hi
                                             : 0.0;
      if (gap > r) continue;
      const double half = std::sqrt(r * r - gap * gap);
      fn(iy, CellSpan{Col(c.center.x() - half), Col(c.center.x() + half)});
    }
  }
};

}  // namespace

double RaySegmentHit(const Vec2& origin, const Vec2& dir, const Segment& s) {
  return SegmentHit(origin.x(), origin.y(), dir.x(), dir.y(), s.a.x(), s.a.y(), s.b.x() - s.a.x(),
                    s.b.y() - s.a.y());
}

double RayCircleHit(const Vec2& origin, const Vec2& dir, const Circle& c) {
  const double uu = dir.x() * dir.x() + dir.y() * dir.y();
  return CircleHit(origin.x(), origin.y(), dir.x(), dir.y(), uu, c.center.x(), c.center.y(),
                   c.radius * c.radius);
}

RayCaster::RayCaster(const StaticGeometry& geometry, double cell_size) {
  RETRACE_CHECK(cell_size >= 0.0 && std::isfinite(cell_size));
  const auto& segments = geometry.segments();
  const auto& circles = geometry.circles();
  const std::size_t n = segments.size() + circles.size();
  if (n == 0) {
    cells_.assign(1, CellRange{0, 0});
    return;
  }
  RETRACE_CHECK(n < std::numeric_limits<std::uint32_t>::max() / 64);
  const Aabb box = geometry.Bounds();
  FitGrid(box, cell_size, n);
  // Primitives go into every cell their geometry comes within the margin of.
  const RayCasterCover cover{
      grid_min_, cell_size_, inv_cell_size_, RayCasterCellMargin(box, cell_size_), nx_, ny_};

  // Two passes: count entries per cell, then fill (CSR layout, segments before circles).
  const std::size_t cell_count = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  std::vector<std::uint32_t> seg_count(cell_count, 0), circle_count(cell_count, 0);
  auto counter = [&](std::vector<std::uint32_t>& count) {
    return [&](int iy, CellSpan span) {
      for (int ix = span.lo; ix <= span.hi; ++ix) ++count[static_cast<std::size_t>(iy) * nx_ + ix];
    };
  };
  for (const Segment& s : segments) cover.ForSegment(s, counter(seg_count));
  for (const Circle& c : circles) cover.ForCircle(c, counter(circle_count));
  std::vector<std::uint32_t> seg_fill(cell_count), circle_fill(cell_count);
  LayOutCells(seg_count, circle_count, &seg_fill, &circle_fill);
  for (const Segment& s : segments) {
    const Item item{s.a.x(), s.a.y(), s.b.x() - s.a.x(), s.b.y() - s.a.y()};
    cover.ForSegment(s, [&](int iy, CellSpan span) {
      for (int ix = span.lo; ix <= span.hi; ++ix) {
        items_[seg_fill[static_cast<std::size_t>(iy) * nx_ + ix]++] = item;
      }
    });
  }
  for (const Circle& c : circles) {
    const Item item{c.center.x(), c.center.y(), c.radius, c.radius * c.radius};
    cover.ForCircle(c, [&](int iy, CellSpan span) {
      for (int ix = span.lo; ix <= span.hi; ++ix) {
        items_[circle_fill[static_cast<std::size_t>(iy) * nx_ + ix]++] = item;
      }
    });
  }
}

void RayCaster::FitGrid(const Aabb& box, double cell_size, std::size_t primitives) {
  const double width = box.max.x() - box.min.x();
  const double height = box.max.y() - box.min.y();
  const double extent = std::max({width, height, 1e-3});
  double h = cell_size;
  if (h == 0.0) {
    // About one primitive per cell: walls in rooms then share cells with their few
    // neighbours, and open space costs one cheap step per cell.
    const double area = std::max(width, extent * 1e-3) * std::max(height, extent * 1e-3);
    h = std::sqrt(area / static_cast<double>(primitives));
  }
  // At most ~16M cells whatever the request.
  h = std::max(h, extent / 4096.0);
  cell_size_ = h;
  inv_cell_size_ = 1.0 / h;
  const double pad = 0.01 * h;
  grid_min_ = box.min - Vec2(pad, pad);
  nx_ = std::max(1, static_cast<int>(std::ceil((width + 2.0 * pad) * inv_cell_size_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((height + 2.0 * pad) * inv_cell_size_)));
  grid_max_ = grid_min_ + Vec2(nx_ * h, ny_ * h);
}

void RayCaster::LayOutCells(const std::vector<std::uint32_t>& seg_count,
                            const std::vector<std::uint32_t>& circle_count,
                            std::vector<std::uint32_t>* seg_fill,
                            std::vector<std::uint32_t>* circle_fill) {
  const std::size_t cell_count = seg_count.size();
  cells_.resize(cell_count + 1);
  std::uint64_t total = 0;
  for (std::size_t c = 0; c < cell_count; ++c) {
    cells_[c].begin = static_cast<std::uint32_t>(total);
    cells_[c].mid = static_cast<std::uint32_t>(total + seg_count[c]);
    (*seg_fill)[c] = cells_[c].begin;
    (*circle_fill)[c] = cells_[c].mid;
    total += seg_count[c] + circle_count[c];
    RETRACE_CHECK(total < std::numeric_limits<std::uint32_t>::max());
  }
  cells_[cell_count] =
      CellRange{static_cast<std::uint32_t>(total), static_cast<std::uint32_t>(total)};
  items_.resize(total);
}

double RayCaster::Cast(const Vec2& origin, const Vec2& dir, double max_t) const {
  RETRACE_CHECK(std::isfinite(origin.x()) && std::isfinite(origin.y()));
  RETRACE_CHECK(std::isfinite(dir.x()) && std::isfinite(dir.y()) &&
                (dir.x() != 0.0 || dir.y() != 0.0));
  return CastFrom(origin, dir, max_t);
}

inline bool RayCaster::ClipToGrid(double ox, double oy, double ux, double uy, double* t0,
                                  double* t1, double* inv_ux, double* inv_uy) const {
  if (ux != 0.0) {
    *inv_ux = 1.0 / ux;
    const double ta = (grid_min_.x() - ox) * *inv_ux;
    const double tb = (grid_max_.x() - ox) * *inv_ux;
    *t0 = std::max(*t0, std::min(ta, tb));
    *t1 = std::min(*t1, std::max(ta, tb));
  } else if (ox < grid_min_.x() || ox > grid_max_.x()) {
    return false;
  }
  if (uy != 0.0) {
    *inv_uy = 1.0 / uy;
    const double ta = (grid_min_.y() - oy) * *inv_uy;
    const double tb = (grid_max_.y() - oy) * *inv_uy;
    *t0 = std::max(*t0, std::min(ta, tb));
    *t1 = std::min(*t1, std::max(ta, tb));
  } else if (oy < grid_min_.y() || oy > grid_max_.y()) {
    return false;
  }
  return *t0 <= *t1;
}

inline RayCaster::Walk RayCaster::StartWalk(double ox, double oy, double ux, double uy, double t0,
                                            double inv_ux, double inv_uy) const {
  const double h = cell_size_;
  const double ex = ox + t0 * ux, ey = oy + t0 * uy;
  Walk w;
  w.ix =
      std::clamp(static_cast<int>(std::floor((ex - grid_min_.x()) * inv_cell_size_)), 0, nx_ - 1);
  w.iy =
      std::clamp(static_cast<int>(std::floor((ey - grid_min_.y()) * inv_cell_size_)), 0, ny_ - 1);
  if (ux > 0.0) {
    w.step_x = 1;
    w.tx = (grid_min_.x() + (w.ix + 1) * h - ox) * inv_ux;
    w.dtx = h * inv_ux;
  } else if (ux < 0.0) {
    w.step_x = -1;
    w.tx = (grid_min_.x() + w.ix * h - ox) * inv_ux;
    w.dtx = -h * inv_ux;
  }
  if (uy > 0.0) {
    w.step_y = 1;
    w.ty = (grid_min_.y() + (w.iy + 1) * h - oy) * inv_uy;
    w.dty = h * inv_uy;
  } else if (uy < 0.0) {
    w.step_y = -1;
    w.ty = (grid_min_.y() + w.iy * h - oy) * inv_uy;
    w.dty = -h * inv_uy;
  }
  return w;
}

inline double RayCaster::NearestHitInCell(std::size_t c, double ox, double oy, double ux, double uy,
                                          double uu, double best) const {
  const CellRange* cells = cells_.data();
  const Item* items = items_.data();
  const std::uint32_t mid = cells[c].mid;
  const std::uint32_t end = cells[c + 1].begin;
  for (std::uint32_t k = cells[c].begin; k < mid; ++k) {
    const Item& s = items[k];
    const double t = SegmentHit(ox, oy, ux, uy, s.p, s.q, s.u, s.v);
    if (t < best) best = t;
  }
  for (std::uint32_t k = mid; k < end; ++k) {
    const Item& s = items[k];
    const double t = CircleHit(ox, oy, ux, uy, uu, s.p, s.q, s.v);
    if (t < best) best = t;
  }
  return best;
}

RayCaster::FanStart RayCaster::StartFan(double ox, double oy) const {
  // The terms as ClipToGrid and StartWalk compute them; a ray from inside the box starts at
  // t0 = 0, where StartWalk's entry point is the origin itself.
  const double h = cell_size_;
  FanStart f;
  f.ox = ox;
  f.oy = oy;
  f.ix =
      std::clamp(static_cast<int>(std::floor((ox - grid_min_.x()) * inv_cell_size_)), 0, nx_ - 1);
  f.iy =
      std::clamp(static_cast<int>(std::floor((oy - grid_min_.y()) * inv_cell_size_)), 0, ny_ - 1);
  f.x = {grid_min_.x() - ox, grid_max_.x() - ox, grid_min_.x() + (f.ix + 1) * h - ox,
         grid_min_.x() + f.ix * h - ox};
  f.y = {grid_min_.y() - oy, grid_max_.y() - oy, grid_min_.y() + (f.iy + 1) * h - oy,
         grid_min_.y() + f.iy * h - oy};
  const double far_x = std::max(f.x.hi, -f.x.lo), far_y = std::max(f.y.hi, -f.y.lo);
  f.far = std::sqrt(far_x * far_x + far_y * far_y);
  // Twice the margin of the cells' contents, and rounding in distances across the grid.
  const double magnitude = std::max({std::abs(grid_min_.x()), std::abs(grid_min_.y()),
                                     std::abs(grid_max_.x()), std::abs(grid_max_.y())});
  f.eps = 2e-6 * h + 2e-9 * magnitude + 1e-9 * f.far;
  return f;
}

double RayCaster::CastFromFan(const FanStart& fan, double ux, double uy, double max_t) const {
  if (!(max_t >= 0.0)) return kInf;
  double t1 = max_t;
  const Walk w = StartFanWalk(fan, ux, uy, &t1);
  const double best = Traverse(fan.ox, fan.oy, ux, uy, t1, w);
  return best <= max_t ? best : kInf;
}

double RayCaster::CastFrom(const Vec2& origin, const Vec2& dir, double max_t) const {
  if (!(max_t >= 0.0) || nx_ == 0) return kInf;
  const double ox = origin.x(), oy = origin.y();
  const double ux = dir.x(), uy = dir.y();
  // Clip [0, max_t] to the grid's box (slab test).
  double t0 = 0.0, t1 = max_t;
  double inv_ux = 0.0, inv_uy = 0.0;
  if (!ClipToGrid(ox, oy, ux, uy, &t0, &t1, &inv_ux, &inv_uy)) return kInf;
  // Amanatides-Woo walk from the entry cell.
  const double best = Traverse(ox, oy, ux, uy, t1, StartWalk(ox, oy, ux, uy, t0, inv_ux, inv_uy));
  return best <= max_t ? best : kInf;
}

double RayCaster::Traverse(double ox, double oy, double ux, double uy, double t1, Walk w) const {
  const double uu = ux * ux + uy * uy;
  double best = kInf;
  for (;;) {
    const std::size_t c = static_cast<std::size_t>(w.iy) * static_cast<std::size_t>(nx_) +
                          static_cast<std::size_t>(w.ix);
    best = NearestHitInCell(c, ox, oy, ux, uy, uu, best);
    // Every primitive the ray meets before leaving this cell is in this cell or an earlier one.
    const double t_exit = std::min(w.tx, w.ty);
    if (best <= t_exit || t_exit >= t1) break;
    if (w.tx < w.ty) {
      w.ix += w.step_x;
      if (w.ix < 0 || w.ix >= nx_) break;
      w.tx += w.dtx;
    } else {
      w.iy += w.step_y;
      if (w.iy < 0 || w.iy >= ny_) break;
      w.ty += w.dty;
    }
  }
  return best;
}

inline bool RayCaster::WedgeMayHold(const FanStart& fan, std::span<const Vec2> dirs,
                                    std::span<const double> max_t, std::size_t first,
                                    double depth) const {
  // Wedges pay where the rays' hits lie a few cells out; on finer grids each of their rays
  // would cross many cells that the other rays do not.
  if (first + kMinWedge > dirs.size() || depth > kWedgeMaxDepthCells * cell_size_) return false;
  // kMinWedge - 1 steps like the first, at the depth of the first ray (tan k x ~ k tan x).
  const Vec2& a = dirs[first];
  const Vec2& b = dirs[first + 1];
  const double cross = a.x() * b.y() - a.y() * b.x(), dot = a.x() * b.x() + a.y() * b.y();
  const double reach = max_t[first] >= 0.0 ? std::min({max_t[first], fan.far, depth}) : 0.0;
  const double slack = std::sqrt(2.0) * cell_size_;
  return cross > 0.0 && dot > 0.0 &&
         2.0 * (reach + slack) * static_cast<double>(kMinWedge - 1) * cross <=
             kWedgeWidth * cell_size_ * (1.0 + dot);
}

std::size_t RayCaster::CastFan(const Vec2& origin, std::span<const Vec2> dirs,
                               std::span<const double> max_t, std::span<double> out) const {
  RETRACE_CHECK(dirs.size() == max_t.size() && dirs.size() == out.size());
  RETRACE_CHECK(std::isfinite(origin.x()) && std::isfinite(origin.y()));
  const bool inside = nx_ > 0 && origin.x() > grid_min_.x() && origin.x() < grid_max_.x() &&
                      origin.y() > grid_min_.y() && origin.y() < grid_max_.y();
  for (const Vec2& dir : dirs) {
    RETRACE_CHECK(std::isfinite(dir.x()) && std::isfinite(dir.y()) &&
                  (dir.x() != 0.0 || dir.y() != 0.0));
  }
  if (!inside) {
    for (std::size_t i = 0; i < dirs.size(); ++i) out[i] = CastFrom(origin, dirs[i], max_t[i]);
    return 0;
  }
  const FanStart fan = StartFan(origin.x(), origin.y());
  std::size_t in_wedges = 0;
  // How deep the next wedge is made valid (m): first as deep as its rays reach, then a margin past
  // a running mean of the hits before it. A deeper wedge holds fewer rays; rays it leaves open are
  // cast again on their own. Only the speed depends on it, never a range.
  double depth = kNoHit, mean_hit = 0.0;
  bool any_hit = false;
  const auto note = [&](double range) {
    if (!(range < kNoHit)) return;
    mean_hit = any_hit ? mean_hit + 0.125 * (range - mean_hit) : range;
    any_hit = true;
    depth = std::max(kWedgeDepthCells * cell_size_, kWedgeDepthFactor * mean_hit);
  };
  const std::size_t n = dirs.size();
  for (std::size_t i = 0; i < n;) {
    if (WedgeMayHold(fan, dirs, max_t, i, depth)) {
      const std::size_t last = WedgeEnd(fan, dirs, max_t, i, depth);
      if (last - i + 1 >= kMinWedge) {
        CastWedge(fan, dirs, max_t, i, last, out);
        in_wedges += last - i + 1;
        for (std::size_t k = i; k <= last; k += 4) note(out[k]);
        i = last + 1;
        continue;
      }
    }
    // One by one, kMinWedge rays before the next try: on a grid too fine for wedges this loop
    // is all there is.
    const std::size_t end = std::min(n, i + kMinWedge);
    for (std::size_t k = i; k < end; ++k) {
      out[k] = CastFromFan(fan, dirs[k].x(), dirs[k].y(), max_t[k]);
    }
    note(out[end - 1]);
    i = end;
  }
  return in_wedges;
}

}  // namespace retrace::sim
