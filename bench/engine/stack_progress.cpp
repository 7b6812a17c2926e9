#include "bench/engine/stack_progress.hpp"

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

double StackProgress::Remaining(std::size_t map, const core::Pose2& X_MR) {
  RETRACE_CHECK(map < lines_.size());
  const PathLine& line = lines_[map];
  if (map != map_ || !entered_) {
    progress_ = {};
    const double inf = std::numeric_limits<double>::infinity();
    progress_.MoveTo(core::ProjectOntoPath(line.points, line.arc, X_MR.translation(), 0.0, inf).s);
    entered_ = true;
    map_ = map;
  }
  const double s =
      progress_.Advance(line.points, line.arc, X_MR.translation(), progress_.value() + kReach);
  return line.arc.empty() ? 0.0 : line.arc.back() - s;
}

}  // namespace retrace::bench
