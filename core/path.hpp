#pragma once

#include <cstddef>
#include <vector>

#include "core/pose2.hpp"

namespace retrace::core {

/// An ordered sequence of poses (a taught trajectory or a route) with cumulative arc length.
class Path {
 public:
  Path() = default;
  explicit Path(std::vector<Pose2> poses);

  const std::vector<Pose2>& poses() const { return poses_; }
  std::size_t size() const { return poses_.size(); }
  bool empty() const { return poses_.empty(); }
  const Pose2& operator[](std::size_t i) const { return poses_[i]; }
  const Pose2& front() const { return poses_.front(); }
  const Pose2& back() const { return poses_.back(); }

  void PushBack(const Pose2& p);
  /// The positions of the poses (m), and the arc length at each (m): the polyline that
  /// core/path_projection.hpp projects onto.
  const std::vector<Vec2>& positions() const { return positions_; }
  const std::vector<double>& arc_lengths() const { return arc_; }
  /// Total length of the polyline through the positions (m).
  double Length() const { return arc_.empty() ? 0.0 : arc_.back(); }
  /// Arc length from the first pose to pose i (m).
  double ArcLength(std::size_t i) const { return arc_[i]; }
  /// Pose at arc length s (m), interpolated; clamped to the ends.
  Pose2 AtArcLength(double s) const;

 private:
  std::vector<Pose2> poses_;
  std::vector<Vec2> positions_;
  std::vector<double> arc_;
};

}  // namespace retrace::core
