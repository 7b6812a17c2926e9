#include "bench/engine/stack_progress.hpp"

#include <algorithm>
#include <limits>

#include "core/check.hpp"

namespace retrace::bench {

StackProgress::StackProgress(const nav::TeachBundle& bundle) {
  for (const nav::PartialMap& map : bundle.maps) {
    PathLine& line = lines_.emplace_back();
    for (const core::Pose2& p : map.path.poses()) line.points.push_back(p.translation());
    line.arc = core::CumulativeArcLength(line.points);
  }
}

double StackProgress::EntryArc(const PathLine& line, const core::Vec2& p) {
  if (line.points.empty()) return 0.0;
  double nearest = std::numeric_limits<double>::infinity();
  for (const core::Vec2& q : line.points) nearest = std::min(nearest, (q - p).norm());
  for (std::size_t i = 0; i < line.points.size(); ++i) {
    if ((line.points[i] - p).norm() <= nearest + kEntryTolerance) return line.arc[i];
  }
  return 0.0;
}

double StackProgress::Remaining(std::size_t map, const core::Pose2& X_MR) {
  RETRACE_CHECK(map < lines_.size());
  const PathLine& line = lines_[map];
  if (map != map_ || !entered_) {
    progress_ = {};
    progress_.MoveTo(EntryArc(line, X_MR.translation()));
    entered_ = true;
    map_ = map;
  }
  const double s =
      progress_.Advance(line.points, line.arc, X_MR.translation(), progress_.value() + kReach);
  return line.arc.empty() ? 0.0 : line.arc.back() - s;
}

}  // namespace retrace::bench
