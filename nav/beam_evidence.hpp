#pragma once
// What a scan says about a pose in a map (docs/METHOD.md, "Reliability"): each tested beam is
//
//   explained     its end point lies within explained_distance of a wall of the map;
//   shorter       it ends in space the map saw free, before the wall the map predicts: something
//                 the map does not hold stands there (a person, a parked bike), or the pose is
//                 wrong. No evidence for or against the pose;
//   unknown       it ends in cells the map never observed: no evidence either way;
//   through wall  it ends more than contradiction_margin beyond a wall of the map that lies on
//                 its ray (wherever it ends), met at more than 20° from the wall's surface: it
//                 sees through the map. (A ray that meets a wall at less than that only grazes
//                 a corner cell of it, as a pose a few centimetres off does along any
//                 corridor.) A person can only shorten a beam, so this contradicts the pose (or
//                 the map has changed).
//
// The map's coverage of the scene is the share of beams that end in observed cells (all but the
// unknown ones); the scan supports the pose when enough beams are explained and few contradict.

#include <cstdint>
#include <span>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "nav/grid_ray_caster.hpp"
#include "nav/likelihood_field.hpp"

namespace retrace::nav {

/// How each tested beam of one scan was explained at one pose.
struct BeamEvidence {
  int explained = 0;
  int shorter = 0;
  int unknown = 0;
  int through_wall = 0;

  int total() const { return explained + shorter + unknown + through_wall; }
  /// Share of the beams that end in observed cells (0 without beams).
  double Coverage() const;
  /// Share of the beams explained by the map (0 without beams).
  double Explained() const;
  /// Share of the beams that see through a mapped wall (0 without beams).
  double Contradicted() const;
};

/// The thresholds of ClassifyBeams, from the likelihood field's σ_hit (eq. 5-6): a beam ending
/// within 1.5 σ of a wall is explained; one ending 2 σ beyond a wall on its ray contradicts.
struct BeamEvidenceThresholds {
  double explained_distance = 0.3;    ///< m
  double contradiction_margin = 0.4;  ///< m
  static BeamEvidenceThresholds Of(const LikelihoodField& field);
};

/// What one beam says (the classes above).
enum class BeamClass : std::uint8_t { kExplained, kShorter, kUnknown, kThroughWall };

/// The class of each beam whose end points (LiDAR frame) are xs_L, ys_L, for a LiDAR at X_ML in
/// the field's map, into `classes` (resized): one ray cast on the grid per beam. A beam that
/// passes a wall of the map more than contradiction_margin before its end sees through it, even
/// if it ends on another wall.
void ClassifyEachBeam(const LikelihoodField& field, const GridRayCaster& caster,
                      const core::Pose2& X_ML, std::span<const double> xs_L,
                      std::span<const double> ys_L, std::vector<BeamClass>* classes);

/// The counts of the classes.
BeamEvidence CountClasses(std::span<const BeamClass> classes);

/// ClassifyEachBeam, counted.
BeamEvidence ClassifyBeams(const LikelihoodField& field, const GridRayCaster& caster,
                           const core::Pose2& X_ML, std::span<const double> xs_L,
                           std::span<const double> ys_L);

/// The share of end points (LiDAR frame) that fall in cells the grid observed, for a LiDAR at
/// X_ML in the grid's frame: how much of what the robot sees the map covers. 0 without points.
double GridCoverage(const core::OccupancyGrid& grid, const core::Pose2& X_ML,
                    std::span<const double> xs_L, std::span<const double> ys_L);

}  // namespace retrace::nav
