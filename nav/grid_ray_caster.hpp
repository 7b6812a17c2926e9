#pragma once
// Expected ranges on an occupancy grid: the distance along a ray to the first occupied cell.
//
// The exact result is defined by the per-cell traversal of Amanatides and Woo: the ray visits
// every cell it passes through, in order, and the range is the ray parameter t (m) at which it
// enters the first occupied cell (0 if it starts in one). Cell-boundary crossings are computed
// in closed form, t = (boundary - start) / direction, never accumulated, so a traversal resumed
// at any t reproduces the full traversal's numbers bit for bit. `Cast` sphere-traces on the
// likelihood field's distance field and finishes with that traversal over the last cells; it
// returns exactly what `CastDda` (the straightforward reference) returns. `CastMany` does the
// same for a batch of rays, sphere-tracing several of them in lockstep.

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
  /// clearance grid from its distance field (width x height bytes).
  explicit GridRayCaster(const LikelihoodField& field);

  /// Range (m) from origin (M) along the unit direction (dx, dy) to where the ray enters the
  /// first occupied cell, or kNoHit (+inf) when there is none within range_max (m) or before the
  /// ray leaves the map. A ray starting outside the map is clipped to it first. Sphere tracing
  /// on the distance field; bit-identical to CastDda.
  double Cast(double x, double y, double dx, double dy, double range_max) const;
  double Cast(const core::Vec2& origin_M, const core::Vec2& dir_M, double range_max) const {
    return Cast(origin_M.x(), origin_M.y(), dir_M.x(), dir_M.y(), range_max);
  }

  /// Cast for a batch of rays: out[i] = Cast(x[i], y[i], dx[i], dy[i], range_max), bit for bit.
  /// The sphere-tracing steps of several rays are interleaved so that their dependent chains
  /// (position, cell, clearance load, step) overlap instead of running one after the other,
  /// in rounds whose only data-dependent branch is once per round, not once per ray's end.
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
  // Direction, crossings and clipping of one ray; false when the ray misses the map or starts
  // beyond range_max (the result is kNoHit).
  bool Setup(double x, double y, double dx, double dy, double range_max, Ray* ray) const;
  // The traversal from ray parameter t (m), after every segment before t has been found clear.
  // kSphere: sphere-trace first (and again whenever the traversal reaches open space).
  // sphere_now: whether to start with a sphere step (false right after a sphere step stopped).
  template <bool kSphere>
  double Trace(const Ray& ray, double t, bool sphere_now) const;

  const LikelihoodField* field_;
  double ox_, oy_, res_;
  int width_, height_;
  double margin_;  // m subtracted from the clearance for a step that cannot skip a cell
  // Per cell: a code for a lower bound of the distance field (1/16 cell up to 9 cells, then 2
  // cells, saturated at 255); 0 exactly on occupied cells. One byte per cell serves both the
  // occupancy test and the sphere steps, so tracing a ray touches a quarter of the memory of the
  // float field. Rows of stride_ = width + 1 bytes, plus one row: the padding is 0.
  std::vector<std::uint8_t> clearance_;
  std::size_t stride_ = 1;
  // Per clearance code c: the sphere step D_c res (1 - 1e-6) - margin (m), D_c the code's lower
  // bound (cells), that is safe from any point of the cell (NaN below min_step_clearance_); and
  // the smallest code whose step gains enough to be worth taking.
  std::array<double, 256> step_{};
  int min_step_clearance_ = 256;
  // The smallest clearance from which the traversal resumes sphere tracing (gains two cells).
  int min_resume_clearance_ = 256;
};

}  // namespace retrace::nav
