#pragma once
// The localizer's point estimate: the mean of one cluster of the belief, not of all particles,
// so that minor modes and fresh recovery hypotheses do not drag it (docs/METHOD.md, "The
// estimate").

#include <optional>
#include <span>

#include "core/pose2.hpp"
#include "nav/particle.hpp"

namespace retrace::nav {

/// A cluster's weighted mean (circular for θ) and the total weight of its particles.
struct ClusterMean {
  core::Pose2 X_MR;
  double weight = 0.0;
};

/// Half-widths of a cluster: particles within this distance (m) and heading difference (rad) of
/// its mean belong to it.
inline constexpr double kClusterRadius = 1.0;
inline constexpr double kClusterAngle = 0.5;

/// Mean shift from `around`: up to three steps to the weighted mean of the particles within
/// kClusterRadius and kClusterAngle. nullopt when no particle of positive weight is there.
std::optional<ClusterMean> ClusterAround(std::span<const Particle> particles,
                                         const core::Pose2& around);

/// The belief's main cluster: the heaviest neighbourhood (a cell and the 26 around it, heading
/// wrapping) of a (0.5 m, 0.5 m, 30°) histogram seeds ClusterAround. Summing neighbourhoods
/// matters: a converged cloud that straddles cell borders splits over up to eight cells, and a
/// lone heavy particle elsewhere could then outweigh each part. nullopt for no particles.
std::optional<ClusterMean> MainCluster(std::span<const Particle> particles);

/// The belief's spread: the weighted RMS distance (m) of the particles' positions from their
/// weighted mean. 0 for no particles or no weight.
double ParticleSpread(std::span<const Particle> particles);

}  // namespace retrace::nav
