#include "nav/grid_ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/check.hpp"

namespace retrace::nav {
namespace {

// Direction components smaller than this are treated as 0 (the ray never crosses a boundary of
// that axis); for a unit direction the neglected drift is below 1e-10 m over 100 m.
constexpr double kTinyComponent = 1e-12;

// Sphere tracing hands over to the exact traversal when a step would gain less than this many
// cells.
constexpr double kMinStepCells = 0.5;

// CastMany finds a common clear start for groups of this many consecutive rays.
constexpr std::size_t kBundle = 32;

// The ray parameter t (m) at which a ray from p (m) with inverse direction component inv (1/m)
// crosses the grid line o + i res of one axis. The one formula every traversal uses, so that
// all of them cross at the same numbers (CastMany takes o + i res from a table of the same
// values).
double Crossing(double o, int i, double res, double p, double inv) {
  return (o + static_cast<double>(i) * res - p) * inv;
}

// The cell index along one axis after every crossing with t' <= t has been made, for a ray from
// p with inverse direction component inv (step its sign), from a guess of the position at t
// (cells); clamped to [-1, n] (outside either way).
int AxisCellAt(double t, double guess, double p, double inv, double o, double r, int step, int n) {
  if (step == 0) {
    const double g = std::floor((p - o) / r);
    return g < 0.0 ? -1 : (g >= n ? n : static_cast<int>(g));
  }
  const auto cross = [&](int i) { return Crossing(o, i, r, p, inv); };
  // `guess` (cells) is only a guess: the loops below settle the cell by the crossings from any
  // start in [-1, n], so truncation toward 0 (off by one below the map) will do.
  int i = guess < -1.0 ? -1 : (guess > n ? n : static_cast<int>(guess));
  if (step > 0) {  // cell i spans crossings [cross(i), cross(i + 1))
    while (i >= 0 && cross(i) > t) --i;
    while (i < n && cross(i + 1) <= t) ++i;
  } else {  // cell i spans crossings [cross(i + 1), cross(i))
    while (i < n && cross(i + 1) > t) ++i;
    while (i >= 0 && cross(i) <= t) --i;
  }
  return std::clamp(i, -1, n);
}

// The next crossing (m) of one axis for a ray in cell i: the grid line that leaves the cell,
// i + 1 going up, i going down; +inf when the ray never crosses that axis.
double NextCrossing(int i, double o, double res, double p, double inv, int step) {
  if (step == 0) return std::numeric_limits<double>::infinity();
  return Crossing(o, step > 0 ? i + 1 : i, res, p, inv);
}

// Narrows [t_lo, t_exit) (m) to where the ray is inside the map's extent [o, o + n res) along
// one axis; false when a ray parallel to that axis lies outside it.
bool ClipAxis(double p, double inv, int step, double o, double res, int n, double* t_lo,
              double* t_exit) {
  if (step == 0) return p >= o && p < o + n * res;
  const double a = Crossing(o, 0, res, p, inv), b = Crossing(o, n, res, p, inv);
  *t_lo = std::max(*t_lo, step > 0 ? a : b);
  *t_exit = std::min(*t_exit, step > 0 ? b : a);
  return true;
}

// {1 / a, 1 / b}, in one two-wide division where the target has SSE2 (x86-64 always has):
// the divider limits CastMany's setup. Bit for bit the two scalar divisions.
std::array<double, 2> Inverses(double a, double b) {
#if defined(__SSE2__)
  std::array<double, 2> q;
  _mm_storeu_pd(q.data(), _mm_div_pd(_mm_set1_pd(1.0), _mm_set_pd(b, a)));
  return q;
#else
  return {1.0 / a, 1.0 / b};
#endif
}

// The sign of a direction component, 0 for a negligible one.
int StepOf(double d) { return d > kTinyComponent ? 1 : (d < -kTinyComponent ? -1 : 0); }

// The clearance byte of a free cell encodes a lower bound of L (see the constructor): 1/16-cell
// steps up to 8 cells, where the sphere steps decide how close to an obstacle the exact
// traversal takes over, then 2-cell steps up to 262 cells. Codes v = 1..kClearanceFineCodes
// stand for L >= (v - 1) / 16.
constexpr int kClearanceFineCodes = 128;
constexpr double kClearanceFinePerCell = 16.0;
constexpr double kClearanceCoarseStart = kClearanceFineCodes / kClearanceFinePerCell;
constexpr double kClearanceCoarseCells = 2.0;

// The lower bound of L (cells) that clearance code v >= 1 stands for.
double ClearanceLowerBoundCells(int v) {
  return v <= kClearanceFineCodes
             ? (v - 1) / kClearanceFinePerCell
             : kClearanceCoarseStart + (v - kClearanceFineCodes - 1) * kClearanceCoarseCells;
}

// The clearance code of a free cell whose distance transform value is `clearance_cells`.
std::uint8_t ClearanceCode(float clearance_cells) {
  // The float distance carries a relative error of about 6e-8, so 1e-4 cells below it is a
  // lower bound of L wherever the code resolves it (below 262 cells).
  const double cells = std::max(0.0, static_cast<double>(clearance_cells) - 1e-4);
  const double v = cells < kClearanceCoarseStart
                       ? 1.0 + std::floor(cells * kClearanceFinePerCell)
                       : kClearanceFineCodes + 1.0 +
                             std::floor((cells - kClearanceCoarseStart) / kClearanceCoarseCells);
  return static_cast<std::uint8_t>(std::clamp(v, 1.0, 255.0));
}

// The occupied cells of a width x height mask, dilated by their 3 x 3 neighbourhood.
std::vector<std::uint8_t> DilatedOccupancy(const std::vector<std::uint8_t>& occupied, int width,
                                           int height) {
  std::vector<std::uint8_t> dilated(occupied.size(), 0);
  for (int iy = 0; iy < height; ++iy) {
    for (int ix = 0; ix < width; ++ix) {
      if (occupied[static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(ix)] == 0) {
        continue;
      }
      for (int y = std::max(iy - 1, 0); y <= std::min(iy + 1, height - 1); ++y) {
        for (int x = std::max(ix - 1, 0); x <= std::min(ix + 1, width - 1); ++x) {
          dilated[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)] = 1;
        }
      }
    }
  }
  return dilated;
}

// The cone of a bundle of rays: its axis c + t u, with c (m) and u the centres of the bounding
// boxes of the origins and of the directions, and rho (m) and alpha those boxes' half
// diagonals, so that |o_j - c| <= rho and |d_j - u| <= alpha for every ray j; t (m) is how far
// it has marched.
struct BundleCone {
  double cx, cy, ux, uy, rho, alpha, scale;  // scale = 1 / (alpha + |u|)
  double t = 0.0;
  bool marching = false;
};

// The cone of the rays first..last - 1 (origins x, y, directions dx, dy); marching when the
// directions are close enough for it to help.
BundleCone ConeOfBundle(std::span<const double> x, std::span<const double> y,
                        std::span<const double> dx, std::span<const double> dy, std::size_t first,
                        std::size_t last) {
  double x_lo = x[first], x_hi = x[first], y_lo = y[first], y_hi = y[first];
  double dx_lo = dx[first], dx_hi = dx[first], dy_lo = dy[first], dy_hi = dy[first];
  for (std::size_t r = first + 1; r < last; ++r) {
    x_lo = std::min(x_lo, x[r]);
    x_hi = std::max(x_hi, x[r]);
    y_lo = std::min(y_lo, y[r]);
    y_hi = std::max(y_hi, y[r]);
    dx_lo = std::min(dx_lo, dx[r]);
    dx_hi = std::max(dx_hi, dx[r]);
    dy_lo = std::min(dy_lo, dy[r]);
    dy_hi = std::max(dy_hi, dy[r]);
  }
  BundleCone cone;
  cone.cx = 0.5 * (x_lo + x_hi);
  cone.cy = 0.5 * (y_lo + y_hi);
  cone.ux = 0.5 * (dx_lo + dx_hi);
  cone.uy = 0.5 * (dy_lo + dy_hi);
  const auto norm = [](double a, double b) { return std::sqrt(a * a + b * b); };
  cone.rho = 0.5 * norm(x_hi - x_lo, y_hi - y_lo);
  cone.alpha = 0.5 * norm(dx_hi - dx_lo, dy_hi - dy_lo);
  cone.scale = 1.0 / (cone.alpha + norm(cone.ux, cone.uy));
  // Directions too spread for a cone to help (or not finite): no common start.
  cone.marching = cone.alpha < 0.5;
  return cone;
}

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
  double TX(int i) const { return Crossing(ox, i, res, px, inv_dx); }
  double TY(int i) const { return Crossing(oy, i, res, py, inv_dy); }
};

