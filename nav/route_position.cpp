#include "nav/route_position.hpp"

#include <algorithm>
#include <cmath>

#include "core/angle.hpp"
#include "core/check.hpp"
#include "nav/route_graph.hpp"

namespace retrace::nav {
namespace {

// m either side of an arc length over which a path's direction is the chord's.
constexpr double kChord = 1.0;
// cos 60°: a heading within ±60° of a direction goes that way.
constexpr double kSameWay = 0.5;

// The direction of the path's chord around arc length s (rad); false for a path without length.
bool ChordDirection(const core::Path& path, double s, double* angle) {
  if (path.size() < 2 || !(path.Length() > 0.0)) return false;
  const core::Vec2 a = path.AtArcLength(std::max(0.0, s - kChord)).translation();
  const core::Vec2 b = path.AtArcLength(std::min(path.Length(), s + kChord)).translation();
  const core::Vec2 d = b - a;
  if (!(d.norm() > 1e-6)) return false;
  *angle = std::atan2(d.y(), d.x());
  return true;
}

// The arc length continued along the tangent beyond either end of the path.
double Extended(const core::Path& path, double s, const core::Vec2& p) {
  double angle = 0.0;
  if (!ChordDirection(path, s, &angle)) return s;
  const core::Vec2 t(std::cos(angle), std::sin(angle));
  if (s <= 0.0) return std::min(0.0, (p - path.positions().front()).dot(t));
  if (s >= path.Length()) return path.Length() + std::max(0.0, (p - path.positions().back()).dot(t));
  return s;
}

}  // namespace

Travel TravelOf(const core::Path& path, double s, double heading) {
  double angle = 0.0;
  if (!ChordDirection(path, s, &angle)) return Travel::kUnknown;
  const double c = std::cos(core::WrapAngle(heading - angle));
  if (c >= kSameWay) return Travel::kForward;
  if (c <= -kSameWay) return Travel::kBackward;
  return Travel::kUnknown;
}

void RouteTracker::Reset(const core::Path& path, std::size_t map, double s,
                         const core::Pose2& X_MR, Travel travel) {
  path_ = &path;
  const double length = path.Length();
  s = std::clamp(s, 0.0, length);
  const core::PathProjection here =
      core::ProjectOntoPath(path.positions(), path.arc_lengths(), X_MR.translation(), s, s);
  position_ = RoutePosition{};
  position_.map = map;
  position_.s = s;
  position_.s_extended = Extended(path, s, X_MR.translation());
  position_.distance = std::isfinite(here.distance) ? here.distance : 0.0;
  position_.travel = travel != Travel::kUnknown ? travel : TravelOf(path, s, X_MR.theta);
  last_xy_ = X_MR.translation();
  slack_ = 0.0;
  anchor_ = position_.s_extended;
}

const RoutePosition& RouteTracker::Update(const core::Pose2& X_MR, double window,
                                          double max_distance) {
  RETRACE_CHECK(path_ != nullptr);
  const core::Vec2 p = X_MR.translation();
  slack_ += (p - last_xy_).norm();
  last_xy_ = p;
  RoutePosition& pos = position_;
  if (path_->size() < 2) {
    pos.distance = Project(*path_, p).distance;
    pos.on_path = pos.distance <= max_distance;
    pos.s_extended = pos.s;
    return pos;
  }
  const double reach = window + slack_;
  const core::PathProjection near = core::ProjectOntoPath(
      path_->positions(), path_->arc_lengths(), p, pos.s - reach, pos.s + reach);
  pos.distance = near.distance;
  pos.on_path = near.distance <= max_distance;
  pos.off_path_driven = pos.on_path ? 0.0 : slack_;
  if (!pos.on_path) return pos;
  const bool rejoined = slack_ > window;
  slack_ = 0.0;
  pos.s = near.s;
  pos.s_extended = Extended(*path_, near.s, p);
  if (rejoined) {
    // Back on the path after a stretch off it: where it came back says nothing of the direction.
    anchor_ = pos.s_extended;
  } else if (pos.s_extended - anchor_ >= kTravelHysteresis) {
    pos.travel = Travel::kForward;
    anchor_ = pos.s_extended;
  } else if (anchor_ - pos.s_extended >= kTravelHysteresis) {
    pos.travel = Travel::kBackward;
    anchor_ = pos.s_extended;
  }
  return pos;
}

}  // namespace retrace::nav
