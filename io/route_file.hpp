#pragma once
// Plain-text route and path files. A route is a polyline of waypoints (m, world frame W) that
// the simulated teacher drives; a path is a sequence of poses as AutoNavi stores its taught
// paths (`paths/path_k.txt`): one `x y z qx qy qz qw` per line, in the partial map's frame.
// `#` starts a comment; blank lines are skipped.

#include <filesystem>
#include <vector>

#include "core/path.hpp"
#include "core/pose2.hpp"

namespace retrace::io {

/// Reads route waypoints from lines of `x y`, or of AutoNavi's `x y z qx qy qz qw` (only x
/// and y are used); every line of a file must have the same number of columns.
/// Throws core::IoError naming the file and line for a line with another column count, a
/// token that is not a finite number or a single waypoint, and naming the file for an empty
/// or unreadable file.
std::vector<core::Vec2> ReadRouteFile(const std::filesystem::path& path);

/// Reads an AutoNavi path file (7 columns per line); the heading is the yaw of the
/// quaternion, z, roll and pitch are ignored. Throws core::IoError naming the file and line
/// for a malformed line or a zero quaternion, and for an empty or unreadable file.
core::Path ReadPathFile(const std::filesystem::path& path);

/// Writes a path as `x y z qx qy qz qw` lines (z = 0, rotation about z by the heading),
/// numbers in shortest round-trip form, atomically. Throws core::IoError if the file cannot
/// be written.
void WritePathFile(const std::filesystem::path& path, const core::Path& poses);

}  // namespace retrace::io
