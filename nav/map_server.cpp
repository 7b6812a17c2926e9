#include "nav/map_server.hpp"

#include <utility>

#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::nav {

MapServer::MapServer(TeachBundle bundle) : bundle_(std::move(bundle)) {
  if (bundle_.maps.empty())
    throw core::ConfigError("maps", "the teach bundle holds no partial map");
}

void MapServer::Start(Localizer& localizer, PathFollower& follower) {
  index_ = 0;
  localizer.SetMap(current().grid);
  follower.SetPath(current().path);
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
  follower.SetPath(current().path);
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
  follower.SetPath(current().path);
  s.X_MnR = localizer.Estimate();
  return s;
}

}  // namespace retrace::nav
