#include "nav/map_server.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/path_projection.hpp"

namespace retrace::nav {

MapServer::MapServer(TeachBundle bundle, const LoopConfig& loop)
    : bundle_(std::move(bundle)), loop_(loop) {
  if (bundle_.maps.empty())
    throw core::ConfigError("maps", "the teach bundle holds no partial map");
  for (const PartialMap& map : bundle_.maps) route_length_ += map.path.Length();
  if (loop_.enabled && !bundle_.maps.back().path.empty() && !bundle_.maps.front().path.empty()) {
    const core::Pose2 end_in_first = LastMapInFirst() * bundle_.maps.back().path.back();
    loops_ = core::Distance(end_in_first, bundle_.maps.front().path.front()) <=
             loop_.closure_radius + loop_.drift * route_length_;
  }
}

void MapServer::HandOver(Localizer& localizer, PathFollower& follower) {
  follower.SetPath(current().path);
  previous_tail_.clear();
  if (index_ > 0) {
    const core::Path& path = bundle_.maps[index_ - 1].path;
    const core::Pose2 X_this_previous = bundle_.maps[index_ - 1].X_MS.Inverse();
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (path.Length() - path.ArcLength(i) <= kPreviousPathReach)
        previous_tail_.push_back((X_this_previous * path[i]).translation());
    }
  }
  previous_tail_arc_ = core::CumulativeArcLength(previous_tail_);
  std::vector<core::Pose2> where = current().path.poses();
  const bool has_next = !IsLast() || loops_;
  if (has_next) {
    // The next map's frame in this one: its start is this map's switch pose (or, after the last
    // map of a loop, map 0's origin carried back through the chain).
    const std::size_t next = IsLast() ? 0 : index_ + 1;
    const core::Pose2 X_this_next = IsLast() ? LastMapInFirst().Inverse() : current().X_MS;
    const core::Path& path = bundle_.maps[next].path;
    for (std::size_t i = 0; i < path.size() && path.ArcLength(i) <= kNextPathReach; ++i) {
      where.push_back(X_this_next * path[i]);
    }
  }
  localizer.SetRecoveryPoses(std::move(where));
}

void MapServer::Start(Localizer& localizer, PathFollower& follower) {
  index_ = 0;
  localizer.SetMap(current().grid);
  HandOver(localizer, follower);
}

MapStep MapServer::Decide(const FollowerOutput& f, const core::Pose2& X_MR,
                          double max_distance) const {
  if (f.goal_reached || (f.remaining <= kPathEndTolerance && !f.off_path)) {
    if (!IsLast()) return MapStep::kNext;
    return loops_ ? MapStep::kWrap : MapStep::kDone;
  }
  if (f.off_path && previous_tail_.size() >= 2 &&
      core::ProjectOntoPath(previous_tail_, previous_tail_arc_, X_MR.translation(), 0.0,
                            previous_tail_arc_.back())
              .distance <= max_distance) {
    return MapStep::kBack;
  }
  return MapStep::kStay;
}

MapSwitch MapServer::SwitchBack(Localizer& localizer, PathFollower& follower) {
  RETRACE_CHECK(index_ > 0);
  MapSwitch s;
  s.from = index_;
  s.to = index_ - 1;
  s.X_MkR = localizer.Estimate();
  index_ = s.to;
  // The previous map's switch pose is the current map's frame in it: eq. (1) inverted.
  localizer.ApplyMapSwitch(current().grid, current().X_MS);
  HandOver(localizer, follower);
  follower.SetPathFromEnd(current().path, localizer.Estimate().translation(), kPreviousPathReach);
  s.X_MnR = localizer.Estimate();
  return s;
}

MapSwitch MapServer::SwitchToNext(Localizer& localizer, PathFollower& follower) {
  RETRACE_CHECK(!IsLast());
  MapSwitch s;
  s.from = index_;
  s.to = index_ + 1;
  s.X_MkR = localizer.Estimate();
  // X_{M_{k+1} M_k} = inverse(X_{M_k S}); applied to X_{M_k R} it is eq. (1).
  const core::Pose2 X_next_prev = current().X_MS.Inverse();
  ++index_;
  localizer.ApplyMapSwitch(current().grid, X_next_prev);
  HandOver(localizer, follower);
  s.X_MnR = localizer.Estimate();
  return s;
}

core::Pose2 MapServer::LastMapInFirst() const {
  core::Pose2 X_first_last = core::Pose2::Identity();
  for (std::size_t k = 0; k + 1 < bundle_.maps.size(); ++k)
    X_first_last = X_first_last * bundle_.maps[k].X_MS;
  return X_first_last;
}

MapSwitch MapServer::WrapToFirst(Localizer& localizer, PathFollower& follower) {
  RETRACE_CHECK(IsLast());
  MapSwitch s;
  s.from = index_;
  s.to = 0;
  s.X_MkR = localizer.Estimate();
  const core::Pose2 X_first_last = LastMapInFirst();
  index_ = 0;
  localizer.ApplyMapSwitch(current().grid, X_first_last);
  HandOver(localizer, follower);
  SpreadAfterWrap(localizer);
  s.X_MnR = localizer.Estimate();
  return s;
}

void MapServer::SpreadAfterWrap(Localizer& localizer) const {
  // The chain of switch poses carries the maps' drift over the whole loop: spread the particles
  // over what that drift allows, and let the scans find the robot again.
  const double sigma_xy = std::max(loop_.min_sigma_xy, 0.5 * loop_.drift * route_length_);
  localizer.Initialize(localizer.Estimate(), sigma_xy, loop_.min_sigma_theta);
}

}  // namespace retrace::nav