// The rays of one CastMany batch (indexed by the ray's position r in the batch) and lists of
// them. Sphere tracing and the exact traversal both run in rounds over a list: one step of every
// listed ray per round, so that the rays' dependent chains (position, cell, memory load, step)
// overlap instead of running one after the other, and without a data-dependent branch: a ray
// that is done is simply not copied forward in the list. A ray's end is then no longer a
// mispredicted branch in the middle of the other rays' work.
struct GridRayCaster::Batch {
  static constexpr std::size_t kCapacity = 256;
  // What the exact traversal of a batch reads of the caster, in one local copy, so that it stays
  // in registers through the rounds: the map's origin (m) and size (cells) per axis, the grid
  // lines, the clearance codes (ClearanceRow(0), rows of w bytes), min_resume_clearance_, the
  // resolution and range_max (m).
  struct Grid {
    std::array<double, 2> origin;
    std::array<int, 2> cells;
    std::array<const double*, 2> lines;
    const std::uint8_t* clearance;
    std::ptrdiff_t w;
    int min_open;
    double res, range_max;
  };
  // How a ray's exact traversal starts: done (no hit, or a hit where it starts), or in its
  // first cell after one crossing, where it stops or from where it goes on.
  enum class WalkStart { kDone, kStops, kGoesOn };
  // One ray's numbers side by side, so that a round addresses them from one base.
  struct RayState {
    // Sphere tracing: the position at ray parameter t is (gx0 + t ux, gy0 + t uy) in cell
    // units; t (m) is where the next step starts (where the last one started once it failed),
    // and t_end where the trace ends, as Ray::t_end.
    double gx0, gy0, ux, uy, t, t_end;
    // The exact traversal, per axis (0: x, 1: y), as in Ray: origin (m), inverse direction
    // (1/m) and its sign; the current cell and the next crossing (m). There t is the t_enter
    // of the current cell, and t_stop that of the cell where the traversal stopped.
    double t_stop;
    std::array<double, 2> p, inv, next;
    std::array<int, 2> step, cell;

