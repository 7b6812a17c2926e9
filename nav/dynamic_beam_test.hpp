#pragma once
// The dynamic scan point test of Probabilistic Robotics Table 8.5 (paper eq. 9) over a particle
// cloud: a beam is "dynamic" (it hit something the map does not contain) when, summed over the
// particles, the short-reading term explains most of its probability.

#include <cstdint>
#include <span>
#include <vector>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "nav/beam_model.hpp"
#include "nav/grid_ray_caster.hpp"

namespace retrace::nav {

/// How the dynamic-point test computes the expected ranges.
enum class RayCastMethod {
  kSphereTracing,  ///< GridRayCaster::CastMany (all particles of a beam at once)
  kDda,            ///< GridRayCaster::CastDda (the reference; same results, slower)
};

/// How the test works; every choice gives the same mask.
struct DynamicTestOptions {
  RayCastMethod method = RayCastMethod::kSphereTracing;
  /// Decide a beam as soon as bounds on the two sums settle it (docs/METHOD.md, "The
  /// dynamic-point test by bounds"): first from a sample of the particles cast exactly and the
  /// rest bounded, then from every ray cast only to a little beyond the reading. Such beams get
  /// no ratio (NaN). false: every ray cast to range_max, every ratio computed.
  bool decide_by_bounds = true;
};

/// Outcome of the dynamic scan point test for a set of beams.
struct DynamicBeamResult {
  std::vector<std::uint8_t> dynamic;  ///< per tested beam: 1 when the ratio exceeds χ
  /// Per tested beam: Σ_j z_short p_short / Σ_j p_beam, or NaN where bounds decided the beam.
  std::vector<double> ratio;
};

/// The dynamic scan point test (eq. 9) for the readings `beams` (indices into scan.ranges, all
/// of which must be finite and inside [scan.range_min, scan.range_max]: checked) over the
/// particles' LiDAR poses X_ML (M): beam i is dynamic when Σ_j w_j z_short p_short(z_i | x_j, m)
/// / Σ_j w_j p_beam(z_i | x_j, m) > chi. `weights` are the particles' weights (one per pose) or
/// empty for equal weights, which is Table 8.5's unweighted sum; with weights the sums stay
/// expectations over the belief when the particles have not been resampled. Beam angles come
/// from the scan (angle in L). The expected ranges are ray-cast on `caster`'s map up to
/// model.range_max(). Writes into *result (resized; reuses its storage).
void TestDynamicBeams(const BeamModel& model, const GridRayCaster& caster,
                      std::span<const core::Pose2> X_ML, std::span<const double> weights,
                      const core::LaserScan& scan, std::span<const int> beams, double chi,
                      const DynamicTestOptions& options, DynamicBeamResult* result);

}  // namespace retrace::nav
