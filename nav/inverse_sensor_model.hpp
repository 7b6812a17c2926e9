#pragma once
// The inverse sensor model of the mapper (paper §4.1): p(m | z, x), the occupancy probability
// of a cell given one beam, for the binary Bayes filter in log-odds (eq. 3-4):
//
//   l <- clamp(l + logit(p(m | z, x)) - l0),  l0 = logit(0.5) = 0.
//
// It is the likelihood-field model (eq. 5-6) read as an inverse model, as the original
// implementation does: a cell at distance d (m, along the beam) from the beam's end point gets
//
//   p(d) = p_miss + (p_hit - p_miss) * exp(-d^2 / (2 sigma^2))     in front of the end point,
//   p(d) = 0.5    + (p_hit - 0.5)    * exp(-d^2 / (2 sigma^2))     behind it,
//
// where exp(-d^2/2sigma^2) is the hit term p_hit of eq. (6) without its normaliser, p_hit the
// value on the end cell (d = 0) and p_miss the floor z_hit p_hit(d_max) + z_rand p_rand of
// eq. (5) (see InverseModelFromLikelihoodField). Cells more than `neighbourhood_sigmas` sigma
// in front of the end point get exactly p_miss (the beam passed through them); cells more
// than that behind it are not updated (the beam never got there). The distance d of a cell is
// measured between the end point and the cell's stretch [t_in, t_out] of the ray, so the
// cell holding the end point has d = 0.

#include "core/config.hpp"

namespace retrace::nav {

/// Shape of the inverse sensor model. Defaults: a hit raises an unknown cell to 0.94 and a
/// miss lowers it to 0.04, as in the original implementation; sigma is about the range noise
/// of a Hokuyo UTM-30LX at 10 m. The original's sigma of 0.2 m (the localizer's) marks about
/// two cells in front of every wall as occupied; even 0.05 m thickens 0.1 m-cell walls on
/// their free side (on the room of tests/nav/mapper_test.cpp, measured while tuning: banded
/// IoU 0.6-0.8 with 0.05 m against 0.97 with 0.02 m).
struct InverseSensorModelConfig {
  double hit_probability = 0.94;   ///< p(m | z) of the cell holding the end point
  double miss_probability = 0.04;  ///< p(m | z) of a cell the beam passed through
  double sigma = 0.02;             ///< m, width of the hit term along the beam
  /// Extent of the end point's neighbourhood on either side, in units of sigma.
  double neighbourhood_sigmas = 3.0;

  template <class V>
  void Reflect(V& v) {
    v("hit_probability", hit_probability);
    v("miss_probability", miss_probability);
    v("sigma", sigma);
    v("neighbourhood_sigmas", neighbourhood_sigmas);
  }
  /// Throws core::ConfigError naming the key: hit_probability must lie in (0.5, 1),
  /// miss_probability in (0, 0.5), sigma > 0, neighbourhood_sigmas in [0, 10].
  void Validate() const;

  /// Distance (m) beyond the end point up to which cells are updated.
  double ReachBehind() const { return neighbourhood_sigmas * sigma; }
};

/// The inverse model that eq. (5)-(6) give for a beam end point at distance d from a cell
/// that is the obstacle: p(d) = z_hit exp(-d^2/2sigma^2) + z_hit exp(-d_max^2/2sigma^2) +
/// z_rand / range_max, where d_max (m) truncates the likelihood field and range_max (m) is
/// the sensor's (p_rand = 1/range_max). The original's values z_hit 0.9, z_rand 0.05,
/// sigma 0.2 m, d_max 0.5 m, range_max 30 m give p_hit 0.941 and p_miss 0.041. The result's
/// sigma is `sigma`. Throws core::ConfigError if the parameters give an invalid model.
InverseSensorModelConfig InverseModelFromLikelihoodField(double z_hit, double z_rand, double sigma,
                                                         double d_max, double range_max);

/// Signed distance (m) along the beam from the end point at range z (m) to the stretch
/// [t_in, t_out] (m from the sensor, t_in <= t_out) of the ray inside a cell: 0 if z lies in
/// it, t_out - z < 0 if the cell is in front of the end point, t_in - z > 0 if behind it.
double SignedDistanceToEndPoint(double t_in, double t_out, double z);

/// p(m | z, x) of a cell at signed along-beam distance `d` (m, from SignedDistanceToEndPoint)
/// from the end point. Returns 0.5 (no information) for cells too far behind it.
double OccupancyProbability(const InverseSensorModelConfig& config, double d);

/// The log-odds increment logit(p(m | z, x)) - l0 (eq. 4) for that cell; 0 when too far behind.
double LogOddsUpdate(const InverseSensorModelConfig& config, double d);

/// The increment of a cell that a beam passed through well before its end point, or that a
/// no-return (+inf) beam crossed: logit(miss_probability).
double MissLogOdds(const InverseSensorModelConfig& config);

/// The increment of the cell holding the end point: logit(hit_probability).
double HitLogOdds(const InverseSensorModelConfig& config);

}  // namespace retrace::nav