    // Sets step and inv for the direction (dx, dy).
    void SetDirection(double dx, double dy);
    // The cell and the next crossing (m) of axis a at t, from `position` (cells), a guess.
    void StartAxis(const Grid& g, std::size_t a, double position, int* cell_a,
                   double* next_a) const;
    // Starts the exact traversal at t (*hit = t for a ray that starts in an occupied cell).
    WalkStart StartWalk(const Grid& g, double* hit);
    // One step of the traversal; whether the ray goes on.
    bool StepCell(const Grid& g);
  };
  std::array<RayState, kCapacity> rays;
  // The rays to sphere-trace, the rays to traverse cell by cell, and the rays going on to the
  // next round. A round reads one list and writes the next into another, so that its loads
  // never wait for its stores.
  std::array<std::uint16_t, kCapacity> sphere, walk, round;

  // Sorts out the first num_stopped rays of `sphere`, whose traversal stopped, by the code of
  // their cell: an occupied cell is a hit at its t_enter (into out); an open cell resumes
  // sphere tracing from there (listed again in `sphere`, their number returned); the padding
  // or range_max is no hit.
  std::size_t SortOutStopped(const Grid& g, std::size_t num_stopped, std::span<double> out);
};

inline void GridRayCaster::Batch::RayState::SetDirection(double dx, double dy) {
  step = {StepOf(dx), StepOf(dy)};
  // As in Setup, a negligible component's inverse is 0 (the division by 1 is discarded).
  const std::array<double, 2> q = Inverses(step[0] != 0 ? dx : 1.0, step[1] != 0 ? dy : 1.0);
  inv = {step[0] != 0 ? q[0] : 0.0, step[1] != 0 ? q[1] : 0.0};
}

inline void GridRayCaster::Batch::RayState::StartAxis(const Grid& g, std::size_t a, double position,
                                                      int* cell_a, double* next_a) const {
  // Cell i spans the crossings [lo, hi) of lines i and i + 1 going up, i + 1 and i going
  // down; the crossing that leaves it is hi.
  const int i = static_cast<int>(position), s = step[a];
  const double lo = (g.lines[a][s > 0 ? i : i + 1] - p[a]) * inv[a];
  *next_a = (g.lines[a][s > 0 ? i + 1 : i] - p[a]) * inv[a];
  *cell_a = i;
  if (s == 0 || lo > t || *next_a <= t) {
    *cell_a = AxisCellAt(t, position, p[a], inv[a], g.origin[a], g.res, s, g.cells[a]);
    *next_a = NextCrossing(*cell_a, g.origin[a], g.res, p[a], inv[a], s);
  }
}

inline GridRayCaster::Batch::WalkStart GridRayCaster::Batch::RayState::StartWalk(const Grid& g,
                                                                                 double* hit) {
  // The cell and the next crossing of each axis at t, in scalars: in an array indexed by the
  // axis they would go through memory, and reading them back stalls.
  int cell_x, cell_y;
  double next_x, next_y;
  StartAxis(g, 0, gx0 + t * ux, &cell_x, &next_x);
  StartAxis(g, 1, gy0 + t * uy, &cell_y, &next_y);
  if (static_cast<unsigned>(cell_x) >= static_cast<unsigned>(g.cells[0]) ||
      static_cast<unsigned>(cell_y) >= static_cast<unsigned>(g.cells[1])) {
    return WalkStart::kDone;  // left the map: no hit
  }
  if (g.clearance[cell_y * g.w + cell_x] == 0) {
    *hit = t;  // starts in an occupied cell
    return WalkStart::kDone;
  }
  // The first crossing, as in StepCell, without a branch on which axis it crosses: the
  // crossing is the smaller one (y on a tie), the cells move by products, and the axis not
  // crossed gets its next crossing computed again, to the same number.
  const int along_x = next_x < next_y ? 1 : 0;
  const double t_next = std::min(next_y, next_x);
  if (t_next > g.range_max) return WalkStart::kDone;  // no hit
  cell_x += step[0] * along_x;
  cell_y += step[1] * (1 - along_x);
  if (step[0] != 0) next_x = (g.lines[0][cell_x + (step[0] > 0 ? 1 : 0)] - p[0]) * inv[0];
  if (step[1] != 0) next_y = (g.lines[1][cell_y + (step[1] > 0 ? 1 : 0)] - p[1]) * inv[1];
  cell = {cell_x, cell_y};
  next = {next_x, next_y};
  t = t_next;
  t_stop = t_next;
  return g.clearance[cell_y * g.w + cell_x] == 0 ? WalkStart::kStops : WalkStart::kGoesOn;
}

