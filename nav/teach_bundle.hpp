#pragma once
// The teach bundle: what the teaching run leaves for playback (docs/DESIGN.md §6) — per partial map
// k its occupancy grid, its taught path and its switch pose — and its files on disk, laid out as
// AutoNavi writes them:
//
//   <dir>/maps/ogm_k.yaml, maps/ogm_k.pgm   map k (ROS map_server, trinary), k = 0, 1, ...
//   <dir>/paths/path_k.txt                  path k: one `x y z qx qy qz qw` per line, in M_k
//   <dir>/switch_poses.txt                  `#` header lines, then one `x y yaw` data line per
//                                           map: data line k+1 holds X_{M_k S}
//   <dir>/last_pose_k.txt                   X_{M_k S} again as AutoNavi's path_register writes
//                                           it: a single `x y yaw` line, no header
//   <dir>/sub_map_num.txt                   the number of partial maps
//   <dir>/revisits.txt                      the route graph's revisit edges (RevisitEdge), one
//                                           `a b s_a s_b x y yaw` line each (retrace's own;
//                                           absent in folders written before it: see `linked`)
//
// Units: m and rad. Every file is written atomically.

#include <filesystem>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/path.hpp"
#include "core/pose2.hpp"

namespace retrace::nav {

/// One partial map of the teaching run, all in its own frame M (the odometry pose at which
/// the map was started).
struct PartialMap {
  core::OccupancyGrid grid;  ///< occupancy in M (log-odds)
  core::Path path;           ///< the taught path: keyframe poses X_MR in M, ending at X_MS
  core::Pose2 X_MS;          ///< switch pose: where the next map starts, in M
};

/// A place where the taught paths of two maps come back to each other (a revisit), and the
/// transform between the two frames measured there by registering the maps
/// (nav/route_graph.hpp, nav/map_registration.hpp). The switch poses relate consecutive maps;
/// these edges relate the maps a route passes again.
struct RevisitEdge {
  std::size_t a = 0;  ///< the earlier map
  std::size_t b = 0;  ///< the later map (a < b)
  double s_a = 0.0;   ///< m: arc length of the place on path a
  double s_b = 0.0;   ///< m: ... and on path b
  core::Pose2 X_ab;   ///< X_{M_a M_b}: map b's frame in map a's, as registered at the place
};

/// The partial maps of one teaching run, in driving order, and the route graph's revisit edges.
struct TeachBundle {
  std::vector<PartialMap> maps;
  std::vector<RevisitEdge> revisits;
  /// The revisits have been searched for (nav::LinkRoute); a bundle read from a folder written
  /// before route graphs existed has not, and the map server searches when it loads it.
  bool linked = false;
};

/// Writes `bundle` into the folder `dir` (created if needed) in the layout above; grids are
/// written in trinary mode (0 occupied, 254 free, 205 unknown), so reading back reproduces
/// their cell classes, not their log-odds. Throws core::IoError for an empty bundle, an empty
/// grid or path, or a file that cannot be written.
void WriteTeachBundle(const std::filesystem::path& dir, const TeachBundle& bundle);

/// Reads a bundle written by WriteTeachBundle: the number of maps from sub_map_num.txt, then
/// every map, path and switch pose, which must all be present and agree in number
/// (switch_poses.txt and last_pose_k.txt must also agree with each other within 1e-6).
/// Throws core::IoError with one message naming the bundle, the offending file and what is
/// wrong, for a missing, unreadable or malformed file or an inconsistent count.
TeachBundle ReadTeachBundle(const std::filesystem::path& dir);

}  // namespace retrace::nav
