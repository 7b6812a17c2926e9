#pragma once
// One step of the repeating robot's navigation (docs/DESIGN.md §5, the Navigator): the
// localizer, the map server and the path follower, driven by odometry increments, scans and
// control ticks. The simulator's playback and a log's replay are two sources of the same inputs
// and call exactly this: predict on every odometry increment, update on every scan, and at every
// control tick the follower's command from the estimate and the map server's one rule for
// switching maps or wrapping a loop. Obstacle avoidance, which needs a robot to command, stays
// with the caller.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"
#include "core/rng.hpp"
#include "core/twist.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"
#include "nav/path_follower.hpp"
#include "nav/robot_geometry.hpp"
#include "nav/route_position.hpp"
#include "nav/teach_bundle.hpp"

namespace retrace::nav {

/// What one control tick decided.
struct NavigatorTick {
  FollowerOutput follow;                ///< the follower's output, after any switch
  std::optional<MapSwitch> map_switch;  ///< the switch or wrap made at this tick
  bool wrapped = false;                 ///< map_switch went from the last map back to map 0
  bool route_done = false;              ///< at the end of the last path (and no loop to go on)
  /// The command was held to follower.creep_speed: the localizer is lost, the robot is off map,
  /// or a re-acquisition has not held for augmented.confirm_updates updates yet.
  bool creeping = false;
  /// No map covers the robot's place (MapStep::kOffMap): the estimate runs on odometry alone.
  bool off_map = false;
  /// The share of the last scan's tested beams the current map covers (1 before any scan).
  double coverage = 1.0;
};

class Navigator {
 public:
  /// The map server's options, route link and loop as MapServer's. Throws core::ConfigError for
  /// an invalid config or a bundle without maps.
  Navigator(const LocalizerConfig& localizer, const PathFollowerConfig& follower,
            const RobotGeometry& robot, TeachBundle bundle, const MapServerConfig& server,
            const RouteLinkConfig& link, bool loop, core::Rng localizer_rng);

  /// Map `map` and its path, the follower's progress where X_MR lies on it, and the particles
  /// drawn around X_MR (Localizer::Initialize).
  void Start(std::size_t map, const core::Pose2& X_MR, double sigma_xy, double sigma_theta);
  /// As Start, in the map whose taught path lies nearest X_M0R, a pose given in map 0's frame
  /// (MapServer::NearestMap): a run that begins mid-route begins in the map that holds it.
  void StartNearest(const core::Pose2& X_M0R, double sigma_xy, double sigma_theta);
  /// One odometry increment (robot frame), to the belief and to a settling switch's.
  void OnOdometry(const core::OdometryDelta& delta);
  /// One scan (LiDAR frame); the update is gated on motion (Localizer::Update), and skipped
  /// while the robot is off map. A settling switch's belief takes it too. Its tested beams are
  /// what the next control tick's map decision weighs the maps' coverage on.
  LocalizerUpdate OnScan(const core::LaserScan& scan);
  /// One control tick, dt s after the previous one: the follower on the estimate, the robot's
  /// place on the route tracked along the current path (nav/route_position.hpp), then the map
  /// server's rule (MapServer::Decide); after a switch the follower runs again on the new path.
  /// A switch whose transform may be off by more than min_sigma_xy settles first
  /// (MapServerConfig::settle_rms): until it commits, the estimate and the follower stay in the
  /// map left. The rule asking for another map restarts it; the end of the route abandons it.
  /// While the localizer is lost, and for augmented.confirm_updates updates after a
  /// re-acquisition, the command is held to follower.creep_speed (its turn rate scaled alike).
  NavigatorTick OnControlTick(double dt);

  /// After an operator drove the robot and handed it back: the map and the place on its path
  /// where the robot is now (MapServer::Resume), the follower's progress there. Returns the
  /// switch when the map changed.
  std::optional<MapSwitch> Resume();

  core::Pose2 Estimate() const { return localizer_.Estimate(); }
  const Localizer& localizer() const { return localizer_; }
  /// A switch is settling (its belief converging in the map it enters).
  bool settling() const { return pending_.has_value(); }
  const MapServer& server() const { return server_; }
  const PathFollower& follower() const { return follower_; }
  /// The robot's place on the route as of the last control tick.
  const RoutePosition& position() const { return tracker_.position(); }
  /// No map covers the robot's place: the estimate runs on odometry alone.
  bool off_map() const { return off_map_; }

 private:
  // A switch settling before it commits: where it goes, the belief converging there (seeded at
  // its first scan by a dense search, nav/place_search.hpp), its updates and the time it has
  // waited.
  struct PendingSwitch {
    RoutePlace place;
    Localizer belief;
    core::Rng rng;
    Travel travel = Travel::kUnknown;  // on the path entered
    bool wrap = false;  // round a loop's end
    bool seeded = false;
    int updates = 0;
    double waited = 0.0;
    // Σ over the scans both beliefs weighed of log(w_avg settling / w_avg current): > 0 when the
    // map entered explains the scans better than the map left (nats per beam, summed).
    double evidence = 0.0;
  };
  // The switch (or wrap) the rule asks for at this tick: made now, or settling first (a new
  // settling switch when it goes to another map than the one settling).
  std::optional<MapSwitch> SwitchTo(const RoutePlace& place, Travel travel, bool wrap);
  bool Settled(const PendingSwitch& p) const;
  bool Abandoned(const PendingSwitch& p) const;
  // The settling belief's particles at the best places for its first scan.
  void Seed(const core::LaserScan& scan);
  // The tracker on the current path at arc length s, going `travel`.
  void Track(double s, Travel travel);

  Localizer localizer_;
  PathFollower follower_;
  MapServer server_;
  int confirming_ = 0;    // updates a re-acquisition must still hold for
  core::Rng settle_rng_;  // each settling belief's stream: Split(settles_)
  std::uint64_t settles_ = 0;
  std::optional<PendingSwitch> pending_;
  RouteTracker tracker_;
  std::vector<double> scan_xs_, scan_ys_;  // the last scan's tested beams' end points (L)
  bool off_map_ = false;
};

}  // namespace retrace::nav
