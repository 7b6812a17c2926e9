// Wedges of a fan: neighbouring rays of a scan cast together (RayCaster::CastFan).
//
// A wedge is a run of unit rays from one origin, each turned counter-clockwise from the one before,
// narrow enough that its lateral width stays below 0.9 grid cells out to the depth where it is
// valid. Only its two edge rays walk the grid; every cell either of them crosses is tested against
// all the wedge's rays that are still open. That is enough: a cell that meets the wedge cannot
// fit between the edge rays, so one of them crosses it (and with a good part of the cell on
// either side, far above the walk's rounding). A ray is closed once its nearest hit so far lies
// nearer than every cell not yet tested: those lie in the quadrants ahead of the two walks.
//
// Each hit takes the operations of ray_hits::SegmentHit / CircleHit on the operands of a single
// cast (the segment's range checks as masks), and a ray's result is the minimum over a set of
// primitives that holds the nearest one, so the ranges are the single casts' bit for bit. The gain:
// one walk for many rays, and a cell's primitives tested against the rays in one tight loop.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "sim/ray_caster.hpp"
#include "sim/ray_hits.hpp"

namespace retrace::sim {
namespace {

double Square(double x) { return x * x; }

// A direction the wedge may carry: unit within rounding, so that ray parameters are distances.
bool IsWedgeUnit(const Vec2& d) { return std::abs(d.x() * d.x() + d.y() * d.y() - 1.0) <= 1e-12; }

}  // namespace

// The half-planes beyond a wedge's edges (unit directions a and b, counter-clockwise from a by
// less than 90 degrees) and behind its origin, where no ray of the wedge goes. A primitive
// farther than eps (m) inside one of them is not tested: every one of its hits would be +inf.
struct RayCaster::WedgeSides {
  double ax, ay, bx, by, eps;

