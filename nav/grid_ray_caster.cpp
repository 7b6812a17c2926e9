#include "nav/grid_ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/check.hpp"

namespace retrace::nav {
namespace {

// Direction components smaller than this are treated as 0 (the ray never crosses a boundary of
// that axis); for a unit direction the neglected drift is below 1e-10 m over 100 m.
constexpr double kTinyComponent = 1e-12;

// Sphere tracing hands over to the exact traversal when a step would gain less than this many
// cells.
constexpr double kMinStepCells = 0.5;

}  // namespace

// One ray, with the closed-form boundary crossings of both axes and its clipped extent.
struct GridRayCaster::Ray {
  double px, py, dx, dy;
  double inv_dx, inv_dy;
  int step_x, step_y;
  double ox, oy, res;
  double range_max;
  double t_lo;   // m, where the ray enters the map (0 when it starts inside)
  double t_end;  // m, min(range_max, where it leaves the map)

  // t (m) at which the ray crosses the grid line x = ox + i * res (only if step_x != 0).
  double TX(int i) const { return (ox + static_cast<double>(i) * res - px) * inv_dx; }
  double TY(int i) const { return (oy + static_cast<double>(i) * res - py) * inv_dy; }

  // The cell index along one axis after every crossing with t' <= t has been made; clamped to
  // [-1, n] (outside either way). `cross` is TX or TY.
  template <class Cross>
  static int AxisCellAt(double t, double p, double d, double o, double r, int step, int n,
                        Cross cross) {
    if (step == 0) {
      const double g = std::floor((p - o) / r);
      return g < 0.0 ? -1 : (g >= n ? n : static_cast<int>(g));
    }
    // Only a guess (the loops below settle the cell by the crossings from any start in
    // [-1, n]), so a product and truncation toward 0 (off by one below the map) will do.
    const double g = (p + t * d - o) * (1.0 / r);
    int i = g < -1.0 ? -1 : (g > n ? n : static_cast<int>(g));
    if (step > 0) {  // cell i spans crossings [cross(i), cross(i + 1))
      while (i >= 0 && cross(i) > t) --i;
      while (i < n && cross(i + 1) <= t) ++i;
    } else {  // cell i spans crossings [cross(i + 1), cross(i))
      while (i < n && cross(i + 1) > t) ++i;
      while (i >= 0 && cross(i) <= t) --i;
    }
    return std::clamp(i, -1, n);
  }
};

GridRayCaster::GridRayCaster(const LikelihoodField& field)
    : field_(&field),
      ox_(field.origin().x()),
      oy_(field.origin().y()),
      res_(field.resolution()),
      width_(field.width()),
      height_(field.height()),
      // A point of a cell is within res/sqrt(2) of its centre, and so is every point of an
      // occupied cell: a step of D - sqrt(2) res from anywhere in a cell whose centre is D from
      // the nearest occupied centre stays clear of every occupied cell. The extra 1e-3 res
      // absorbs rounding of positions and crossings.
      margin_(res_ * (std::sqrt(2.0) + 1e-3)) {
  // The clearance byte of a free cell encodes a lower bound of D, the distance (cells) from its
  // centre to the nearest occupied centre: 1/16-cell steps up to 9 cells, where the sphere steps
  // decide how close to an obstacle the exact traversal takes over, then 2-cell steps up to 263
  // cells. kFineCodes codes v = 1..kFineCodes stand for D >= 1 + (v - 1) / 16.
  constexpr int kFineCodes = 128;
  constexpr double kFinePerCell = 16.0;
  constexpr double kCoarseStart = 1.0 + (kFineCodes - 1) / kFinePerCell + 1.0 / kFinePerCell;
  constexpr double kCoarseCells = 2.0;
  const auto lower_bound_cells = [&](int v) {
    return v <= kFineCodes ? 1.0 + (v - 1) / kFinePerCell
                           : kCoarseStart + (v - kFineCodes - 1) * kCoarseCells;
  };
  const std::vector<float>& d = field.distance();
  const std::vector<std::uint8_t>& occupied = field.occupied();
  // Rows of width + 1 bytes and one extra row, the padding 0 (the lanes of CastMany index the
  // cell of a position up to one cell past the far edges without a bounds check).
  stride_ = static_cast<std::size_t>(width_) + 1;
  clearance_.assign(stride_ * (static_cast<std::size_t>(height_) + 1), 0);
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (occupied[i] != 0) continue;
    // The float distance (m) carries a relative error of about 1e-7, so 1e-4 cells below it is
    // a lower bound of D; D >= 1 on every free cell.
    const double cells = std::max(1.0, static_cast<double>(d[i]) / res_ - 1e-4);
    const double v = cells < kCoarseStart
                         ? 1.0 + std::floor((cells - 1.0) * kFinePerCell)
                         : kFineCodes + 1.0 + std::floor((cells - kCoarseStart) / kCoarseCells);
    const std::size_t row = i / static_cast<std::size_t>(width_);
    clearance_[i + row] = static_cast<std::uint8_t>(std::clamp(v, 1.0, 255.0));
  }
  for (int v = 255; v >= 1; --v) {
    step_[static_cast<std::size_t>(v)] = res_ * lower_bound_cells(v) * (1.0 - 1e-6) - margin_;
    if (step_[static_cast<std::size_t>(v)] >= kMinStepCells * res_) min_step_clearance_ = v;
  }
  // Codes too small for a step get NaN, so that one comparison (t + step < t_end) tells a lane
  // both that it may step and that it stays in range.
  for (int v = 0; v < min_step_clearance_ && v < 256; ++v) {
    step_[static_cast<std::size_t>(v)] = std::numeric_limits<double>::quiet_NaN();
  }
  // Resume sphere tracing from a traversed cell only when it gains at least two cells.
  const double resume_distance = margin_ + 2.0 * res_;
  for (int v = 255; v >= 1; --v) {
    if (res_ * lower_bound_cells(v) >= resume_distance) min_resume_clearance_ = v;
  }
}

