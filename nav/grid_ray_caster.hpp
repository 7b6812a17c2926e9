#pragma once
// Expected ranges on an occupancy grid: the distance along a ray to the first occupied cell.
//
// The exact result is defined by the per-cell traversal of Amanatides and Woo: the ray visits
// every cell it passes through, in order, and the range is the ray parameter t (m) at which it
// enters the first occupied cell (0 if it starts in one). Cell-boundary crossings are computed
// in closed form, t = (boundary - start) / direction, never accumulated, so a traversal resumed
// at any t reproduces the full traversal's numbers bit for bit. `Cast` sphere-traces on a
// clearance grid (the exact distance from a cell to the nearest occupied cell) and finishes with
// that traversal over the last cells; it returns exactly what `CastDda` (the straightforward
// reference) returns. `CastMany` does the same for a batch of rays: it first clears a common
// start for each bundle of coherent rays, then sphere-traces and traverses many rays in lockstep.

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/pose2.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace::nav {

/// Returned when no occupied cell lies on the ray within range_max (or before the ray leaves
/// the map): the map predicts no return. Never 0.
inline constexpr double kNoHit = std::numeric_limits<double>::infinity();

/// Ray casting on the occupancy mask of a LikelihoodField, in its map frame M.
class GridRayCaster {
 public:
  /// Keeps a reference to `field`, which must outlive the caster, and builds a one-byte
  /// clearance grid from its occupancy mask ((width + 2) x (height + 2) bytes; one distance
  /// transform) and a table of the grid lines.
  explicit GridRayCaster(const LikelihoodField& field);

  /// Range (m) from origin (M) along the unit direction (dx, dy) to where the ray enters the
  /// first occupied cell, or kNoHit (+inf) when there is none within range_max (m) or before the
  /// ray leaves the map. A ray starting outside the map is clipped to it first. Sphere tracing
  /// on the clearance grid; bit-identical to CastDda.
  double Cast(double x, double y, double dx, double dy, double range_max) const;
  double Cast(const core::Vec2& origin_M, const core::Vec2& dir_M, double range_max) const {
    return Cast(origin_M.x(), origin_M.y(), dir_M.x(), dir_M.y(), range_max);
  }

  /// Cast for a batch of rays: out[i] = Cast(x[i], y[i], dx[i], dy[i], range_max), bit for bit.
  /// Fastest when consecutive rays are coherent, like the rays of one beam from a particle cloud
  /// in the order of the particles' headings: for each group of 32 consecutive rays it finds a
  /// length over which all of them are provably clear and starts them there. The steps of many
  /// rays are interleaved so that their dependent chains (position, cell, clearance load, step)
  /// overlap instead of running one after the other, in rounds without data-dependent branches.
  /// All spans must have the same size (checked).
  void CastMany(std::span<const double> x, std::span<const double> y, std::span<const double> dx,
                std::span<const double> dy, double range_max, std::span<double> out) const;

  /// The reference: the same result by visiting every cell (Amanatides-Woo DDA).
  double CastDda(double x, double y, double dx, double dy, double range_max) const;
  double CastDda(const core::Vec2& origin_M, const core::Vec2& dir_M, double range_max) const {
    return CastDda(origin_M.x(), origin_M.y(), dir_M.x(), dir_M.y(), range_max);
  }

  const LikelihoodField& field() const { return *field_; }

 private:
  struct Ray;
  struct Batch;
  // Direction, crossings and clipping of one ray; false when the ray misses the map or starts
  // beyond range_max (the result is kNoHit).
  bool Setup(double x, double y, double dx, double dy, double range_max, Ray* ray) const;
  // Clips a ray from (x, y) (M) with inverse direction components inv_dx, inv_dy (1/m; 0 with
  // a step of 0) to the map: [*t_lo, *t_end] (m), t_end at most range_max; false when the ray
  // misses the map or enters it beyond range_max.
  bool ClipToMap(double x, double y, double inv_dx, double inv_dy, int step_x, int step_y,
                 double range_max, double* t_lo, double* t_end) const;
  // Sets the clearance codes of the cells (padding ring included) from the occupancy mask and
  // the distance transform (cells) of its dilation.
  void FillClearance(const std::vector<std::uint8_t>& occupied,
                     const std::vector<float>& clearance_cells);
  // Sets the sphere step per code and the codes from which to step and to resume stepping.
  void FillStepTables();
  // CastMany for at most Batch::kCapacity rays, in three passes over *batch: SetupBatch lists
  // the rays to trace (and answers the others), SphereTraceBatch steps the listed rays until
  // each is near an obstacle or past its end, WalkBatch finishes those near an obstacle cell by
  // cell, exactly, or lists them for sphere tracing again when they reach open space.
  void CastBatch(std::span<const double> x, std::span<const double> y, std::span<const double> dx,
                 std::span<const double> dy, double range_max, std::span<double> out,
                 Batch* batch) const;
  std::size_t SetupBatch(std::span<const double> x, std::span<const double> y,
                         std::span<const double> dx, std::span<const double> dy, double range_max,
                         std::span<double> out, Batch* batch) const;
  // SetupBatch's last step: starts each of the first num_listed rays of batch->walk at its
  // bundle's clear length (BundleClearLengths), listing in batch->sphere (their number
  // returned) those that do not end before it.
  std::size_t StartAtClearLengths(std::size_t num_listed, std::span<const double> x,
                                  std::span<const double> y, std::span<const double> dx,
                                  std::span<const double> dy, Batch* batch) const;
  // For each bundle of kBundle consecutive rays (from nearby origins in similar directions), the
  // length t_clear[g] (m) for which all are clear: x[r] + t' dx[r] misses every occupied cell
  // for all t' in [0, t_clear[g]]. 0 when the rays are not coherent enough.
  void BundleClearLengths(std::span<const double> x, std::span<const double> y,
                          std::span<const double> dx, std::span<const double> dy,
                          std::span<double> t_clear) const;
  std::size_t SphereTraceBatch(std::size_t num_sphere, Batch* batch) const;
  std::size_t WalkBatch(std::size_t num_walk, double range_max, std::span<double> out,
                        Batch* batch) const;
  // The traversal from ray parameter t (m), after every segment before t has been found clear.
  // kSphere: sphere-trace first (and again whenever the traversal reaches open space).
  // sphere_now: whether to start with a sphere step (false right after a sphere step stopped).
  template <bool kSphere>
  double Trace(const Ray& ray, double t, bool sphere_now) const;
  // Trace's steps (inv_res = 1 / res_; x_ahead, y_ahead: 1 for an axis the ray goes up).
  struct Cell;
  // Sphere-traces from *t as far as the clearance allows; false when the ray passes its end.
  bool SphereSteps(const Ray& ray, double inv_res, double* t) const;
  // Starts the exact traversal at t (the cell after every crossing up to t); false off the map.
  bool EnterCell(const Ray& ray, double t, double inv_res, Cell* cell) const;
  // The reference's textbook step into the next cell; false off the map or beyond range_max.
  bool DdaStep(const Ray& ray, Cell* cell) const;
  // DdaStep's crossing without a branch on the axis; false off the map or beyond range_max.
  bool SelectStep(const Ray& ray, int x_ahead, int y_ahead, Cell* cell) const;

  const LikelihoodField* field_;
  double ox_, oy_, res_;
  int width_, height_;
  double margin_;  // m subtracted from every sphere step for rounding
  // Per cell: a code for a lower bound of the distance (cells) from any point of the cell to
  // any point of an occupied cell (1/16 cell up to 8 cells, then 2 cells, saturated at 255);
  // 0 exactly on occupied cells. One byte per cell serves both the occupancy test and the sphere
  // steps. A ring of padding cells (code 0) surrounds the map, so that a position up to one cell
  // outside it has a code: rows of stride_ = width + 2 bytes, height + 2 rows.
  std::vector<std::uint8_t> clearance_;
  std::ptrdiff_t stride_ = 2;
  // The code of cell (ix, iy), -1 <= ix <= width, -1 <= iy <= height.
  const std::uint8_t* ClearanceRow(int iy) const {
    return clearance_.data() + (iy + 1) * stride_ + 1;
  }
  std::uint8_t ClearanceAt(int ix, int iy) const { return ClearanceRow(iy)[ix]; }
  // The grid lines' coordinates o + i res (m) of each axis (0: x, 1: y) for i = -1..n + 1, as
  // Crossing computes them: a table lookup instead of a conversion, a product and a sum.
  std::array<std::vector<double>, 2> grid_lines_;
  const double* GridLines(std::size_t axis) const { return grid_lines_[axis].data() + 1; }
  // Per clearance code c: the sphere step L_c res (1 - 1e-6) - margin (m), L_c the code's lower
  // bound (cells), that is safe from any point of the cell (NaN below min_step_clearance_); and
  // the smallest code whose step gains enough to be worth taking.
  std::array<double, 256> step_{};
  int min_step_clearance_ = 256;
  // The smallest clearance from which the traversal resumes sphere tracing (gains two cells).
  int min_resume_clearance_ = 256;
};

}  // namespace retrace::nav
