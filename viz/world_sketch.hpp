#pragma once
// A quick top-down drawing of a world (OpenCV): solids, edges, circles, pedestrians, a route
// and the robot. The OSMesa renderer for the paper's figures comes later; this one is for
// checking world files.

#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::viz {

using core::Vec2;

/// What to draw, in W (m).
struct SketchScene {
  std::vector<std::vector<Vec2>> solids;      ///< filled polygons
  std::vector<std::pair<Vec2, Vec2>> edges;   ///< thin edges (imported maps)
  std::vector<std::pair<Vec2, double>> discs; ///< static circles: centre, radius
  std::vector<std::pair<Vec2, double>> pedestrians;
  std::vector<Vec2> route;
  std::optional<core::Pose2> robot;
  double robot_radius = 0.3;
};

struct SketchOptions {
  double pixels_per_meter = 20.0;
  int max_pixels = 4000;  ///< the longer side is capped by lowering pixels_per_meter
  double margin = 1.0;    ///< m around the scene
};

/// Renders the scene to a PNG file (written atomically). Throws core::IoError on failure.
void RenderSketchPng(const SketchScene& scene, const std::filesystem::path& png,
                     const SketchOptions& options = {});

}  // namespace retrace::viz
