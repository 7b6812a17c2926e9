#pragma once
// TUM RGB-D trajectory files, one pose per line: `t x y z qx qy qz qw` (s, m, unit
// quaternion), the format evo reads for APE/RPE. Planar poses are written with z = 0 and a
// rotation about z only.

#include <filesystem>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::io {

/// A pose with its time stamp (s; simulated time in retrace's own files).
struct StampedPose {
  double t = 0.0;
  core::Pose2 pose;
};

/// Writes a trajectory atomically, every number in shortest round-trip form (so reading it
/// back gives the same doubles, up to the quaternion's rounding of the heading).
/// Throws core::IoError if the file cannot be written.
void WriteTum(const std::filesystem::path& path, const std::vector<StampedPose>& poses);

/// Reads a trajectory; `#` comments and blank lines are skipped. The pose is the projection
/// onto the plane: x, y and the yaw of the quaternion (z, roll and pitch are ignored).
/// Throws core::IoError naming the file and line for a line that does not hold 8 finite
/// numbers or whose quaternion is zero, and if the file cannot be read.
std::vector<StampedPose> ReadTum(const std::filesystem::path& path);

}  // namespace retrace::io