inline bool GridRayCaster::Batch::RayState::StepCell(const Grid& g) {
  // A traversal in a cell it entered by a crossing, with that crossing in t: the ray stops in
  // the cell, with the cell's t_enter in t_stop, when its code is 0 (occupied, or the padding
  // just outside the map), when it is open (sphere tracing resumes there), or when the next
  // cell lies beyond range_max; else it crosses to the next cell. No branch on the ray's data:
  // which boundary comes next, and whether the ray stops, are coin tosses for the branch
  // predictor.
  const int c = g.clearance[cell[1] * g.w + cell[0]];
  // The textbook step, across the nearer boundary (y on a tie, as in CastDda): the same
  // crossings as CastDda's. The axis is an index, and only the crossed axis gets a new
  // crossing; a zero step never crosses (its next stays +inf).
  const std::size_t a = next[0] < next[1] ? 0 : 1;
  const double t_next = next[a];
  const int s = step[a];
  // (Bitwise operators on the flags: && would be a branch.)
  const bool going_on = (c != 0) & (c < g.min_open) & !(t_next > g.range_max);
  t_stop = t;  // two stores rather than a select, which GCC would make a branch
  t = t_next;
  // The cell stays as it is for a ray that stops (a product: a ?: would be a branch).
  cell[a] += s * static_cast<int>(going_on);
  next[a] = (g.lines[a][cell[a] + (s > 0 ? 1 : 0)] - p[a]) * inv[a];
  return going_on;
}

inline std::size_t GridRayCaster::Batch::SortOutStopped(const Grid& g, std::size_t num_stopped,
                                                        std::span<double> out) {
  std::size_t num_sphere = 0;
  for (std::size_t k = 0; k < num_stopped; ++k) {
    const std::uint16_t r = sphere[k];
    RayState& ray = rays[r];
    const int c = g.clearance[ray.cell[1] * g.w + ray.cell[0]];
    const bool inside = static_cast<unsigned>(ray.cell[0]) < static_cast<unsigned>(g.cells[0]) &&
                        static_cast<unsigned>(ray.cell[1]) < static_cast<unsigned>(g.cells[1]);
    if (c == 0 && inside) out[r] = ray.t_stop;
    ray.t = ray.t_stop;
    sphere[num_sphere] = r;
    num_sphere += c >= g.min_open ? 1 : 0;
  }
  return num_sphere;
}

GridRayCaster::GridRayCaster(const LikelihoodField& field)
    : field_(&field),
      ox_(field.origin().x()),
      oy_(field.origin().y()),
      res_(field.resolution()),
      width_(field.width()),
      height_(field.height()),
      // The clearance is exact (below), so the margin only absorbs rounding of positions and
      // crossings.
      margin_(res_ * 1e-3) {
  // The clearance of a free cell A is L, the distance (cells) from any point of A to any point
  // of an occupied cell: between unit squares whose centres are (dx, dy) apart it is
  // |(max(|dx| - 1, 0), max(|dy| - 1, 0))|, and as max(|d| - 1, 0) = min over e in {-1, 0, 1}
  // of |d - e| for integer d, L is the distance from A's centre to the nearest centre of the
  // occupied cells dilated by their 3 x 3 neighbourhood: one exact distance transform. (The
  // distance field of the likelihood field, centre to centre, would need a margin of a cell
  // diagonal on every step.) L is 0 next to an obstacle.
  const std::vector<std::uint8_t>& occupied = field.occupied();
  FillClearance(occupied, DistanceTransformCells(DilatedOccupancy(occupied, width_, height_),
                                                 width_, height_));
  FillStepTables();
  // The grid lines of each axis, by the same expression as Crossing's.
  for (std::size_t a = 0; a < 2; ++a) {
    const int n = a == 0 ? width_ : height_;
    const double o = a == 0 ? ox_ : oy_;
    for (int i = -1; i <= n + 1; ++i) grid_lines_[a].push_back(o + static_cast<double>(i) * res_);
  }
}

void GridRayCaster::FillClearance(const std::vector<std::uint8_t>& occupied,
                                  const std::vector<float>& clearance_cells) {
  // The padding ring lets sphere tracing index the cell of a position up to one cell past the
  // far edges, and the exact traversal step one cell out of the map, without a bounds check.
  stride_ = static_cast<std::ptrdiff_t>(width_) + 2;
  clearance_.assign(static_cast<std::size_t>(stride_ * (height_ + 2)), 0);
  for (std::size_t i = 0; i < occupied.size(); ++i) {
    if (occupied[i] != 0) continue;
    const std::size_t w = static_cast<std::size_t>(width_);
    const int ix = static_cast<int>(i % w), iy = static_cast<int>(i / w);
    clearance_[static_cast<std::size_t>(ClearanceRow(iy) + ix - clearance_.data())] =
        ClearanceCode(clearance_cells[i]);
  }
}

