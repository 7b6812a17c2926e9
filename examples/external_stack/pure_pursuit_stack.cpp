#include "pure_pursuit_stack.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "bench/engine/stack_registry.hpp"
#include "core/twist.hpp"

namespace external {

namespace bench = retrace::bench;
namespace core = retrace::core;

namespace {

constexpr std::size_t kSearchWindow = 40;  // path points ahead searched for the nearest
constexpr double kEndReached = 0.3;        // m from a path's last point: its end is reached
constexpr double kFrontHalfAngle = 20.0 * M_PI / 180.0;
constexpr double kMaxTurnRate = 1.0;       // rad/s

}  // namespace

PurePursuitStack::PurePursuitStack(std::vector<TaughtPath> paths, PurePursuitOptions options)
    : paths_(std::move(paths)), options_(options) {}

void PurePursuitStack::OnOdometry(double /*t*/, const core::OdometryDelta& delta) {
  X_MR_ = core::IntegrateOdometry(X_MR_, delta);
}

void PurePursuitStack::OnScan(const core::LaserScan& scan) {
  // The scan is in the LiDAR's frame; near the robot's centre that is close enough to its front.
  const double reach = options_.robot_radius + options_.stop_distance;
  blocked_ = false;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (scan.Valid(i) && std::abs(scan.Angle(i)) < kFrontHalfAngle && scan.ranges[i] < reach) {
      blocked_ = true;
    }
  }
}

bench::StackOutput PurePursuitStack::OnControlTick(double /*t*/, double /*dt*/) {
  bench::StackOutput out;
  const std::vector<core::Pose2>* path = &paths_[map_].poses;
  // The nearest of the next path points: progress only forwards.
  const std::size_t end = std::min(path->size(), reached_ + kSearchWindow);
  double nearest = core::Distance((*path)[reached_], X_MR_);
  for (std::size_t i = reached_ + 1; i < end; ++i) {
    if (const double d = core::Distance((*path)[i], X_MR_); d < nearest) nearest = d, reached_ = i;
  }
  if (reached_ + 1 == path->size() && nearest < kEndReached) {
    if (map_ + 1 == paths_.size()) {
      out.X_MR = X_MR_;
      out.map = map_;
      out.route_done = true;
      return out;  // a zero command: the route is done
    }
    // Eq. (1): into the next map, whose frame starts at this map's switch pose.
    const core::Pose2 X_MkR = X_MR_;
    X_MR_ = paths_[map_].X_MS.Inverse() * X_MR_;
    out.map_change = bench::MapChange{map_, map_ + 1, X_MkR, X_MR_};
    ++map_;
    reached_ = 0;
    path = &paths_[map_].poses;
  }
  std::size_t goal = reached_;
  while (goal + 1 < path->size() && core::Distance((*path)[goal], X_MR_) < options_.lookahead) {
    ++goal;
  }
  const core::Vec2 local = X_MR_.Inverse() * (*path)[goal].translation();
  const double curvature = 2.0 * local.y() / std::max(local.squaredNorm(), 1e-6);
  const double v = blocked_ ? 0.0 : options_.speed;
  out.drive.command.v = v;
  out.drive.command.omega = std::clamp(v * curvature, -kMaxTurnRate, kMaxTurnRate);
  out.drive.blocked = blocked_;
  out.X_MR = X_MR_;
  out.map = map_;
  return out;
}

void RegisterPurePursuit() {
  constexpr auto kNumber = bench::StackOption::Kind::kNumber;
  bench::RegisterStack({
      .name = "pure_pursuit",
      .summary = "the taught paths by pure pursuit on odometry, stopping for what is just ahead",
      .options = {{"speed", "0.6", "m/s", kNumber},
                  {"lookahead", "0.8", "m: the path point steered at", kNumber},
                  {"stop_distance", "0.25", "m beyond the robot's radius", kNumber}},
      .make = [](const bench::StackContext& context) -> std::unique_ptr<bench::NavigationStack> {
        std::vector<TaughtPath> paths;
        for (const auto& map : context.bundle.maps) {
          paths.push_back({map.path.poses(), map.X_MS});
        }
        PurePursuitOptions options;
        options.speed = context.Number("speed");
        options.lookahead = context.Number("lookahead");
        options.stop_distance = context.Number("stop_distance");
        options.robot_radius = context.scenario.robot.radius;
        return std::make_unique<PurePursuitStack>(std::move(paths), options);
      },
  });
}

}  // namespace external
