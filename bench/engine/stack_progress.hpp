#pragma once
// A stack's progress along the route, worked out by the harness from the stack's own answers
// (bench/stack/navigation_stack.hpp): the metres of its current map's taught path still ahead of
// its estimate (the end conditions' stall check), and whether that map is the route's last. The
// estimate is projected onto the map's path from where it enters the map, then forward only and
// within reach of the last projection, so that a path that passes a place twice does not count
// the second pass at the first. Where it enters is the earliest point of the path within 1 m of
// the nearest one: a looped path's start, not its end, where both lie at the robot.

#include <cstddef>
#include <vector>

#include "core/path_projection.hpp"
#include "core/pose2.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::bench {

class StackProgress {
 public:
  /// The taught paths of `bundle`.
  explicit StackProgress(const nav::TeachBundle& bundle);

  /// After a control tick whose answer put the robot at X_MR in map `map`: the metres left of
  /// that map's path.
  double Remaining(std::size_t map, const core::Pose2& X_MR);
  /// Whether `map` is the route's last.
  bool IsLast(std::size_t map) const { return map + 1 == lines_.size(); }

 private:
  static constexpr double kReach = 2.0;           // m ahead of the last progress
  static constexpr double kEntryTolerance = 1.0;  // m beyond the nearest point of the path
  struct PathLine {
    std::vector<core::Vec2> points;
    std::vector<double> arc;
  };
  // The arc length where a robot at p enters the path.
  static double EntryArc(const PathLine& line, const core::Vec2& p);
  std::vector<PathLine> lines_;
  std::size_t map_ = 0;
  bool entered_ = false;
  core::ForwardProgress progress_;
};

}  // namespace retrace::bench