void GridRayCaster::FillStepTables() {
  for (int v = 255; v >= 1; --v) {
    step_[static_cast<std::size_t>(v)] =
        res_ * ClearanceLowerBoundCells(v) * (1.0 - 1e-6) - margin_;
    if (step_[static_cast<std::size_t>(v)] >= kMinStepCells * res_) min_step_clearance_ = v;
  }
  // Codes too small for a step get NaN, so that one comparison (t + step < t_end) tells a ray
  // both that it may step and that it stays in range.
  for (int v = 0; v < min_step_clearance_ && v < 256; ++v) {
    step_[static_cast<std::size_t>(v)] = std::numeric_limits<double>::quiet_NaN();
  }
  // Resume sphere tracing from a traversed cell only when it gains at least two cells.
  const double resume_distance = margin_ + 2.0 * res_;
  for (int v = 255; v >= 1; --v) {
    if (res_ * ClearanceLowerBoundCells(v) >= resume_distance) min_resume_clearance_ = v;
  }
}

inline bool GridRayCaster::ClipToMap(double x, double y, double inv_dx, double inv_dy, int step_x,
                                     int step_y, double range_max, double* t_lo,
                                     double* t_end) const {
  // The ray is inside for t in [lo, t_exit).
  double lo = 0.0;
  double t_exit = std::numeric_limits<double>::infinity();
  if (!ClipAxis(x, inv_dx, step_x, ox_, res_, width_, &lo, &t_exit) ||
      !ClipAxis(y, inv_dy, step_y, oy_, res_, height_, &lo, &t_exit)) {
    return false;
  }
  if (lo > range_max || lo >= t_exit) return false;
  *t_lo = lo;
  *t_end = std::min(range_max, t_exit);
  return true;
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
  ray->step_x = StepOf(dx);
  ray->step_y = StepOf(dy);
  RETRACE_CHECK(std::isfinite(x) && std::isfinite(y));
  RETRACE_CHECK(ray->step_x != 0 || ray->step_y != 0);
  ray->inv_dx = ray->step_x != 0 ? 1.0 / dx : 0.0;
  ray->inv_dy = ray->step_y != 0 ? 1.0 / dy : 0.0;
  return ClipToMap(x, y, ray->inv_dx, ray->inv_dy, ray->step_x, ray->step_y, range_max, &ray->t_lo,
                   &ray->t_end);
}

// Where an exact traversal stands: in cell (ix, iy), entered at ray parameter t_enter (m), with
// the next crossing (m) of each axis.
struct GridRayCaster::Cell {
  int ix, iy;
  double next_x, next_y;
  double t_enter;
};

inline bool GridRayCaster::SphereSteps(const Ray& ray, double inv_res, double* t) const {
  const std::uint8_t* clearance = ClearanceRow(0);
  double s = *t;
  while (true) {
    const double gx = (ray.px + s * ray.dx - ox_) * inv_res;
    const double gy = (ray.py + s * ray.dy - oy_) * inv_res;
    const int cx = gx < 0.0 ? 0 : (gx >= width_ ? width_ - 1 : static_cast<int>(gx));
    const int cy = gy < 0.0 ? 0 : (gy >= height_ ? height_ - 1 : static_cast<int>(gy));
    const int c = clearance[cy * stride_ + cx];
    if (c < min_step_clearance_) break;
    s += step_[static_cast<std::size_t>(c)];
    if (s >= ray.t_end) return false;
  }
  *t = s;
  return true;
}

inline bool GridRayCaster::EnterCell(const Ray& ray, double t, double inv_res, Cell* cell) const {
  const double x = ray.px, y = ray.py;
  cell->ix =
      AxisCellAt(t, (x + t * ray.dx - ox_) * inv_res, x, ray.inv_dx, ox_, res_, ray.step_x, width_);
  cell->iy = AxisCellAt(t, (y + t * ray.dy - oy_) * inv_res, y, ray.inv_dy, oy_, res_, ray.step_y,
                        height_);
  if (cell->ix < 0 || cell->iy < 0 || cell->ix >= width_ || cell->iy >= height_) return false;
  cell->next_x = NextCrossing(cell->ix, ox_, res_, x, ray.inv_dx, ray.step_x);
  cell->next_y = NextCrossing(cell->iy, oy_, res_, y, ray.inv_dy, ray.step_y);
  cell->t_enter = t;
  return true;
}

inline bool GridRayCaster::DdaStep(const Ray& ray, Cell* cell) const {
  if (cell->next_x < cell->next_y) {
    cell->t_enter = cell->next_x;
    cell->ix += ray.step_x;
    if (cell->ix < 0 || cell->ix >= width_) return false;
    cell->next_x = ray.step_x > 0 ? ray.TX(cell->ix + 1) : ray.TX(cell->ix);
  } else {
    cell->t_enter = cell->next_y;
    cell->iy += ray.step_y;
    if (cell->iy < 0 || cell->iy >= height_) return false;
    cell->next_y = ray.step_y > 0 ? ray.TY(cell->iy + 1) : ray.TY(cell->iy);
  }
  return !(cell->t_enter > ray.range_max);
}

