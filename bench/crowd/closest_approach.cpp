#include "bench/crowd/closest_approach.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.hpp"

namespace retrace::bench {
namespace {

// Which side of a the point b lies round the origin: +1 counter-clockwise, -1 clockwise, 0 abreast
// (within 1e-6 rad: rounding must not make two people walking side by side pass each other).
std::int8_t Side(const core::Vec2& a, const core::Vec2& b) {
  const double cross = a.x() * b.y() - a.y() * b.x();
  if (std::abs(cross) <= 1e-6 * a.norm() * b.norm()) return 0;
  return cross > 0.0 ? 1 : -1;
}

}  // namespace

ClosestApproachTracker::ClosestApproachTracker(std::size_t people, double radius)
    : people_(people),
      radius_(radius),
      open_min_(people * people, -1.0),
      side_(people * people, 0),
      passed_(people * people, 0) {
  RETRACE_CHECK(radius > 0.0);
  RETRACE_CHECK(people * people < std::numeric_limits<std::uint32_t>::max());
}

void ClosestApproachTracker::OpenEncounters(const std::vector<core::Vec2>& positions) {
  RETRACE_CHECK(positions.size() == people_);
  const double r2 = radius_ * radius_;
  for (std::size_t i = 0; i < people_; ++i) {
    for (std::size_t j = i + 1; j < people_; ++j) {
      const std::size_t k = i * people_ + j;
      if (open_min_[k] >= 0.0) continue;
      const double d2 = (positions[i] - positions[j]).squaredNorm();
      if (d2 >= r2) continue;
      open_min_[k] = std::sqrt(d2);
      side_[k] = Side(positions[i], positions[j]);
      passed_[k] = 0;
      open_.push_back(static_cast<std::uint32_t>(k));
    }
  }
}

void ClosestApproachTracker::Update(const std::vector<core::Vec2>& positions) {
  RETRACE_CHECK(positions.size() == people_);
  std::size_t kept = 0;
  for (const std::uint32_t k : open_) {
    const std::size_t i = k / people_;
    const std::size_t j = k % people_;
    const double d = (positions[i] - positions[j]).norm();
    const std::int8_t side = Side(positions[i], positions[j]);
    if (side_[k] == 0) side_[k] = side;  // began abreast: the first side taken counts
    if (side != 0 && side == -side_[k]) passed_[k] = 1;
    if (d >= radius_) {
      Close(k);
      continue;
    }
    open_min_[k] = std::min(open_min_[k], d);
    open_[kept++] = k;
  }
  open_.resize(kept);
}

void ClosestApproachTracker::Close(std::uint32_t k) {
  if (passed_[k] != 0) closed_.push_back(open_min_[k]);
  open_min_[k] = -1.0;
}

ClosestApproachStats ClosestApproachTracker::Finish() {
  for (const std::uint32_t k : open_) Close(k);
  open_.clear();
  ClosestApproachStats s;
  s.encounters = static_cast<std::int64_t>(closed_.size());
  if (closed_.empty()) {
    s.mean = s.p05 = std::numeric_limits<double>::quiet_NaN();
    return s;
  }
  double sum = 0.0;
  for (const double d : closed_) sum += d;
  s.mean = sum / static_cast<double>(closed_.size());
  std::vector<double> sorted = closed_;
  const auto nth = static_cast<std::ptrdiff_t>(0.05 * static_cast<double>(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + nth, sorted.end());
  s.p05 = sorted[static_cast<std::size_t>(nth)];
  return s;
}

}  // namespace retrace::bench
