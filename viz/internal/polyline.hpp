#pragma once
// Polyline simplification for drawing: a trajectory of 20k poses covers a few thousand pixels,
// and dropping points that lie within a fraction of a pixel of the kept line is invisible but
// makes software rasterization several times cheaper.

#include <vector>

#include "core/pose2.hpp"

namespace retrace::viz::internal {

/// The subsequence of `points` (first and last kept) such that every dropped point lies within
/// `tolerance` of the kept polyline (radial pre-pass, then Douglas-Peucker). Non-finite points
/// are dropped. Units are the caller's (pixels here).
std::vector<core::Vec2> SimplifyPolyline(const std::vector<core::Vec2>& points, double tolerance);

}  // namespace retrace::viz::internal