inline bool GridRayCaster::SelectStep(const Ray& ray, int x_ahead, int y_ahead, Cell* cell) const {
  // Select rather than branch: which boundary comes next is a coin toss for the branch
  // predictor over the few cells left after sphere tracing. The same crossings as the
  // reference's; a zero step never crosses (its next crossing stays +inf).
  const bool cross_x = cell->next_x < cell->next_y;
  cell->t_enter = cross_x ? cell->next_x : cell->next_y;
  cell->ix += cross_x ? ray.step_x : 0;
  cell->iy += cross_x ? 0 : ray.step_y;
  if (static_cast<unsigned>(cell->ix) >= static_cast<unsigned>(width_) ||
      static_cast<unsigned>(cell->iy) >= static_cast<unsigned>(height_)) {
    return false;
  }
  const double new_x = ray.TX(cell->ix + x_ahead), new_y = ray.TY(cell->iy + y_ahead);
  cell->next_x = cross_x ? new_x : cell->next_x;
  cell->next_y = cross_x ? cell->next_y : new_y;
  return !(cell->t_enter > ray.range_max);
}

template <bool kSphere>
double GridRayCaster::Trace(const Ray& ray, double t, bool sphere_now) const {
  // The reference tests the field's occupancy mask; sphere tracing the clearance bytes
  // (clearance 0 exactly on the occupied cells, so both see the same obstacles).
  const std::uint8_t* occupied = kSphere ? ClearanceRow(0) : field_->occupied().data();
  const std::uint8_t* clearance = ClearanceRow(0);
  const std::ptrdiff_t w = kSphere ? stride_ : width_;
  const double inv_res = 1.0 / res_;
  const auto is_occupied = [occupied](std::ptrdiff_t idx) {
    return kSphere ? occupied[idx] == 0 : occupied[idx] != 0;
  };
  // The crossing that leaves cell i is grid line i + 1 going up, i going down.
  const int x_ahead = ray.step_x > 0 ? 1 : 0, y_ahead = ray.step_y > 0 ? 1 : 0;
  while (true) {
    if constexpr (kSphere) {
      // Sphere tracing: every segment [t, t + step] is clear of occupied cells.
      if (sphere_now && !SphereSteps(ray, inv_res, &t)) return kNoHit;
    }
    // Exact traversal from t: the state after every crossing up to t has been made.
    Cell cell;
    if (!EnterCell(ray, t, inv_res, &cell)) return kNoHit;
    while (true) {
      const std::ptrdiff_t idx = cell.iy * w + cell.ix;
      if (is_occupied(idx)) return cell.t_enter;
      if constexpr (kSphere) {
        if (clearance[idx] >= min_resume_clearance_ && cell.t_enter > t) break;
        if (!SelectStep(ray, x_ahead, y_ahead, &cell)) return kNoHit;
      } else {  // the reference: the textbook loop
        if (!DdaStep(ray, &cell)) return kNoHit;
      }
    }
    t = cell.t_enter;  // only reached by sphere tracing resuming in open space
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
  Batch batch;
  for (std::size_t first = 0; first < n; first += Batch::kCapacity) {
    const std::size_t m = std::min(Batch::kCapacity, n - first);
    CastBatch(x.subspan(first, m), y.subspan(first, m), dx.subspan(first, m), dy.subspan(first, m),
              range_max, out.subspan(first, m), &batch);
  }
}

void GridRayCaster::CastBatch(std::span<const double> x, std::span<const double> y,
                              std::span<const double> dx, std::span<const double> dy,
                              double range_max, std::span<double> out, Batch* batch) const {
  std::size_t num_sphere = SetupBatch(x, y, dx, dy, range_max, out, batch);
  // A ray alternates between the two until it hits or ends; most need one sphere tracing and
  // one short walk, a ray grazing past a corner into open space more.
  while (num_sphere > 0) {
    const std::size_t num_walk = SphereTraceBatch(num_sphere, batch);
    num_sphere = WalkBatch(num_walk, range_max, out, batch);
  }
}

std::size_t GridRayCaster::SetupBatch(std::span<const double> x, std::span<const double> y,
                                      std::span<const double> dx, std::span<const double> dy,
                                      double range_max, std::span<double> out, Batch* batch) const {
  // Every ray is kNoHit until a traversal finds its cell.
  std::fill(out.begin(), out.end(), kNoHit);
  if (width_ == 0 || height_ == 0 || !(range_max >= 0.0)) return 0;
  // A sphere-traced position (gx0 + t ux, gy0 + t uy) differs from Cast's by rounding only
  // (1e-12 cells), far inside the 1e-3 cell margin of the steps, and the steps' results need
  // not match Cast's: only the exact traversal decides the range, and it is exact from any t
  // before which the ray is clear. The position stays within [t_lo, t_end], inside the map up
  // to that rounding, so its cell index needs no clamping: the truncation of a coordinate a hair
  // below 0 is 0, and one a hair past the far edge lands in the padding (code 0: the exact
  // traversal takes over). Rays starting farther than kFarCells from the map, where the
  // rounding could grow to a cell, are left to Cast.
  constexpr double kFarCells = 1 << 20;
  const double inv_res = 1.0 / res_;
  const std::size_t n = x.size();
  // Deep inside: range_max plus two cells (for rounding) from every edge, in cells.
  const double deep_lo = range_max * inv_res + 2.0;
  const std::array<double, 2> deep_hi = {width_ - deep_lo, height_ - deep_lo};
  bool finite = true, has_direction = true;
  // Rays that need tracing, before their bundles' clear lengths are known.
  std::size_t num_listed = 0;
  for (std::size_t r = 0; r < n; ++r) {
    Batch::RayState& ray = batch->rays[r];
    ray.SetDirection(dx[r], dy[r]);
    finite = finite && std::isfinite(x[r]) && std::isfinite(y[r]);
    has_direction = has_direction && (ray.step[0] != 0 || ray.step[1] != 0);
    ray.gx0 = (x[r] - ox_) * inv_res;
    ray.gy0 = (y[r] - oy_) * inv_res;
    ray.t = 0.0;
    ray.t_end = range_max;
    // A ray from deep inside the map (and a direction of at most unit length) cannot leave it
    // within range_max: Setup's clipping gives t_lo = max(0, crossings behind the origin) = 0
    // and t_end = min(range_max, t_exit) = range_max, the values just set.
    const bool deep_inside = ray.gx0 >= deep_lo && ray.gx0 <= deep_hi[0] && ray.gy0 >= deep_lo &&
                             ray.gy0 <= deep_hi[1] && std::abs(dx[r]) <= 1.0 &&
                             std::abs(dy[r]) <= 1.0;
    if (!deep_inside && !ClipToMap(x[r], y[r], ray.inv[0], ray.inv[1], ray.step[0], ray.step[1],
                                   range_max, &ray.t, &ray.t_end)) {
      continue;  // misses the map
    }
    if (!(std::abs(ray.gx0) < kFarCells && std::abs(ray.gy0) < kFarCells)) {
      out[r] = Cast(x[r], y[r], dx[r], dy[r], range_max);
      continue;
    }
    ray.ux = dx[r] * inv_res;
    ray.uy = dy[r] * inv_res;
    ray.p = {x[r], y[r]};
    batch->walk[num_listed++] = static_cast<std::uint16_t>(r);
  }
  RETRACE_CHECK(finite);
  RETRACE_CHECK(has_direction);
  return StartAtClearLengths(num_listed, x, y, dx, dy, batch);
}

std::size_t GridRayCaster::StartAtClearLengths(std::size_t num_listed, std::span<const double> x,
                                               std::span<const double> y,
                                               std::span<const double> dx,
                                               std::span<const double> dy, Batch* batch) const {
  // Every ray of a bundle is clear up to the bundle's clear length: sphere tracing starts there,
  // and a ray clear beyond its end has no hit.
  std::array<double, Batch::kCapacity / kBundle> t_clear;
  BundleClearLengths(x, y, dx, dy, t_clear);
  std::size_t num_sphere = 0;
  for (std::size_t k = 0; k < num_listed; ++k) {
    const std::size_t r = batch->walk[k];
    Batch::RayState& ray = batch->rays[r];
    const double t = t_clear[r / kBundle];
    if (t >= ray.t_end) continue;
    ray.t = std::max(ray.t, t);
    batch->sphere[num_sphere++] = static_cast<std::uint16_t>(r);
  }
  return num_sphere;
}

void GridRayCaster::BundleClearLengths(std::span<const double> x, std::span<const double> y,
                                       std::span<const double> dx, std::span<const double> dy,
                                       std::span<double> t_clear) const {
  // From the axis point a = c + t u of a bundle's cone (BundleCone), a step s keeps every ray of
  // the bundle clear for t' in [t, t + s], since
  // |o_j + t' d_j - a| <= |o_j - c| + t' |d_j - u| + (t' - t) |u| <= rho + (t + s) alpha + s |u|,
  // which is at most the safe radius R of a's cell (step_) when
  // s = (R - rho - t alpha) / (alpha + |u|). Rounding (1e-14 m here, 1e-7 m for origins 10^6 km
  // away) stays far inside the 1e-3 cell margin of R.
  const std::size_t n = x.size();
  const std::size_t num_cones = (n + kBundle - 1) / kBundle;
  std::array<BundleCone, Batch::kCapacity / kBundle> cones;
  for (std::size_t g = 0; g < num_cones; ++g) {
    cones[g] = ConeOfBundle(x, y, dx, dy, g * kBundle, std::min(n, g * kBundle + kBundle));
  }
  // The cones march in lockstep, so that their dependent chains (position, cell, load, step)
  // overlap.
  const double inv_res = 1.0 / res_;
  const double min_step = kMinStepCells * res_;
  for (bool marching = true; marching;) {
    marching = false;
    for (std::size_t g = 0; g < num_cones; ++g) {
      BundleCone& cone = cones[g];
      if (!cone.marching) continue;
      const double gx = (cone.cx + cone.t * cone.ux - ox_) * inv_res;
      const double gy = (cone.cy + cone.t * cone.uy - oy_) * inv_res;
      // Outside the map (or NaN) the cone stops; in it, the cell's code.
      const bool in_map = gx >= 0.0 && gy >= 0.0 && gx < width_ && gy < height_;
      const int c = in_map ? ClearanceAt(static_cast<int>(gx), static_cast<int>(gy)) : 0;
      const double s =
          (step_[static_cast<std::size_t>(c)] - cone.rho - cone.t * cone.alpha) * cone.scale;
      cone.marching = s >= min_step;  // false for NaN (a code too small to step)
      if (cone.marching) cone.t += s;
      marching = marching || cone.marching;
    }
  }
  for (std::size_t g = 0; g < num_cones; ++g) t_clear[g] = cones[g].t;
}

std::size_t GridRayCaster::SphereTraceBatch(std::size_t num_sphere, Batch* batch) const {
  const std::uint8_t* clearance = ClearanceRow(0);
  const double* step = step_.data();
  const std::ptrdiff_t w = stride_;
  // The rays that stop go to batch->walk (kept + stopped = rays so far, so one counter serves
  // both lists), and are sorted out after the rounds.
  std::size_t num_stopped = 0;
  std::uint16_t* list = batch->sphere.data();
  std::uint16_t* kept_list = batch->round.data();
  while (num_sphere > 0) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < num_sphere; ++k) {
      const std::uint16_t r = list[k];
      Batch::RayState& ray = batch->rays[r];
      const double t = ray.t;
      const int cx = static_cast<int>(ray.gx0 + t * ray.ux);
      const int cy = static_cast<int>(ray.gy0 + t * ray.uy);
      const double t_next = t + step[clearance[cy * w + cx]];  // NaN when too close to step
      // Past t_end (no hit) or near an obstacle (NaN): the ray stops. A NaN leaves t as it is
      // (max rather than a select, which GCC would make a branch).
      const bool go_on = t_next < ray.t_end;
      ray.t = std::max(t, t_next);
      kept_list[kept] = r;
      batch->walk[num_stopped + k - kept] = r;
      kept += go_on ? 1 : 0;
    }
    std::swap(list, kept_list);
    num_stopped += num_sphere - kept;
    num_sphere = kept;
  }
  // A ray near an obstacle goes on to the exact traversal, from where it stood (t < t_end);
  // one past t_end has no hit (its out stays kNoHit).
  std::size_t num_walk = 0;
  for (std::size_t k = 0; k < num_stopped; ++k) {
    const std::uint16_t r = batch->walk[k];
    const Batch::RayState& ray = batch->rays[r];
    batch->walk[num_walk] = r;
    num_walk += ray.t < ray.t_end ? 1 : 0;
  }
  return num_walk;
}

