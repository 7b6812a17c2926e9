#pragma once
// The spread of a particle set in tests: the weighted covariance of the particles' (x, y, θ)
// around a pose (m², m·rad, rad²), θ differences wrapped to [-π, π).

#include <Eigen/Core>
#include <vector>

#include "core/angle.hpp"
#include "core/pose2.hpp"
#include "nav/particle.hpp"

namespace retrace::testing {

inline Eigen::Matrix3d ParticleCovariance(const std::vector<nav::Particle>& particles,
                                          const core::Pose2& mean) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double total = 0.0;
  for (const nav::Particle& p : particles) {
    const Eigen::Vector3d d(p.X_MR.x - mean.x, p.X_MR.y - mean.y,
                            core::AngleDiff(p.X_MR.theta, mean.theta));
    cov += p.weight * (d * d.transpose());
    total += p.weight;
  }
  return total > 0.0 ? Eigen::Matrix3d(cov / total) : cov;
}

}  // namespace retrace::testing
