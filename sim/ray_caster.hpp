#pragma once
// Exact 2D ray casting against the static geometry (segments and circles), accelerated by a
// uniform grid of buckets walked in ray order (Amanatides-Woo DDA). Hit parameters are computed
// in double precision directly from the primitives, never quantised to the grid: the grid only
// decides which primitives are tested, and it is conservative, so the result is bit-identical
// to testing every primitive (min over RaySegmentHit / RayCircleHit).

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "sim/static_geometry.hpp"

namespace retrace::sim {

/// Ray parameter t >= 0 at which origin + t * dir meets segment s (either side), or +inf if it
/// does not. A ray collinear with the segment does not hit it (it grazes it). With a unit dir, t
/// is the distance (m).
double RaySegmentHit(const Vec2& origin, const Vec2& dir, const Segment& s);

/// Smallest ray parameter t >= 0 at which origin + t * dir meets the boundary of circle c, or
/// +inf. From inside the circle that is the exit point (the boundary is seen from both sides,
/// like a segment). dir must be non-zero.
double RayCircleHit(const Vec2& origin, const Vec2& dir, const Circle& c);

/// Casts rays against a copy of a StaticGeometry's segments and circles.
/// Thread-safe for concurrent casts (all query methods are const and keep no scratch state).
class RayCaster {
 public:
  static constexpr double kNoHit = std::numeric_limits<double>::infinity();

  /// Builds the grid. cell_size (m) > 0 forces the bucket size; 0 picks it from the geometry's
  /// extent and primitive count. Keeps no reference to `geometry`.
  explicit RayCaster(const StaticGeometry& geometry, double cell_size = 0.0);

  /// Closest hit of the ray origin + t * dir (W, m; dir need not be unit, t is in units of |dir|)
  /// with 0 <= t <= max_t, or +inf if there is none. origin and dir must be finite and dir
  /// non-zero (checked).
  double Cast(const Vec2& origin, const Vec2& dir, double max_t) const;

  /// Casts a fan of rays sharing one origin: out[i] = Cast(origin, dirs[i], max_t[i]), bit for
  /// bit. The spans must have equal sizes; out may alias max_t. Where consecutive unit dirs turn
  /// counter-clockwise in small steps (a scanner's beams), runs of them are cast together as
  /// wedges (sim/ray_caster_wedge.cpp). Returns how many rays were cast in wedges.
  std::size_t CastFan(const Vec2& origin, std::span<const Vec2> dirs, std::span<const double> max_t,
                      std::span<double> out) const;

  double cell_size() const { return cell_size_; }
  int grid_width() const { return nx_; }
  int grid_height() const { return ny_; }
  /// Number of (cell, primitive) entries: a measure of the structure's memory.
  std::size_t entry_count() const { return items_.size(); }

 private:
  // One bucket entry, stored inline for locality. Segment: a = (p, q), b - a = (u, v).
  // Circle: centre = (p, q), radius = u, radius^2 = v.
  struct Item {
    double p, q, u, v;
  };
  // Items of cell c: segments in [cells_[c].begin, cells_[c].mid), circles in
  // [cells_[c].mid, cells_[c + 1].begin).
  struct CellRange {
    std::uint32_t begin;
    std::uint32_t mid;
  };

  // Sizes the grid over `box` (m): cell_size_ (the request, or about one primitive per cell),
  // its origin, cell counts and far corner.
  void FitGrid(const Aabb& box, double cell_size, std::size_t primitives);
  // Sets cells_ from the entries per cell (segments, circles), sizes items_ for them all, and
  // sets each cell's next free slot for segments and for circles.
  void LayOutCells(const std::vector<std::uint32_t>& seg_count,
                   const std::vector<std::uint32_t>& circle_count,
                   std::vector<std::uint32_t>* seg_fill, std::vector<std::uint32_t>* circle_fill);

  // The walk of one ray through the grid: its cell, its step per axis (-1, 0, 1), the ray
  // parameter of its next crossing per axis and the parameter between crossings (+inf for an
  // axis it never crosses).
  struct Walk {
    int ix, iy;
    int step_x = 0, step_y = 0;
    double tx = kNoHit, ty = kNoHit, dtx = kNoHit, dty = kNoHit;
  };
  // One axis of a fan: the box's sides minus the origin, and the sides of the origin's cell minus
  // the origin (the numerators of the first crossing going up and going down).
  struct FanAxis {
    double lo = 0.0, hi = 0.0, up = 0.0, down = 0.0;
  };
  struct FanStart {
    double ox = 0.0, oy = 0.0;
    int ix = 0, iy = 0;  // the origin's cell
    FanAxis x, y;
    double far = 0.0;  // distance (m) to the grid's farthest corner
    double eps = 0.0;  // slack (m) for rounding in the distances a wedge compares
  };
  // A wedge casts at least kMinWedge rays (fewer walk faster one by one) and at most kMaxWedge.
  static constexpr std::size_t kMinWedge = 12;
  static constexpr std::size_t kMaxWedge = 64;
  // A wedge is at most this many cells wide where it is valid.
  static constexpr double kWedgeWidth = 0.9;
  // A wedge is made valid to kWedgeDepthFactor times the mean hit distance of the rays before it,
  // and at least kWedgeDepthCells cells deep.
  static constexpr double kWedgeDepthFactor = 1.5;
  static constexpr double kWedgeDepthCells = 4.0;
  // Wedges are tried only while that depth is at most this many cells.
  static constexpr double kWedgeMaxDepthCells = 12.0;
  // One axis of a ray of a fan (direction component u): its slab clips [*t0, *t1]; sets the
  // walk's step, first crossing and spacing along it (h: the cell size). Nothing for u = 0.
  static void StartFanAxis(const FanAxis& a, double u, double h, double* t0, double* t1, int* step,
                           double* t, double* dt);