inline bool GridRayCaster::Setup(double x, double y, double dx, double dy, double range_max,
                          Ray* ray) const {
  if (width_ == 0 || height_ == 0 || !(range_max >= 0.0)) return false;
  ray->px = x;
  ray->py = y;
  ray->dx = dx;
  ray->dy = dy;
  ray->ox = ox_;
  ray->oy = oy_;
  ray->res = res_;
  ray->range_max = range_max;
  ray->step_x = dx > kTinyComponent ? 1 : (dx < -kTinyComponent ? -1 : 0);
  ray->step_y = dy > kTinyComponent ? 1 : (dy < -kTinyComponent ? -1 : 0);
  RETRACE_CHECK(std::isfinite(x) && std::isfinite(y));
  RETRACE_CHECK(ray->step_x != 0 || ray->step_y != 0);
  ray->inv_dx = ray->step_x != 0 ? 1.0 / dx : 0.0;
  ray->inv_dy = ray->step_y != 0 ? 1.0 / dy : 0.0;

  // Clip to the map: the ray is inside for t in [t_lo, t_exit).
  double t_lo = 0.0;
  double t_exit = std::numeric_limits<double>::infinity();
  if (ray->step_x == 0) {
    if (!(x >= ox_ && x < ox_ + width_ * res_)) return false;
  } else {
    const double a = ray->TX(0), b = ray->TX(width_);
    t_lo = std::max(t_lo, ray->step_x > 0 ? a : b);
    t_exit = std::min(t_exit, ray->step_x > 0 ? b : a);
  }
  if (ray->step_y == 0) {
    if (!(y >= oy_ && y < oy_ + height_ * res_)) return false;
  } else {
    const double a = ray->TY(0), b = ray->TY(height_);
    t_lo = std::max(t_lo, ray->step_y > 0 ? a : b);
    t_exit = std::min(t_exit, ray->step_y > 0 ? b : a);
  }
  if (t_lo > range_max || t_lo >= t_exit) return false;
  ray->t_lo = t_lo;
  ray->t_end = std::min(range_max, t_exit);
  return true;
}