  // The segment from p to q (relative to the origin).
  bool Outside(double px, double py, double qx, double qy) const {
    const double sx = ax + bx, sy = ay + by;  // along the wedge, |s| > 1
    return (ax * py - ay * px < -eps && ax * qy - ay * qx < -eps) ||
           (bx * py - by * px > eps && bx * qy - by * qx > eps) ||
           (sx * px + sy * py < -eps && sx * qx + sy * qy < -eps);
  }
  // The circle of radius r about c (relative to the origin).
  bool Outside(double cx, double cy, double r) const {
    const double sx = ax + bx, sy = ay + by;
    const double m = r + eps;
    return ax * cy - ay * cx < -m || bx * cy - by * cx > m ||
           sx * cx + sy * cy < -m * std::sqrt(sx * sx + sy * sy);
  }
};

// best[k] = min(best[k], SegmentHit(origin, (ux[k], uy[k]), segment s)) for k < n, without a
// branch: the same operations as ray_hits::SegmentHit, its range checks as masks, so that the
// loop runs as vector code and never mispredicts.
inline void RayCaster::WedgeSegmentHits(double ox, double oy, const Item& s, std::size_t n,
                                        const double* ux, const double* uy, double* best) {
  const double dx = s.u, dy = s.v;
  const double wx = s.p - ox;
  const double wy = s.q - oy;
  const double nt = wx * dy - wy * dx;
  for (std::size_t k = 0; k < n; ++k) {
    const double denom = ux[k] * dy - uy[k] * dx;
    const double ns = wx * uy[k] - wy * ux[k];
    const double t = nt / denom + 0.0;
    const bool ahead = (denom > 0.0) & (nt >= 0.0) & (ns >= 0.0) & (ns <= denom);
    const bool behind = (denom < 0.0) & (nt <= 0.0) & (ns <= 0.0) & (ns >= denom);
    best[k] = ((ahead | behind) & (t < best[k])) ? t : best[k];
  }
}

// The state of one edge ray's walk and how near the cells still ahead of it can be.
struct RayCaster::WedgeWalk {
  Walk w;
  double t1 = 0.0;      // the walk ends where the ray parameter passes t1
  double ahead2 = 0.0;  // squared distance (m^2) from the origin to the cells' quadrant
  double past2 = 0.0;   // squared distance (m^2) of the cells it leaves out past t1
  bool done = false;
};

std::size_t RayCaster::WedgeEnd(const FanStart& fan, std::span<const Vec2> dirs,
                                std::span<const double> max_t, std::size_t first,
                                double depth) const {
  const Vec2& a = dirs[first];
  if (!IsWedgeUnit(a)) return first;
  // The walks go on to reach + a cell's diagonal (+ rounding slack).
  const double slack = std::sqrt(2.0) * cell_size_ + 2.0 * fan.eps;
  const auto reach_of = [&fan](double t) { return t >= 0.0 ? std::min(t, fan.far) : 0.0; };
  double reach = reach_of(max_t[first]);
  std::size_t last = first;
  for (std::size_t j = first + 1; j < dirs.size() && j - first < kMaxWedge; ++j) {
    const Vec2& p = dirs[j - 1];
    const Vec2& d = dirs[j];
    // A counter-clockwise step of less than 90 degrees, and at most 90 degrees in all.
    if (!IsWedgeUnit(d) || !(p.x() * d.y() - p.y() * d.x() > 0.0) ||
        !(p.x() * d.x() + p.y() * d.y() > 0.0)) {
      break;
    }
    const double cross = a.x() * d.y() - a.y() * d.x();
    const double dot = a.x() * d.x() + a.y() * d.y();
    if (!(dot > 0.0)) break;
    const double r = std::max(reach, reach_of(max_t[j]));
    // Width 2 t tan(w / 2) at the end of the walks, tan(w / 2) = sin w / (1 + cos w).
    if (2.0 * (std::min(r, depth) + slack) * cross > kWedgeWidth * cell_size_ * (1.0 + dot)) {
      break;
    }
    reach = r;
    last = j;
  }
  return last;
}

RayCaster::WedgeWalk RayCaster::StartWedgeWalk(const FanStart& fan, double ux, double uy,
                                               double t1) const {
  WedgeWalk r;
  r.t1 = t1;
  r.w = StartFanWalk(fan, ux, uy, &r.t1);
  r.ahead2 = 0.0;  // the origin's own cell
  return r;
}

inline void RayCaster::AdvanceWedgeWalk(const FanStart& fan, WedgeWalk* r) const {
  Walk& w = r->w;
  const double t_exit = std::min(w.tx, w.ty);
  if (t_exit >= r->t1) {
    r->ahead2 = r->past2;
    r->done = true;
    return;
  }
  if (w.tx < w.ty) {
    w.ix += w.step_x;
    r->done = w.ix < 0 || w.ix >= nx_;
    w.tx += w.dtx;
  } else {
    w.iy += w.step_y;
    r->done = w.iy < 0 || w.iy >= ny_;
    w.ty += w.dty;
  }
  if (r->done) {
    r->ahead2 = kNoHit;
    return;
  }
  // The cells ahead have column >= ix when the walk steps right, <= ix when it steps left, ix
  // when it does not step in x; rows likewise.
  const double h = cell_size_;
  const auto gap = [h](int step, int i, double lo_side, double origin) {
    const double lo = lo_side + i * h - origin;  // the cell's low side minus the origin
    const double hi = lo_side + (i + 1) * h - origin;
    if (step > 0) return std::max(0.0, lo);
    if (step < 0) return std::max(0.0, -hi);
    return std::max({0.0, lo, -hi});
  };
  const double dx = gap(w.step_x, w.ix, grid_min_.x(), fan.ox);
  const double dy = gap(w.step_y, w.iy, grid_min_.y(), fan.oy);
  r->ahead2 = dx * dx + dy * dy;
}

// The open rays of a wedge, packed at the front: their direction, nearest hit so far, limit and
// index in the fan; the arrays are left uninitialised, only the first `open` entries are read.
struct RayCaster::WedgeRays {
  std::array<double, kMaxWedge> ux, uy, uu, best, limit;
  std::array<std::uint32_t, kMaxWedge> index;
  std::size_t open = 0;
  // The nearest hit and the shortest limit of the open rays: no ray closes before one of them
  // is nearer than the cells ahead.
  double nearest = kNoHit, shortest = kNoHit;