  double CastFrom(const Vec2& origin, const Vec2& dir, double max_t) const;
  // What the rays of a fan from an origin strictly inside the grid's box share: the origin's
  // cell and the numerators of their slab tests and first crossings.
  FanStart StartFan(double ox, double oy) const;
  // CastFrom for a ray of that fan: the same operations on the shared numerators.
  double CastFromFan(const FanStart& fan, double ux, double uy, double max_t) const;
  // The walk of a ray of that fan from the origin's cell; clips *t1 to the grid's box.
  Walk StartFanWalk(const FanStart& fan, double ux, double uy, double* t1) const;
  // Whether a wedge of kMinWedge rays valid `depth` (m) deep may start at ray `first` of a fan: a
  // cheap guess from the first step, so that fine grids skip WedgeEnd (which decides).
  bool WedgeMayHold(const FanStart& fan, std::span<const Vec2> dirs, std::span<const double> max_t,
                    std::size_t first, double depth) const;
  // The last ray of the wedge that starts at ray `first` of a fan and is valid `depth` (m) deep,
  // or as deep as its rays reach if that is less (sim/ray_caster_wedge.cpp).
  std::size_t WedgeEnd(const FanStart& fan, std::span<const Vec2> dirs,
                       std::span<const double> max_t, std::size_t first, double depth) const;
  // Casts rays [first, last] of a fan as one wedge: out[i] = CastFromFan(fan, dirs[i], max_t[i]).
  void CastWedge(const FanStart& fan, std::span<const Vec2> dirs, std::span<const double> max_t,
                 std::size_t first, std::size_t last, std::span<double> out) const;
  struct WedgeWalk;
  struct WedgeRays;
  struct WedgeSides;
  // Tests the primitives of cell c against the wedge's open rays.
  void TestWedgeCell(std::size_t c, const FanStart& fan, const WedgeSides& side,
                     WedgeRays* rays) const;
  // best[k] = min(best[k], hit of ray k with segment s) for the first n rays, without a branch.
  static void WedgeSegmentHits(double ox, double oy, const Item& s, std::size_t n, const double* ux,
                               const double* uy, double* best);
  // The walk of a wedge's edge ray (direction (ux, uy)) up to ray parameter t1.
  WedgeWalk StartWedgeWalk(const FanStart& fan, double ux, double uy, double t1) const;
  // Steps the walk to its next cell and bounds the distance of the cells ahead.
  void AdvanceWedgeWalk(const FanStart& fan, WedgeWalk* r) const;
  // The walk from w until a hit before the current cell's exit or t1: the nearest hit found
  // (+inf if none), not yet compared with max_t.
  double Traverse(double ox, double oy, double ux, double uy, double t1, Walk w) const;
  // Clips [*t0, *t1] to the grid's box (slab test), setting the inverse direction components
  // of the axes the ray moves along; false when the ray misses the box.
  bool ClipToGrid(double ox, double oy, double ux, double uy, double* t0, double* t1,
                  double* inv_ux, double* inv_uy) const;
  // The walk's state in the cell where the ray enters the grid, at ray parameter t0.
  Walk StartWalk(double ox, double oy, double ux, double uy, double t0, double inv_ux,
                 double inv_uy) const;
  // The smaller of `best` and the nearest hit of the ray with the primitives of cell c.
  double NearestHitInCell(std::size_t c, double ox, double oy, double ux, double uy, double uu,
                          double best) const;

  double cell_size_ = 1.0;
  double inv_cell_size_ = 1.0;
  Vec2 grid_min_{0.0, 0.0};
  Vec2 grid_max_{0.0, 0.0};
  int nx_ = 0;
  int ny_ = 0;
  std::vector<CellRange> cells_;  // nx_ * ny_ + 1 (sentinel)
  std::vector<Item> items_;
};

// The fan's set-up, inline for the loops over its rays (ray_caster.cpp and ray_caster_wedge.cpp).

inline void RayCaster::StartFanAxis(const FanAxis& a, double u, double h, double* t0, double* t1,
                                    int* step, double* t, double* dt) {
  if (u == 0.0) return;
  const double inv = 1.0 / u;
  const double ta = a.lo * inv, tb = a.hi * inv;
  *t0 = std::max(*t0, std::min(ta, tb));
  *t1 = std::min(*t1, std::max(ta, tb));
  *step = u > 0.0 ? 1 : -1;
  *t = (u > 0.0 ? a.up : a.down) * inv;
  *dt = u > 0.0 ? h * inv : -h * inv;
}

inline RayCaster::Walk RayCaster::StartFanWalk(const FanStart& fan, double ux, double uy,
                                               double* t1) const {
  // From inside the box the slabs leave t0 at 0.
  double t0 = 0.0;
  Walk w;
  w.ix = fan.ix;
  w.iy = fan.iy;
  StartFanAxis(fan.x, ux, cell_size_, &t0, t1, &w.step_x, &w.tx, &w.dtx);
  StartFanAxis(fan.y, uy, cell_size_, &t0, t1, &w.step_y, &w.ty, &w.dty);
  return w;
}

}  // namespace retrace::sim
