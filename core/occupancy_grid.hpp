#pragma once
// A 2D occupancy grid stored as log-odds per cell (0 = unknown, p = 0.5). Cell (cx, cy) covers
// [origin.x + cx*res, origin.x + (cx+1)*res) x [origin.y + cy*res, ...); row cy = 0 is the
// lowest y (ROS convention; the image file is flipped on I/O).

#include <cstdint>
#include <optional>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::core {

struct CellIndex {
  int x = 0;
  int y = 0;
  bool operator==(const CellIndex&) const = default;
};

class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  /// An all-unknown grid; resolution in m per cell, origin = world position of cell (0,0)'s
  /// lower-left corner. Throws ConfigError on a non-positive resolution or negative size.
  OccupancyGrid(int width, int height, double resolution, Vec2 origin);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Vec2& origin() const { return origin_; }
  bool empty() const { return width_ == 0 || height_ == 0; }

  bool Contains(CellIndex c) const { return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_; }
  /// The cell containing a world point (may lie outside the grid).
  CellIndex WorldToCell(const Vec2& p) const;
  /// Centre of a cell in world coordinates (m).
  Vec2 CellToWorld(CellIndex c) const;
  std::size_t Index(CellIndex c) const {
    return static_cast<std::size_t>(c.y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(c.x);
  }

  float LogOdds(CellIndex c) const { return log_odds_[Index(c)]; }
  void SetLogOdds(CellIndex c, float l) { log_odds_[Index(c)] = l; }
  double Probability(CellIndex c) const;
  void SetProbability(CellIndex c, double p);

  /// Grows the grid (keeping cell alignment and content) so that the world point p lies inside
  /// with at least `margin` cells around it. Returns the (dx, dy) shift of existing indices.
  CellIndex GrowToInclude(const Vec2& p, int margin = 0);

  const std::vector<float>& log_odds() const { return log_odds_; }
  std::vector<float>& log_odds() { return log_odds_; }

 private:
  int width_ = 0;
  int height_ = 0;
  double resolution_ = 0.05;
  Vec2 origin_ = Vec2::Zero();
  std::vector<float> log_odds_;
};

/// log(p / (1 - p)).
double Logit(double p);
/// 1 / (1 + exp(-l)).
double InverseLogit(double l);

}  // namespace retrace::core
