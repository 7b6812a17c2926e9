#include "bench/replay/log_localize.hpp"

#include <algorithm>
#include <cmath>

#include "bench/engine/local_truth.hpp"
#include "bench/engine/snapshot_capture.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "bench/replay/log_metrics.hpp"
#include "core/angle.hpp"
#include "core/errors.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"
#include "nav/path_follower.hpp"

namespace retrace::bench {

namespace {

// The estimate counts as at the end of its path within this much arc length of it.
constexpr double kPathEndTolerance = 0.05;  // m
// Heading spread after going round a loop: the odometry's scale error alone over-counts a full
// turn by about 1 % (3.6 degrees, sim/odometry.hpp).
constexpr double kWrapSigmaTheta = 0.0873;  // rad, 5 degrees

// The odometry increment (an arc, as wheel odometry measures it) that moves `a` to `b`: the
// heading change, and the chord turned into arc length, signed by the direction of travel.
core::OdometryDelta ArcDelta(const core::Pose2& a, const core::Pose2& b) {
  const core::Pose2 step = core::Between(a, b);
  const double half = 0.5 * step.theta;
  const double chord = std::hypot(step.x, step.y);
  const double arc = std::abs(half) < 1e-9 ? chord : chord * half / std::sin(half);
  return {step.x >= 0.0 ? arc : -arc, step.theta};
}

// Consecutive odometry samples are merged into one prediction while the arc from the first to
// the last ends this close to the last (the arc leaves the chord at half the heading change).
constexpr double kArcTolerance = 0.001;  // m

// Predicts from `from` (at from_stamp) through the odometry samples strictly between the two
// stamps to `to`, in as few arcs as kArcTolerance allows: the motion model's variance grows
// linearly with distance and turn, so merging samples changes the spread of the particles only
// through the arcs' shape, while a dense log (odometry at 50 Hz and more) costs one prediction per
// scan instead of one per message.
void PredictBetween(nav::Localizer& localizer, const std::vector<io::StampedPose>& odometry,
                    double from_stamp, const core::Pose2& from, double to_stamp,
                    const core::Pose2& to) {
  core::Pose2 anchor = from;  // where the arc being extended starts
  core::Pose2 previous = from;
  const auto on_arc = [&](const core::Pose2& end) {
    const core::Pose2 step = core::Between(anchor, end);
    const double half = 0.5 * step.theta;  // the arc's chord points at half the turn
    return std::abs(-std::sin(half) * step.x + std::cos(half) * step.y) <= kArcTolerance;
  };
  auto it = std::upper_bound(odometry.begin(), odometry.end(), from_stamp,
                             [](double s, const io::StampedPose& p) { return s < p.t; });
  for (; it != odometry.end() && it->t < to_stamp; ++it) {
    if (!on_arc(it->pose)) {
      localizer.Predict(ArcDelta(anchor, previous));
      anchor = previous;
    }
    previous = it->pose;
  }
  if (!on_arc(to)) {
    localizer.Predict(ArcDelta(anchor, previous));
    anchor = previous;
  }
  localizer.Predict(ArcDelta(anchor, to));
}

}  // namespace

LogLocalizeResult RunLogLocalize(const logs::LogIndex& index, const LogStreams& streams,
                                 const ModeTeach& teach, const LogConfig& config,
                                 const LogWindow& window,
                                 const std::optional<core::Pose2>& initial) {
  const double cpu_start = ThreadCpuSeconds();
  if (teach.trace.maps.size() != teach.bundle.maps.size()) {
    throw core::ConfigError("--teach", "the teach folder's reference traces (" +
                                           std::to_string(teach.trace.maps.size()) +
                                           ") do not match its maps (" +
                                           std::to_string(teach.bundle.maps.size()) + ")");
  }
  const bool truth = !streams.reference.empty() && !teach.trace.X_WR.empty();
  const core::Rng rng = core::Rng(config.seed).Split("log-localize");
  nav::Localizer localizer(config.nav.localizer, streams.robot, rng.Split("localizer"));
  nav::PathFollower follower(config.nav.follower);
  nav::MapServer server(teach.bundle);
  server.Start(localizer, follower);

  // A loop — its last path ends where its first began, chained through the switch poses, within
  // the revisit radius plus the drift allowed over the route — is driven again after its last
  // map.
  double route_length = 0.0;
  for (const nav::PartialMap& map : teach.bundle.maps) route_length += map.path.Length();
  const core::Pose2 end_in_first = server.LastMapInFirst() * teach.bundle.maps.back().path.back();
  const bool loop = core::Distance(end_in_first, teach.bundle.maps.front().path.front()) <=
                    config.route.revisit_radius + config.route.online_drift * route_length;
  // The spread after going round: the drift allowed over the route as two standard deviations.
  const double wrap_sigma_xy =
      std::max(config.playback.initial_sigma_xy, 0.5 * config.route.online_drift * route_length);
  const double wrap_sigma_theta =
      std::max(core::DegToRad(config.playback.initial_sigma_yaw_deg), kWrapSigmaTheta);

  LogLocalizeResult result;
  result.loop = loop;
  std::optional<LocalTruth> local;
  std::optional<double> previous_stamp;
  core::Pose2 previous_X_OR;
  int most_rejected = -1;
  bool started = false;

  logs::ReadScans(index, window.from_s, window.to_s, [&](const logs::ScanMessage& m, double t) {
    const double stamp = m.scan.stamp;
    const std::optional<core::Pose2> X_OR = logs::PoseAt(streams.odometry, stamp);
    if (!X_OR) {
      ++result.scans_outside;
      return;
    }
    const std::optional<core::Pose2> X_WR =
        streams.reference.empty() ? std::nullopt : logs::PoseAt(streams.reference, stamp);
    if (truth && !local) {
      local.emplace(teach.trace.maps.at(server.index()), config.metrics.match_window,
                    config.metrics.match_fallback_distance);
    }
    std::optional<core::Pose2> X_MR_truth;
    if (local && X_WR) X_MR_truth = local->InMap(*X_WR);

    if (!started) {
      started = true;
      result.first_s = t;
      const core::Pose2 start =
          initial ? *initial : (X_MR_truth ? *X_MR_truth : core::Pose2::Identity());
      localizer.Initialize(start, config.playback.initial_sigma_xy,
                           core::DegToRad(config.playback.initial_sigma_yaw_deg));
    } else {
      PredictBetween(localizer, streams.odometry, *previous_stamp, previous_X_OR, stamp, *X_OR);
    }
    const double dt = previous_stamp ? std::max(stamp - *previous_stamp, 1e-3) : 0.1;
    previous_stamp = stamp;
    previous_X_OR = *X_OR;
    result.last_s = t;

    const double cpu0 = ThreadCpuSeconds();
    const nav::LocalizerUpdate update = localizer.Update(m.scan);
    if (update.ran) {
      LocalizerSample u;
      u.time = stamp;
      u.beams_tested = update.beams_tested;
      u.beams_rejected = update.beams_rejected;
      u.spread = update.spread;
      u.rejection_particles = update.rejection_particles;
      u.cpu_s = ThreadCpuSeconds() - cpu0;
      result.updates.push_back(u);
    }
    core::Pose2 estimate = localizer.Estimate();
    const nav::FollowerOutput follow = follower.Compute(estimate, dt);
    // Fig. 4 and 5: the update with the most rejected beams on the taught route (the estimate
    // within kOnRoute of its path) while localized (within metrics.lost_error of the local
    // truth, when there is one). Off the route a map misses what the scan sees, and those
    // beams are rejected for that.
    if (update.ran && update.beams_rejected > most_rejected &&
        std::abs(follow.lateral_error) <= kOnRoute &&
        (!X_MR_truth || Compare(estimate, *X_MR_truth).distance <= config.metrics.lost_error)) {
      most_rejected = update.beams_rejected;
      const core::Pose2 centre = X_MR_truth ? *X_MR_truth : estimate;
      result.snapshot =
          CaptureSnapshot(localizer, update, m.scan, {}, stamp, static_cast<int>(server.index()),
                          X_WR.value_or(core::Pose2::Identity()), centre, {});
    }
    // The map switch at the end of the taught path (eq. 1), as in playback.
    const bool at_end = follow.goal_reached || follow.remaining <= kPathEndTolerance;
    if (at_end && (!server.IsLast() || loop)) {
      const bool wrap = server.IsLast();
      if (wrap) ++result.laps_completed;
      const nav::MapSwitch s =
          wrap ? server.WrapToFirst(localizer, follower) : server.SwitchToNext(localizer, follower);
      if (wrap) {
        // The chain of switch poses carries the maps' drift over the whole loop: spread the
        // particles over what that drift allows, and let the scans find the robot again.
        localizer.Initialize(localizer.Estimate(), wrap_sigma_xy, wrap_sigma_theta);
      }
      estimate = localizer.Estimate();
      result.switches.push_back({stamp, static_cast<int>(s.from), static_cast<int>(s.to),
                                 X_WR.value_or(core::Pose2::Identity()), s.X_MnR});
      if (truth) {
        local.emplace(teach.trace.maps.at(server.index()), config.metrics.match_window,
                      config.metrics.match_fallback_distance);
        if (X_WR) X_MR_truth = local->InMap(*X_WR);
      }
    } else if (at_end) {
      result.laps_completed = std::max(result.laps_completed, 1);
    }
    result.samples.push_back({stamp, static_cast<int>(server.index()), estimate, X_WR, X_MR_truth});
  });
  if (result.samples.empty()) {
    throw core::IoError(index.name + ": no scan with odometry between " +
                        core::FormatNumber(window.from_s) + " and " +
                        core::FormatNumber(window.to_s) + " s of the log");
  }
  result.cpu_time_s = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace retrace::bench