std::size_t GridRayCaster::WalkBatch(std::size_t num_walk, double range_max, std::span<double> out,
                                     Batch* batch) const {
  const Batch::Grid g{{ox_, oy_},
                      {width_, height_},
                      {GridLines(0), GridLines(1)},
                      ClearanceRow(0),
                      stride_,
                      min_resume_clearance_,
                      res_,
                      range_max};
  // Each traversal starts in the state after every crossing up to the ray's t, in the cell
  // of the sphere-traced position (right but for rounding: checked by its crossings), and makes
  // its first crossing at once when that cell is free, as it is but for a ray that starts in an
  // occupied cell. A ray whose next cell has code 0 (most hits) stops there; the others go on
  // in rounds. The rays that stop go to batch->sphere, to be sorted out below, the others to
  // batch->walk (one counter for both lists, as going on + stopped = rays so far: with two, GCC
  // turns the counting into branches).
  std::size_t num = 0, num_started = 0;
  for (std::size_t k = 0; k < num_walk; ++k) {
    const std::uint16_t r = batch->walk[k];
    const Batch::WalkStart start = batch->rays[r].StartWalk(g, &out[r]);
    if (start == Batch::WalkStart::kDone) continue;
    batch->walk[num] = r;
    batch->sphere[num_started - num] = r;
    num += start == Batch::WalkStart::kStops ? 0 : 1;
    ++num_started;
  }
  // Rounds of one step per ray, so that the rays' steps overlap. The rays that stop go on to
  // batch->sphere.
  std::size_t num_stopped = num_started - num;
  std::uint16_t* list = batch->walk.data();
  std::uint16_t* kept_list = batch->round.data();
  while (num > 0) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < num; ++k) {
      const std::uint16_t r = list[k];
      kept_list[kept] = r;
      batch->sphere[num_stopped + k - kept] = r;
      kept += batch->rays[r].StepCell(g) ? 1 : 0;
    }
    std::swap(list, kept_list);
    num_stopped += num - kept;
    num = kept;
  }
  return batch->SortOutStopped(g, num_stopped, out);
}

template double GridRayCaster::Trace<true>(const Ray&, double, bool) const;
template double GridRayCaster::Trace<false>(const Ray&, double, bool) const;

}  // namespace retrace::nav
