#include "core/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::core {

OccupancyGrid::OccupancyGrid(int width, int height, double resolution, Vec2 origin)
    : width_(width), height_(height), resolution_(resolution), origin_(origin) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw ConfigError("resolution", "must be a positive number of metres per cell");
  }
  if (width < 0 || height < 0) throw ConfigError("size", "grid size must not be negative");
  log_odds_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f);
}

CellIndex OccupancyGrid::WorldToCell(const Vec2& p) const {
  return {static_cast<int>(std::floor((p.x() - origin_.x()) / resolution_)),
          static_cast<int>(std::floor((p.y() - origin_.y()) / resolution_))};
}

Vec2 OccupancyGrid::CellToWorld(CellIndex c) const {
  return {origin_.x() + (c.x + 0.5) * resolution_, origin_.y() + (c.y + 0.5) * resolution_};
}

double OccupancyGrid::Probability(CellIndex c) const { return InverseLogit(LogOdds(c)); }

void OccupancyGrid::SetProbability(CellIndex c, double p) {
  SetLogOdds(c, static_cast<float>(Logit(p)));
}

CellIndex OccupancyGrid::GrowToInclude(const Vec2& p, int margin) {
  RETRACE_CHECK(margin >= 0);
  const CellIndex c = WorldToCell(p);
  const int add_left = std::max(0, margin - c.x);
  const int add_bottom = std::max(0, margin - c.y);
  const int add_right = std::max(0, c.x + margin + 1 - width_);
  const int add_top = std::max(0, c.y + margin + 1 - height_);
  if (add_left == 0 && add_bottom == 0 && add_right == 0 && add_top == 0) return {0, 0};
  // Grow in chunks so that a robot driving away does not reallocate every keyframe.
  const int chunk = 64;
  const int left = add_left > 0 ? add_left + chunk : 0;
  const int bottom = add_bottom > 0 ? add_bottom + chunk : 0;
  const int right = add_right > 0 ? add_right + chunk : 0;
  const int top = add_top > 0 ? add_top + chunk : 0;
  const int new_w = width_ + left + right;
  const int new_h = height_ + bottom + top;
  std::vector<float> grown(static_cast<std::size_t>(new_w) * static_cast<std::size_t>(new_h), 0.0f);
  for (int y = 0; y < height_; ++y) {
    std::copy_n(log_odds_.begin() + static_cast<std::ptrdiff_t>(y) * width_, width_,
                grown.begin() + static_cast<std::ptrdiff_t>(y + bottom) * new_w + left);
  }
  log_odds_ = std::move(grown);
  width_ = new_w;
  height_ = new_h;
  origin_ -= Vec2(left * resolution_, bottom * resolution_);
  return {left, bottom};
}

double Logit(double p) { return std::log(p / (1.0 - p)); }
double InverseLogit(double l) { return 1.0 / (1.0 + std::exp(-l)); }

}  // namespace retrace::core
