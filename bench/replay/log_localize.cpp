#include "bench/replay/log_localize.hpp"

#include <algorithm>
#include <cmath>

#include "bench/engine/local_truth.hpp"
#include "bench/engine/snapshot_capture.hpp"
#include "bench/engine/thread_cpu_time.hpp"
#include "bench/engine/update_score.hpp"
#include "bench/replay/log_metrics.hpp"
#include "core/angle.hpp"
#include "core/errors.hpp"
#include "nav/navigator.hpp"

namespace retrace::bench {

namespace {

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

// Feeds the navigator the odometry between consecutive scans. By default in as few arcs as
// kArcTolerance allows, from the pose interpolated at one scan's stamp to the next's: the motion
// model's variance grows linearly with distance and turn, so merging samples changes the spread of
// the particles only through the arcs' shape, while a dense log (odometry at 50 Hz and more) costs
// one prediction per scan instead of one per message. With `every_tick`, one prediction per
// odometry message up to the scan's stamp (a message at the stamp included), each from the
// previous message, and none for a message that did not move: exactly the increments the
// simulator's playback predicts with.
class OdometryFeed {
 public:
  OdometryFeed(const std::vector<io::StampedPose>& odometry, bool every_tick)
      : odometry_(odometry), every_tick_(every_tick) {}

  // The navigator started at the first scan, at `stamp`, where the odometry reads X_OR; with
  // every_tick and `from_first_message`, at the log's first odometry message instead (the
  // increments up to the first scan are still to be predicted, as playback predicts them).
  void Start(nav::Navigator& nav, double stamp, const core::Pose2& X_OR, bool from_first_message) {
    stamp_ = stamp;
    X_OR_ = X_OR;
    next_ = First(stamp);
    if (!every_tick_) return;
    if (from_first_message && !odometry_.empty() && odometry_.front().t <= stamp) {
      X_OR_ = odometry_.front().pose;
      next_ = 1;
      To(nav, stamp, X_OR);
    } else if (next_ > 0) {
      X_OR_ = odometry_[next_ - 1].pose;
    }
  }

  // Predicts up to the next scan, at `stamp`, where the odometry reads X_OR.
  void To(nav::Navigator& nav, double stamp, const core::Pose2& X_OR) {
    if (every_tick_) {
      for (; next_ < odometry_.size() && odometry_[next_].t <= stamp; ++next_) {
        const core::Pose2& X = odometry_[next_].pose;
        if (X == X_OR_) continue;
        nav.OnOdometry(ArcDelta(X_OR_, X));
        X_OR_ = X;
      }
      stamp_ = stamp;
      return;
    }
    core::Pose2 anchor = X_OR_;  // where the arc being extended starts
    core::Pose2 previous = X_OR_;
    const auto on_arc = [&](const core::Pose2& end) {
      const core::Pose2 step = core::Between(anchor, end);
      const double half = 0.5 * step.theta;  // the arc's chord points at half the turn
      return std::abs(-std::sin(half) * step.x + std::cos(half) * step.y) <= kArcTolerance;
    };
    for (std::size_t i = First(stamp_); i < odometry_.size() && odometry_[i].t < stamp; ++i) {
      if (!on_arc(odometry_[i].pose)) {
        nav.OnOdometry(ArcDelta(anchor, previous));
        anchor = previous;
      }
      previous = odometry_[i].pose;
    }
    if (!on_arc(X_OR)) {
      nav.OnOdometry(ArcDelta(anchor, previous));
      anchor = previous;
    }
    nav.OnOdometry(ArcDelta(anchor, X_OR));
    stamp_ = stamp;
    X_OR_ = X_OR;
  }

 private:
  // The first message stamped after `stamp`.
  std::size_t First(double stamp) const {
    return static_cast<std::size_t>(
        std::upper_bound(odometry_.begin(), odometry_.end(), stamp,
                         [](double s, const io::StampedPose& p) { return s < p.t; }) -
        odometry_.begin());
  }

