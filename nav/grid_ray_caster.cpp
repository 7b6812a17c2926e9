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

}  // namespace

// One ray, with the closed-form boundary crossings of both axes.
struct GridRayCaster::Ray {
  double px, py, dx, dy;
  double inv_dx, inv_dy;
  int step_x, step_y;
  double ox, oy, res;

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
    // Only a guess (the loops below settle the cell by the crossings), so a product will do.
    const double g = std::floor((p + t * d - o) * (1.0 / r));
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
  const std::vector<float>& d = field.distance();
  const std::vector<std::uint8_t>& occupied = field.occupied();
  clearance_.resize(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    // A lower bound of the distance in cells: floor never rounds up, and a distance to an
    // occupied centre is the root of an integer, never within float error below an integer
    // it does not equal.
    const double cells = static_cast<double>(d[i]) / res_;
    clearance_[i] = occupied[i] != 0 ? 0
                                     : static_cast<std::uint8_t>(std::clamp(std::floor(cells), 1.0, 255.0));
  }
}

double GridRayCaster::Cast(double x, double y, double dx, double dy, double range_max) const {
  return CastImpl<true>(x, y, dx, dy, range_max);
}

double GridRayCaster::CastDda(double x, double y, double dx, double dy, double range_max) const {
  return CastImpl<false>(x, y, dx, dy, range_max);
}

template <bool kSphere>
double GridRayCaster::CastImpl(double x, double y, double dx, double dy, double range_max) const {
  if (width_ == 0 || height_ == 0 || !(range_max >= 0.0)) return kNoHit;
  Ray ray{};
  ray.px = x;
  ray.py = y;
  ray.dx = dx;
  ray.dy = dy;
  ray.ox = ox_;
  ray.oy = oy_;
  ray.res = res_;
  ray.step_x = dx > kTinyComponent ? 1 : (dx < -kTinyComponent ? -1 : 0);
  ray.step_y = dy > kTinyComponent ? 1 : (dy < -kTinyComponent ? -1 : 0);
  RETRACE_CHECK(std::isfinite(x) && std::isfinite(y));
  RETRACE_CHECK(ray.step_x != 0 || ray.step_y != 0);
  ray.inv_dx = ray.step_x != 0 ? 1.0 / dx : 0.0;
  ray.inv_dy = ray.step_y != 0 ? 1.0 / dy : 0.0;

  // Clip to the map: the ray is inside for t in [t_lo, t_exit).
  const double inf = std::numeric_limits<double>::infinity();
  double t_lo = 0.0;
  double t_exit = inf;
  if (ray.step_x == 0) {
    if (!(x >= ox_ && x < ox_ + width_ * res_)) return kNoHit;
  } else {
    const double a = ray.TX(0), b = ray.TX(width_);
    t_lo = std::max(t_lo, ray.step_x > 0 ? a : b);
    t_exit = std::min(t_exit, ray.step_x > 0 ? b : a);
  }
  if (ray.step_y == 0) {
    if (!(y >= oy_ && y < oy_ + height_ * res_)) return kNoHit;
  } else {
    const double a = ray.TY(0), b = ray.TY(height_);
    t_lo = std::max(t_lo, ray.step_y > 0 ? a : b);
    t_exit = std::min(t_exit, ray.step_y > 0 ? b : a);
  }
  if (t_lo > range_max || t_lo >= t_exit) return kNoHit;
  const double t_end = std::min(range_max, t_exit);

  // The reference tests the field's occupancy mask; sphere tracing the clearance bytes
  // (clearance 0 exactly on the occupied cells, so both see the same obstacles).
  const std::uint8_t* occupied = kSphere ? clearance_.data() : field_->occupied().data();
  const std::uint8_t* clearance = clearance_.data();
  const std::size_t w = static_cast<std::size_t>(width_);
  const auto tx = [&ray](int i) { return ray.TX(i); };
  const auto ty = [&ray](int i) { return ray.TY(i); };
  const double inv_res = 1.0 / res_;
  // Resume sphere tracing from a traversed cell only when it gains at least two cells.
  const double resume_distance = margin_ + 2.0 * res_;
  const auto is_occupied = [occupied](std::size_t idx) {
    return kSphere ? occupied[idx] == 0 : occupied[idx] != 0;
  };

  double t = t_lo;
  while (true) {
    if constexpr (kSphere) {
      // Sphere tracing: every segment [t, t + step] is clear of occupied cells.
      while (true) {
        const double gx = (x + t * dx - ox_) * inv_res;
        const double gy = (y + t * dy - oy_) * inv_res;
        const int cx = gx < 0.0 ? 0 : (gx >= width_ ? width_ - 1 : static_cast<int>(gx));
        const int cy = gy < 0.0 ? 0 : (gy >= height_ ? height_ - 1 : static_cast<int>(gy));
        const double d =
            res_ * clearance[static_cast<std::size_t>(cy) * w + static_cast<std::size_t>(cx)];
        const double step = d * (1.0 - 1e-6) - margin_;
        if (!(step >= res_)) break;
        t += step;
        if (t >= t_end) return kNoHit;
      }
    }
    // Exact traversal from t: the state after every crossing up to t has been made.
    int ix = Ray::AxisCellAt(t, x, dx, ox_, res_, ray.step_x, width_, tx);
    int iy = Ray::AxisCellAt(t, y, dy, oy_, res_, ray.step_y, height_, ty);
    if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return kNoHit;
    double next_x = ray.step_x > 0 ? ray.TX(ix + 1) : (ray.step_x < 0 ? ray.TX(ix) : inf);
    double next_y = ray.step_y > 0 ? ray.TY(iy + 1) : (ray.step_y < 0 ? ray.TY(iy) : inf);
    double t_enter = t;
    while (true) {
      const std::size_t idx = static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix);
      if (is_occupied(idx)) return t_enter;
      if constexpr (kSphere) {
        if (res_ * clearance[idx] >= resume_distance && t_enter > t) break;
      }
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
      if (t_enter > range_max) return kNoHit;
    }
    t = t_enter;  // only reached by sphere tracing resuming in open space
  }
}

template double GridRayCaster::CastImpl<true>(double, double, double, double, double) const;
template double GridRayCaster::CastImpl<false>(double, double, double, double, double) const;

}  // namespace retrace::nav
