#pragma once
// Where a scan fits a map, searched densely around a prior (docs/METHOD.md, "Settling a
// switch"): every pose on a grid of step_xy and step_theta within the prior's uncertainty is
// scored by the likelihood field on the scan's beams, the sum the particle weights use, and the
// best few places that lie apart are returned. A cloud of a few hundred particles spread over a
// metre or more samples that volume too thinly: one update gathers it on the best particle,
// which may lie half a metre from the truth, and resampling cannot bring it back. A dense search
// finds the places a wrong one would have to beat, and the updates that follow decide.

#include <vector>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "nav/likelihood_field.hpp"
#include "nav/particle.hpp"
#include "nav/robot_geometry.hpp"

namespace retrace::nav {

struct PlaceSearchConfig {
  double step_xy = 0.05;        ///< m: grid step of the positions searched
  double step_theta = 0.0175;   ///< rad: grid step of the headings searched (1°)
  int max_places = 10;          ///< places returned at most
  double min_separation = 0.5;  ///< m: two places returned lie at least this far apart
  /// nats: a place scoring this much below the best is not returned (a likelihood ratio of
  /// e^-margin on one scan).
  double margin = 10.0;
};

/// A place and the log-likelihood of the scan there.
struct ScoredPlace {
  core::Pose2 X_MR;
  double log_likelihood = 0.0;
};

/// The end points (LiDAR frame) of beams 0, beam_step, 2 beam_step, ... that are valid and within
/// [robot.range_min, robot.range_max].
void ScanEndPoints(const core::LaserScan& scan, const RobotGeometry& robot, int beam_step,
                   std::vector<double>* xs_L, std::vector<double>* ys_L);

/// The best places for end points xs_L, ys_L of a scan taken by the robot at about `prior`: every
/// pose within radius_xy (each axis) and radius_theta of it, best first, at most max_places,
/// min_separation apart and within margin of the best. Empty for no end point.
std::vector<ScoredPlace> SearchPlaces(const LikelihoodField& field, const RobotGeometry& robot,
                                      const std::vector<double>& xs_L,
                                      const std::vector<double>& ys_L, const core::Pose2& prior,
                                      double radius_xy, double radius_theta,
                                      const PlaceSearchConfig& config = {});

/// `count` particles of equal weight shared evenly between the places, each drawn around its
/// place with std sigma_xy on x and y and sigma_theta on the heading.
std::vector<Particle> ParticlesAtPlaces(const std::vector<ScoredPlace>& places, int count,
                                        double sigma_xy, double sigma_theta, core::Rng& rng);

}  // namespace retrace::nav
