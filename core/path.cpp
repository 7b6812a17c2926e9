#include "core/path.hpp"

#include <algorithm>
#include <limits>

#include "core/check.hpp"

namespace retrace::core {

Path::Path(std::vector<Pose2> poses) {
  poses_.reserve(poses.size());
  positions_.reserve(poses.size());
  arc_.reserve(poses.size());
  for (const Pose2& p : poses) PushBack(p);
}

void Path::PushBack(const Pose2& p) {
  arc_.push_back(poses_.empty() ? 0.0 : arc_.back() + Distance(poses_.back(), p));
  poses_.push_back(p);
  positions_.push_back(p.translation());
}

Pose2 Path::AtArcLength(double s) const {
  RETRACE_CHECK(!poses_.empty());
  if (s <= 0.0 || poses_.size() == 1) return poses_.front();
  if (s >= arc_.back()) return poses_.back();
  const auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
  const std::size_t i = static_cast<std::size_t>(it - arc_.begin());  // arc_[i-1] <= s < arc_[i]
  const double seg = arc_[i] - arc_[i - 1];
  const double t = seg > 0.0 ? (s - arc_[i - 1]) / seg : 0.0;
  return Interpolate(poses_[i - 1], poses_[i], t);
}

}  // namespace retrace::core
