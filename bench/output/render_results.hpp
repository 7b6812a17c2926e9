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

namespace retrace::bench {

/// Renders every figure the folder's data allows; returns the files written. Throws
/// core::IoError for unreadable results and viz::RenderError when OSMesa cannot render (the
/// numeric results are left untouched either way).
std::vector<std::filesystem::path> RenderResults(const std::filesystem::path& out);

}  // namespace retrace::bench