template <bool kSphere>
double GridRayCaster::Trace(const Ray& ray, double t, bool sphere_now) const {
  const double inf = std::numeric_limits<double>::infinity();
  const double x = ray.px, y = ray.py, dx = ray.dx, dy = ray.dy;
  // The reference tests the field's occupancy mask; sphere tracing the clearance bytes
  // (clearance 0 exactly on the occupied cells, so both see the same obstacles).
  const std::uint8_t* occupied = kSphere ? clearance_.data() : field_->occupied().data();
  const std::uint8_t* clearance = clearance_.data();
  const std::size_t w = kSphere ? stride_ : static_cast<std::size_t>(width_);
  const auto tx = [&ray](int i) { return ray.TX(i); };
  const auto ty = [&ray](int i) { return ray.TY(i); };
  const double inv_res = 1.0 / res_;
  const auto is_occupied = [occupied](std::size_t idx) {
    return kSphere ? occupied[idx] == 0 : occupied[idx] != 0;
  };

  while (true) {
    if constexpr (kSphere) {
      // Sphere tracing: every segment [t, t + step] is clear of occupied cells.
      while (sphere_now) {
        const double gx = (x + t * dx - ox_) * inv_res;
        const double gy = (y + t * dy - oy_) * inv_res;
        const int cx = gx < 0.0 ? 0 : (gx >= width_ ? width_ - 1 : static_cast<int>(gx));
        const int cy = gy < 0.0 ? 0 : (gy >= height_ ? height_ - 1 : static_cast<int>(gy));
        const int c = clearance[static_cast<std::size_t>(cy) * w + static_cast<std::size_t>(cx)];
        if (c < min_step_clearance_) break;
        t += step_[static_cast<std::size_t>(c)];
        if (t >= ray.t_end) return kNoHit;
      }
    }
    // Exact traversal from t: the state after every crossing up to t has been made.
    int ix = Ray::AxisCellAt(t, x, dx, ox_, res_, ray.step_x, width_, tx);
    int iy = Ray::AxisCellAt(t, y, dy, oy_, res_, ray.step_y, height_, ty);
    if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return kNoHit;
    double next_x = ray.step_x > 0 ? ray.TX(ix + 1) : (ray.step_x < 0 ? ray.TX(ix) : inf);
    double next_y = ray.step_y > 0 ? ray.TY(iy + 1) : (ray.step_y < 0 ? ray.TY(iy) : inf);
    double t_enter = t;
    // The crossing that leaves cell i is grid line i + 1 going up, i going down.
    const int x_ahead = ray.step_x > 0 ? 1 : 0, y_ahead = ray.step_y > 0 ? 1 : 0;
    while (true) {
      const std::size_t idx = static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix);
      if (is_occupied(idx)) return t_enter;
      if constexpr (kSphere) {
        if (clearance[idx] >= min_resume_clearance_ && t_enter > t) break;
      }
      if constexpr (!kSphere) {  // the reference: the textbook loop
        if (next_x < next_y) {
          t_enter = next_x;
          ix += ray.step_x;
          if (ix < 0 || ix >= width_) return kNoHit;
          next_x = ray.step_x > 0 ? ray.TX(ix + 1) : ray.TX(ix);
        } else {
          t_enter = next_y;
          iy += ray.step_y;
          if (iy < 0 || iy >= height_) return kNoHit;
          next_y = ray.step_y > 0 ? ray.TY(iy + 1) : ray.TY(iy);
        }
        if (t_enter > ray.range_max) return kNoHit;
        continue;
      }
      // Select rather than branch: which boundary comes next is a coin toss for the branch
      // predictor over the few cells left after sphere tracing. The same crossings as the
      // reference's; a zero step never crosses (its next crossing stays +inf).
      const bool cross_x = next_x < next_y;
      t_enter = cross_x ? next_x : next_y;
      ix += cross_x ? ray.step_x : 0;
      iy += cross_x ? 0 : ray.step_y;
      if (static_cast<unsigned>(ix) >= static_cast<unsigned>(width_) ||
          static_cast<unsigned>(iy) >= static_cast<unsigned>(height_)) {
        return kNoHit;
      }
      const double new_x = ray.TX(ix + x_ahead), new_y = ray.TY(iy + y_ahead);
      next_x = cross_x ? new_x : next_x;
      next_y = cross_x ? next_y : new_y;
      if (t_enter > ray.range_max) return kNoHit;
    }
    t = t_enter;  // only reached by sphere tracing resuming in open space
    sphere_now = true;
  }
}

double GridRayCaster::Cast(double x, double y, double dx, double dy, double range_max) const {
  Ray ray;
  return Setup(x, y, dx, dy, range_max, &ray) ? Trace<true>(ray, ray.t_lo, true) : kNoHit;
}

double GridRayCaster::CastDda(double x, double y, double dx, double dy, double range_max) const {
  Ray ray;
  return Setup(x, y, dx, dy, range_max, &ray) ? Trace<false>(ray, ray.t_lo, false) : kNoHit;
}