  void Add(const Vec2& d, double max_t, std::size_t i) {
    ux[open] = d.x();
    uy[open] = d.y();
    uu[open] = d.x() * d.x() + d.y() * d.y();
    best[open] = kNoHit;
    limit[open] = max_t;
    index[open] = static_cast<std::uint32_t>(i);
    shortest = std::min(shortest, max_t);
    ++open;
  }
  // Writes the result of every open ray whose hit is nearer than sqrt(near2) - eps (compared as
  // squares, eps >> their rounding), or whose limit is, and drops it.
  void CloseNearerThan(double near2, double eps, std::span<double> out) {
    if (!(Square(nearest + eps) <= near2 || Square(shortest + eps) < near2)) return;
    for (std::size_t k = 0; k < open;) {
      if (!(Square(best[k] + eps) <= near2 || Square(limit[k] + eps) < near2)) {
        ++k;
        continue;
      }
      out[index[k]] = best[k] <= limit[k] ? best[k] : kNoHit;
      --open;
      ux[k] = ux[open];
      uy[k] = uy[open];
      uu[k] = uu[open];
      best[k] = best[open];
      limit[k] = limit[open];
      index[k] = index[open];
    }
    nearest = *std::min_element(best.begin(), best.begin() + open);
    shortest = *std::min_element(limit.begin(), limit.begin() + open);
  }
};

void RayCaster::TestWedgeCell(std::size_t c, const FanStart& fan, const WedgeSides& side,
                              WedgeRays* rays) const {
  const double ox = fan.ox, oy = fan.oy;
  const std::uint32_t begin = cells_[c].begin, mid = cells_[c].mid, end = cells_[c + 1].begin;
  const std::size_t n = rays->open;
  for (std::uint32_t e = begin; e < mid; ++e) {
    const Item& s = items_[e];
    const double px = s.p - ox, py = s.q - oy;
    if (side.Outside(px, py, px + s.u, py + s.v)) continue;
    WedgeSegmentHits(ox, oy, s, n, rays->ux.data(), rays->uy.data(), rays->best.data());
  }
  if (begin < mid) rays->nearest = *std::min_element(rays->best.begin(), rays->best.begin() + n);
  for (std::uint32_t e = mid; e < end; ++e) {
    const Item& s = items_[e];
    if (side.Outside(s.p - ox, s.q - oy, s.u)) continue;
    for (std::size_t k = 0; k < n; ++k) {
      const double t =
          ray_hits::CircleHit(ox, oy, rays->ux[k], rays->uy[k], rays->uu[k], s.p, s.q, s.v);
      rays->best[k] = std::min(t, rays->best[k]);
      rays->nearest = std::min(rays->nearest, rays->best[k]);
    }
  }
}

void RayCaster::CastWedge(const FanStart& fan, std::span<const Vec2> dirs,
                          std::span<const double> max_t, std::size_t first, std::size_t last,
                          std::span<double> out) const {
  WedgeRays rays;
  double reach = 0.0;
  for (std::size_t i = first; i <= last; ++i) {
    if (max_t[i] >= 0.0) {
      rays.Add(dirs[i], max_t[i], i);
      reach = std::max(reach, std::min(max_t[i], fan.far));
    } else {
      out[i] = kNoHit;
    }
  }
  if (rays.open == 0) return;

  // The wedge holds out to `valid` (m), where its width reaches kWedgeWidth cells less a cell's
  // diagonal; its walks stop a diagonal past min(reach, valid), and every cell left out lies
  // farther than that.
  const double eps = fan.eps;
  const double diagonal = std::sqrt(2.0) * cell_size_;
  const Vec2& a = dirs[first];
  const Vec2& b = dirs[last];
  const double cross = a.x() * b.y() - a.y() * b.x(), dot = a.x() * b.x() + a.y() * b.y();
  const double valid =
      kWedgeWidth * cell_size_ * (1.0 + dot) / (2.0 * cross) - diagonal - 2.0 * eps;
  const double stop = std::min(reach, valid);
  const double t1 = stop + diagonal + 3.0 * eps;
  std::array<WedgeWalk, 2> walks = {StartWedgeWalk(fan, a.x(), a.y(), t1),
                                    StartWedgeWalk(fan, b.x(), b.y(), t1)};
  for (WedgeWalk& w : walks) w.past2 = Square(stop + 2.0 * eps);
  const WedgeSides side{a.x(), a.y(), b.x(), b.y(), eps};
  // The last cells tested: the two walks cross many cells both.
  std::array<std::size_t, 4> recent;
  recent.fill(cells_.size());
  std::size_t next_recent = 0;
  for (;;) {
    // Every cell not yet tested that meets the wedge lies at least sqrt(near2) - eps out.
    rays.CloseNearerThan(std::min(walks[0].ahead2, walks[1].ahead2), eps, out);
    if (rays.open == 0) return;
    WedgeWalk& r = walks[0].ahead2 <= walks[1].ahead2 ? walks[0] : walks[1];
    if (r.done) break;  // both are: the rays still open reach past the wedge's valid depth
    const std::size_t c = static_cast<std::size_t>(r.w.iy) * static_cast<std::size_t>(nx_) +
                          static_cast<std::size_t>(r.w.ix);
    if (std::find(recent.begin(), recent.end(), c) == recent.end()) {
      recent[next_recent++ % recent.size()] = c;
      TestWedgeCell(c, fan, side, &rays);
    }
    AdvanceWedgeWalk(fan, &r);
  }
  // Rays beyond `valid` walk on their own, from the origin.
  for (std::size_t k = 0; k < rays.open; ++k) {
    out[rays.index[k]] = CastFromFan(fan, rays.ux[k], rays.uy[k], rays.limit[k]);
  }
}

}  // namespace retrace::sim
