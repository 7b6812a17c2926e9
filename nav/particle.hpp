#pragma once
// One hypothesis of the localizer's belief.

#include "core/pose2.hpp"

namespace retrace::nav {

/// One hypothesis: the robot pose X_MR in the map frame M and its normalised weight.
struct Particle {
  core::Pose2 X_MR;
  double weight = 0.0;
};

}  // namespace retrace::nav