void GridRayCaster::CastMany(std::span<const double> x, std::span<const double> y,
                             std::span<const double> dx, std::span<const double> dy,
                             double range_max, std::span<double> out) const {
  const std::size_t n = x.size();
  RETRACE_CHECK(y.size() == n && dx.size() == n && dy.size() == n && out.size() == n);
  // The lanes: rays being sphere-traced side by side. Each lane's step is the same safe step
  // as Cast's, from the lane's position in cell units (gx0 + t ux, gy0 + t uy); those differ
  // from Cast's positions by rounding only (1e-12 cells), far inside the 1e-3 cell margin, and
  // the steps' results need not match Cast's: only the final traversal decides the range, and it
  // is exact from any t before which the ray is clear. A lane's position stays within
  // [t_lo, t_end], inside the map up to that rounding, so its cell index needs no clamping: the
  // truncation of a coordinate a hair below 0 is 0, and one a hair past the far edge lands in
  // the padding (code 0: the exact traversal takes over). Rays starting farther than kFarCells
  // from the map, where the rounding could grow to a cell, are traced by Cast instead.
  constexpr double kFarCells = 1 << 20;
  // Structure of arrays, and rounds without a data-dependent branch: every round steps all
  // active lanes, a lane whose step fails (too close to an obstacle, or past t_end) is listed,
  // and the listed lanes are finished and refilled after the round. A ray's end is then no
  // longer a mispredicted branch in the middle of the other lanes' work.
  constexpr int kLanes = 32;
  std::array<double, kLanes> lane_t, lane_t_prev, lane_t_end, lane_gx0, lane_gy0, lane_ux, lane_uy;
  std::array<std::size_t, kLanes> lane_ray;
  std::array<int, kLanes> ended;
  std::array<Ray, kLanes> rays;
  const double inv_res = 1.0 / res_;
  const std::uint8_t* clearance = clearance_.data();
  const double* step = step_.data();
  const std::size_t w = stride_;
  std::size_t next = 0;
  // Loads the next ray that needs tracing into lane k; false when none is left.
  const auto fill = [&](int k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    for (; next < n; ++next) {
      Ray& ray = rays[kk];
      if (!Setup(x[next], y[next], dx[next], dy[next], range_max, &ray)) {
        out[next] = kNoHit;
        continue;
      }
      const double gx0 = (ray.px - ox_) * inv_res, gy0 = (ray.py - oy_) * inv_res;
      if (!(std::abs(gx0) < kFarCells && std::abs(gy0) < kFarCells)) {
        out[next] = Trace<true>(ray, ray.t_lo, true);
        continue;
      }
      lane_t[kk] = ray.t_lo;
      lane_t_end[kk] = ray.t_end;
      lane_gx0[kk] = gx0;
      lane_gy0[kk] = gy0;
      lane_ux[kk] = ray.dx * inv_res;
      lane_uy[kk] = ray.dy * inv_res;
      lane_ray[kk] = next++;
      return true;
    }
    return false;
  };
  int active = 0;
  while (active < kLanes && fill(active)) ++active;
  while (active > 0) {
    int num_ended = 0;
    for (int k = 0; k < active; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const double t = lane_t[kk];
      const int cx = static_cast<int>(lane_gx0[kk] + t * lane_ux[kk]);
      const int cy = static_cast<int>(lane_gy0[kk] + t * lane_uy[kk]);
      const int c = clearance[static_cast<std::size_t>(cy) * w + static_cast<std::size_t>(cx)];
      const double t_next = t + step[c];  // NaN when c is too small to step
      lane_t_prev[kk] = t;
      lane_t[kk] = t_next;
      ended[static_cast<std::size_t>(num_ended)] = k;
      num_ended += t_next < lane_t_end[kk] ? 0 : 1;
    }
    // Finish the listed lanes, highest first, so that moving the last lane into a lane that
    // has no ray left to take only moves lanes that are done with this round.
    for (int e = num_ended - 1; e >= 0; --e) {
      const int k = ended[static_cast<std::size_t>(e)];
      const std::size_t kk = static_cast<std::size_t>(k);
      // Past t_end after a step is no hit; a failed step (NaN) is close to an obstacle: the
      // exact traversal finishes from where the lane stood.
      if (std::isnan(lane_t[kk])) {
        out[lane_ray[kk]] = Trace<true>(rays[kk], lane_t_prev[kk], false);
      } else {
        out[lane_ray[kk]] = kNoHit;
      }
      if (!fill(k)) {  // no ray left: move the last lane here
        --active;
        const std::size_t last = static_cast<std::size_t>(active);
        lane_t[kk] = lane_t[last];
        lane_t_end[kk] = lane_t_end[last];
        lane_gx0[kk] = lane_gx0[last];
        lane_gy0[kk] = lane_gy0[last];
        lane_ux[kk] = lane_ux[last];
        lane_uy[kk] = lane_uy[last];
        lane_ray[kk] = lane_ray[last];
        rays[kk] = rays[last];
      }
    }
  }
}

template double GridRayCaster::Trace<true>(const Ray&, double, bool) const;
template double GridRayCaster::Trace<false>(const Ray&, double, bool) const;

}  // namespace retrace::nav
