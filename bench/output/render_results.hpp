#pragma once
// The figures of a results folder (`retrace render`, and the end of `retrace run`): everything
// is read back from the files `retrace run` wrote, so figures can be re-rendered without
// running anything again.
//
//   <out>/<mode>/figures/  maps.png, playback_<mode>.png, odometry.png, errors.png,
//                          snapshot.png, likelihood.png
//   <out>/figures/         comparison.png (several modes), maps_compare.png (consistent and
//                          single both present)

#include <filesystem>
#include <vector>

#include "bench/engine/teach_drive.hpp"
#include "viz/figure_data.hpp"

namespace retrace::bench {

/// snapshot.png and likelihood.png (paper Fig. 4 and 5) from a snapshot.json written by
/// WriteSnapshot, over the maps of `teach`; appends the files written to `written`. Throws
/// core::IoError for a malformed file and like RenderResults.
void RenderSnapshot(const std::filesystem::path& file, const ModeTeach& teach, double robot_radius,
                    const std::filesystem::path& figures,
                    std::vector<std::filesystem::path>* written);

/// maps.png of one mode's teaching (paper Fig. 1): `world` (may be empty, as for a log) with the
/// taught trajectory coloured per map, then every partial map in its own frame. The trajectory
/// is the truth where the trace has one (`truth` says what it is: a log's is its reference),
/// else the odometry, titled so. Returns the file written; throws like RenderResults.
std::filesystem::path RenderTeachMaps(const ModeTeach& teach, const viz::WorldShapes& world,
                                      const std::filesystem::path& png,
                                      viz::RouteSource truth = viz::RouteSource::kGroundTruth);

/// Renders every figure the folder's data allows; returns the files written. Throws
/// core::IoError for unreadable results and viz::RenderError when OSMesa cannot render (the
/// numeric results are left untouched either way).
std::vector<std::filesystem::path> RenderResults(const std::filesystem::path& out);

}  // namespace retrace::bench