  const std::vector<io::StampedPose>& odometry_;
  bool every_tick_;
  double stamp_ = 0.0;
  core::Pose2 X_OR_;   // the pose predicted up to
  std::size_t next_ = 0;  // every_tick: the first message not yet predicted
};

}  // namespace

core::Rng LogLocalizeRng(std::uint64_t seed) {
  return core::Rng(seed).Split("playback").Split(0).Split("localizer");
}

namespace {

// The replay of one log: per scan, the navigator's step and what the metrics keep of it.
class LogReplay {
 public:
  LogReplay(const LogStreams& streams, const ModeTeach& teach, const LogConfig& config,
            const LogWindow& window, const LogReplayOptions& options)
      : streams_(streams),
        config_(config),
        options_(options),
        from_log_start_(window.from_s <= 0.0),
        nav_(config.nav.localizer, config.nav.follower, streams.robot, teach.bundle,
             config.nav.map_server, config.route.Link(), true, LogLocalizeRng(config.seed)),
        feed_(streams.odometry, options.every_odometry_tick) {
    result_.loop = nav_.server().loops();
    if (!streams.reference.empty() && !teach.trace.X_WR.empty()) {
      local_.emplace(teach.trace, config.metrics.match_window,
                     config.metrics.match_fallback_distance);
    }
  }

  void OnScan(const logs::ScanMessage& m, double t) {
    const double stamp = m.scan.stamp;
    const std::optional<core::Pose2> X_OR = logs::PoseAt(streams_.odometry, stamp);
    if (!X_OR) {
      ++result_.scans_outside;
      return;
    }
    const std::optional<core::Pose2> X_WR =
        streams_.reference.empty() ? std::nullopt : logs::PoseAt(streams_.reference, stamp);
    std::optional<core::Pose2> X_MR_truth;
    if (local_ && X_WR) X_MR_truth = local_->InMap(*X_WR);
    Predict(stamp, t, *X_OR, X_WR, &X_MR_truth);
    const double dt = previous_stamp_ ? std::max(stamp - *previous_stamp_, 1e-3) : 0.1;
    previous_stamp_ = stamp;
    result_.last_s = t;

    const double cpu0 = ThreadCpuSeconds();
    const nav::LocalizerUpdate update = nav_.OnScan(m.scan);
    if (update.ran) {
      result_.updates.push_back(ScoreUpdate(update, stamp, ThreadCpuSeconds() - cpu0, {}));
    }
    const core::Pose2 before = nav_.Estimate();
    const nav::NavigatorTick tick = nav_.OnControlTick(dt);
    if (!tick.map_switch) KeepSnapshot(m.scan, update, tick, before, X_WR, X_MR_truth);
    if (tick.map_switch) {
      OnSwitch(stamp, tick, X_WR);
      if (local_ && X_WR) X_MR_truth = local_->InMap(*X_WR);
    } else if (tick.route_done) {
      result_.laps_completed = std::max(result_.laps_completed, 1);
    }
    result_.samples.push_back({stamp, static_cast<int>(nav_.server().index()), nav_.Estimate(),
                               *X_OR, nav_.localizer().lost(), tick.off_map, X_WR, X_MR_truth});
  }

  LogLocalizeResult Finish(double cpu_time_s) {
    result_.cpu_time_s = cpu_time_s;
    return std::move(result_);
  }
  bool empty() const { return result_.samples.empty(); }

 private:
  // The first scan starts the navigator in the map nearest the start: `initial` (in map 0's
  // frame) carried through the route graph, else the map whose taught trace passes nearest the
  // reference and the local truth there, else map 0's origin. Every later scan gets the
  // odometry since the one before.
  void Predict(double stamp, double t, const core::Pose2& X_OR,
               const std::optional<core::Pose2>& X_WR, std::optional<core::Pose2>* X_MR_truth) {
    if (previous_stamp_) {
      feed_.To(nav_, stamp, X_OR);
      return;
    }
    result_.first_s = t;
    const double sigma_xy = config_.playback.initial_sigma_xy;
    const double sigma_theta = core::DegToRad(config_.playback.initial_sigma_yaw_deg);
    if (options_.initial) {
      nav_.StartNearest(*options_.initial, sigma_xy, sigma_theta);
      if (local_ && X_WR) {  // the local truth in the map the navigator chose
        local_->Enter(nav_.server().index());
        *X_MR_truth = local_->InMap(*X_WR);
      }
    } else if (local_ && X_WR) {
      const std::size_t map = local_->NearestMap(*X_WR);
      local_->Enter(map);
      *X_MR_truth = local_->InMap(*X_WR);
      nav_.Start(map, **X_MR_truth, sigma_xy, sigma_theta);
    } else {
      nav_.Start(0, core::Pose2::Identity(), sigma_xy, sigma_theta);
    }
    feed_.Start(nav_, stamp, X_OR, from_log_start_);
  }

  // Fig. 4 and 5: the update with the most rejected beams on the taught route (the estimate
  // within kOnRoute of its path) while localized (within metrics.lost_error of the local truth,
  // when there is one). Off the route a map misses what the scan sees, and those beams are
  // rejected for that.
  void KeepSnapshot(const core::LaserScan& scan, const nav::LocalizerUpdate& update,
                    const nav::NavigatorTick& tick, const core::Pose2& X_MR,
                    const std::optional<core::Pose2>& X_WR,
                    const std::optional<core::Pose2>& X_MR_truth) {
    if (!update.ran || update.beams_rejected <= most_rejected_ ||
        std::abs(tick.follow.lateral_error) > kOnRoute ||
        (X_MR_truth && Compare(X_MR, *X_MR_truth).distance > config_.metrics.lost_error)) {
      return;
    }
    most_rejected_ = update.beams_rejected;
    result_.snapshot = CaptureSnapshot(nav_.localizer(), update, scan, {}, scan.stamp,
                                       static_cast<int>(nav_.server().index()),
                                       X_WR.value_or(core::Pose2::Identity()),
                                       X_MR_truth.value_or(X_MR), {});
  }

  // A map switch or a loop's wrap: recorded, and the local truth re-anchored in the new map.
  void OnSwitch(double stamp, const nav::NavigatorTick& tick,
                const std::optional<core::Pose2>& X_WR) {
    if (tick.wrapped) ++result_.laps_completed;
    result_.switches.push_back({stamp, static_cast<int>(tick.map_switch->from),
                                static_cast<int>(tick.map_switch->to),
                                X_WR.value_or(core::Pose2::Identity()), tick.map_switch->X_MnR});
    if (local_) local_->Enter(tick.map_switch->to);
  }

  const LogStreams& streams_;
  const LogConfig& config_;
  const LogReplayOptions& options_;
  bool from_log_start_;
  nav::Navigator nav_;
  OdometryFeed feed_;
  std::optional<LocalTruthAcrossMaps> local_;
  std::optional<double> previous_stamp_;
  int most_rejected_ = -1;
  LogLocalizeResult result_;
};

}  // namespace

LogLocalizeResult RunLogLocalize(const logs::LogIndex& index, const LogStreams& streams,
                                 const ModeTeach& teach, const LogConfig& config,
                                 const LogWindow& window, const LogReplayOptions& options) {
  const double cpu_start = ThreadCpuSeconds();
  if (teach.trace.maps.size() != teach.bundle.maps.size()) {
    throw core::ConfigError("--teach", "the teach folder's reference traces (" +
                                           std::to_string(teach.trace.maps.size()) +
                                           ") do not match its maps (" +
                                           std::to_string(teach.bundle.maps.size()) + ")");
  }
  LogReplay replay(streams, teach, config, window, options);
  logs::ReadScans(index, window.from_s, window.to_s,
                  [&](const logs::ScanMessage& m, double t) { replay.OnScan(m, t); });
  if (replay.empty()) {
    throw core::IoError(index.name + ": no scan with odometry between " +
                        core::FormatNumber(window.from_s) + " and " +
                        core::FormatNumber(window.to_s) + " s of the log");
  }
  return replay.Finish(ThreadCpuSeconds() - cpu_start);
}

}  // namespace retrace::bench
