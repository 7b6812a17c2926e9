#pragma once
// Scenario files (scenarios/*.yaml): everything one teaching-playback experiment needs — the
// world, the taught route and its map-switch points, the robot and its sensors, the
// pedestrians, scripted events, how many playback runs, the limits that end a run, and every
// navigation parameter. Strict: unknown keys and bad values are errors naming file, line and
// key. Paths inside a scenario are relative to the scenario file's folder.
//
// The robot's radius, the LiDAR's mount and range are stated once, under `sim`; the navigation
// stack (which cannot see sim) receives them as one value, Scenario::robot.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/engine/clutter.hpp"
#include "bench/engine/metrics_config.hpp"
#include "bench/engine/trace.hpp"
#include "core/config.hpp"
#include "core/pose2.hpp"
#include "io/config_override.hpp"
#include "nav/localizer.hpp"
#include "nav/map_server.hpp"
#include "nav/mapper.hpp"
#include "nav/obstacle_avoidance.hpp"
#include "nav/online_switcher.hpp"
#include "nav/path_follower.hpp"
#include "nav/route_graph.hpp"
#include "nav/robot_geometry.hpp"
#include "nav/scan_matcher.hpp"
#include "sim/simulator.hpp"
#include "sim/teacher.hpp"
#include "sim/world_file.hpp"

namespace retrace::bench {

/// How switch points are chosen instead of being listed: `auto` from the route's geometry when
/// the scenario is loaded, `online` by the teach recorder while it teaches (nav/online_switcher
/// .hpp), from its own odometry and scans.
enum class SwitchPlanning : std::uint8_t { kAuto, kOnline };

}  // namespace retrace::bench

template <>
struct retrace::core::EnumTraits<retrace::bench::SwitchPlanning> {
  static constexpr std::array<std::pair<retrace::bench::SwitchPlanning, std::string_view>, 2>
      kNames{{{retrace::bench::SwitchPlanning::kAuto, "auto"},
              {retrace::bench::SwitchPlanning::kOnline, "online"}}};
};

namespace retrace::bench {

/// The taught route: a polyline in W, from a route file or inline, and where the operator
/// starts a new partial map (modes `partial` and `scan_matched`).
struct RouteConfig {
  std::string file;                ///< route file (x y per line, or AutoNavi x y z qx qy qz qw)
  std::vector<core::Vec2> points;  ///< inline waypoints (W, m), when `file` is empty
  /// Arc lengths (m) along the route at which map k+1 starts; strictly increasing, inside the
  /// route. Empty: one partial map. `auto`: chosen from the route's geometry when the scenario
  /// is loaded (SuggestSwitchPoints, bench/engine/switch_points.hpp): each map ends just before
  /// the route comes back within revisit_radius of where that map has already been. `online`:
  /// the teach recorder decides while teaching, without the route (nav/online_switcher.hpp).
  core::WordOr<SwitchPlanning, std::vector<double>> switch_points;
  /// m: a map's segment that comes back within this distance of where it already drove is
  /// reported as a revisit (its switch point comes too late).
  double revisit_radius = 3.0;
  /// m: a switch point's place is compared with the places up to this far before it
  /// (bench/engine/switch_visibility.hpp); `auto` and `online` points move to the best of them.
  double switch_window = 10.0;
  /// `online`: the odometry error allowed per metre driven between two visits of a place (a
  /// fraction); the recorder treats a place as revisited within revisit_radius plus this times
  /// the distance driven since. Larger: safer against drift, more maps.
  double online_drift = 0.03;
  /// `online`: m of drift a map may gather before it is closed even without a revisit, the
  /// drift being online_drift times the distance driven since the map began, so a map is at
  /// most online_drift_budget / online_drift m of travel long (400 m by default). Must allow
  /// maps longer than switch_window; 0: no budget (maps end only before revisits).
  /// docs/HISTORY.md (online map switching) gives the sweep behind the default.
  double online_drift_budget = 12.0;
  /// `online`: m of expected drift over a loop (online_drift × the distance driven between two
  /// visits of a place) up to which a revisit is consistent and does not close the map; a
  /// revisit map is then at least revisit_tolerance / online_drift m long. 0: every revisit
  /// closes the map. docs/HISTORY.md (online map switching) gives the sweep behind the default.
  double revisit_tolerance = 0.5;
  /// How well a scan at a switch point must constrain the pose (≈ end points constraining the
  /// weakest direction); below it the scenario gets a warning naming a better place nearby.
  /// The default is where the scan matcher calls a scan degenerate (nav.scan_matcher
  /// .min_constraint): a corridor along its axis or an open field. 0: no check.
  double min_switch_constraint = 12.0;

  template <class V>
  void Reflect(V& v) {
    v("file", file);
    v("points", points);
    v("switch_points", switch_points);
    v("revisit_radius", revisit_radius);
    v("switch_window", switch_window);
    v("online_drift", online_drift);
    v("online_drift_budget", online_drift_budget);
    v("revisit_tolerance", revisit_tolerance);
    v("min_switch_constraint", min_switch_constraint);
  }
  /// The switching keys (the scenario checks that exactly one of file and points is given).
  void Validate() const;
  /// The settings of `online` switching (nav/online_switcher.hpp) these keys give.
  nav::OnlineSwitchingConfig OnlineSwitching() const;
  /// The route graph's settings these keys give (drift and revisit radius): how the teach
  /// recorder links the maps (nav::LinkRoute) and how the map server reads them.
  nav::RouteLinkConfig Link() const;
};

/// Static objects that exist only during teaching or only during playback (parked cars, a
/// moved bench, a closed gate): the world changes between teach and repeat.
struct PhaseObjectsConfig {
  std::vector<sim::BoxConfig> boxes;
  std::vector<sim::CircleConfig> circles;
  std::vector<sim::PolygonConfig> polygons;
  std::vector<sim::WallConfig> walls;

  template <class V>
  void Reflect(V& v) {
    v("boxes", boxes);
    v("circles", circles);
    v("polygons", polygons);
    v("walls", walls);
  }
  bool empty() const {
    return boxes.empty() && circles.empty() && polygons.empty() && walls.empty();
  }
};

enum class EventPhase { kTeach, kPlayback, kBoth };
enum class EventAction { kPedestrians, kCrossing, kObstacle, kTakeover };

/// Pedestrians sent across the robot's path: `count` people appear around `from` (within
/// `spread`) and walk to `to` and back, again and again.
struct CrossingConfig {
  core::Vec2 from{0.0, 0.0};
  core::Vec2 to{0.0, 0.0};
  int count = 3;
  double spread = 1.0;      ///< m, half-size of the square they appear in
  double speed_mean = 1.2;  ///< m/s
  double speed_std = 0.2;

  template <class V>
  void Reflect(V& v) {
    v("from", from);
    v("to", to);
    v("count", count);
    v("spread", spread);
    v("speed_mean", speed_mean);
    v("speed_std", speed_std);
  }
  void Validate() const;
};

/// A scripted event: at a time, or when the robot's progress along the route passes an arc
/// length, something happens in the world.
///   pedestrians: the group `pedestrians` spawns (any sim pedestrian group)
///   crossing:    pedestrians walk across the path (see CrossingConfig)
///   obstacle:    `boxes` and `circles` appear (e.g. a bin put on the path)
struct EventConfig {
  std::string name;
  EventPhase phase = EventPhase::kPlayback;
  std::optional<double> at_time;     ///< s since the run (or the teaching drive) started
  std::optional<double> at_route_s;  ///< m of progress along the route
  EventAction action = EventAction::kPedestrians;
  sim::PedestrianGroupConfig pedestrians;
  CrossingConfig crossing;
  std::vector<sim::BoxConfig> boxes;
  std::vector<sim::CircleConfig> circles;
  /// `takeover` (playback only): an operator takes the robot over and drives it through these
  /// points (W, m) as the teacher drives a route, then hands it back where the last one is; the
  /// navigator keeps localizing all the while, its commands unused.
  std::vector<core::Vec2> drive;

  template <class V>
  void Reflect(V& v) {
    v("name", name);
    v("phase", phase);
    v("at_time", at_time);
    v("at_route_s", at_route_s);
    v("action", action);
    v("pedestrians", pedestrians);
    v("crossing", crossing);
    v("boxes", boxes);
    v("circles", circles);
    v("drive", drive);
  }
  void Validate() const;
};

struct TeachConfig {
  sim::TeacherConfig teacher;
  bool pedestrians = true;  ///< the world's pedestrians walk during teaching too
  double timeout_s = 0.0;   ///< s; 0: 3 × the route length at the teacher's speed + 60 s

  template <class V>
  void Reflect(V& v) {
    v("teacher", teacher);
    v("pedestrians", pedestrians);
    v("timeout_s", timeout_s);
  }
  void Validate() const;
};

struct PlaybackConfig {
  int repeats = 5;
  double start_offset_xy = 0.1;       ///< m, std of the start's offset from the teaching start
  double start_offset_yaw_deg = 2.0;  ///< std of the start's heading offset
  double initial_sigma_xy = 0.2;      ///< m, the localizer's initial spread at map 0's origin
  double initial_sigma_yaw_deg = 3.0;
  /// The navigation stack the runs drive with, by its registered name
  /// (bench/engine/stack_registry.hpp): retrace, odometry, or one a program registered
  std::string stack = "retrace";
  /// The stack's options, by the names it declares (unknown keys are refused)
  std::map<std::string, std::string> stack_options;

  template <class V>
  void Reflect(V& v) {
    v("repeats", repeats);
    v("stack", stack);
    v("stack_options", stack_options);
    v("start_offset_xy", start_offset_xy);
    v("start_offset_yaw_deg", start_offset_yaw_deg);
    v("initial_sigma_xy", initial_sigma_xy);
    v("initial_sigma_yaw_deg", initial_sigma_yaw_deg);
  }
  void Validate() const;
};

/// When a playback run ends without reaching the goal.
struct LimitsConfig {
  double timeout_s = 0.0;      ///< s; 0: 2 × the teaching drive's duration + 60 s
  double lost_distance = 2.0;  ///< m: localization error beyond this ...
  double lost_time = 5.0;      ///< s: ... for this long ends the run as `lost`
  /// s without 0.5 m of progress along the path (stuck behind an obstacle, or following a
  /// wrong estimate into a wall) that ends the run as a timeout early
  double stall_time = 60.0;
  bool stop_on_collision = false;
  /// Modes whose runs must all succeed; otherwise `retrace run` exits with code 1.
  std::vector<MapMode> success_required = {MapMode::kPartial, MapMode::kConsistent};

  template <class V>
  void Reflect(V& v) {
    v("timeout_s", timeout_s);
    v("lost_distance", lost_distance);
    v("lost_time", lost_time);
    v("stall_time", stall_time);
    v("stop_on_collision", stop_on_collision);
    v("success_required", success_required);
  }
  void Validate() const;
};

/// The navigation stack's parameters.
struct NavConfig {
  double control_rate_hz = 20.0;  ///< follower and avoidance
  nav::MapperConfig mapper;
  nav::LocalizerConfig localizer;
  nav::PathFollowerConfig follower;
  nav::ObstacleAvoidanceConfig avoidance;
  nav::ScanMatcherConfig scan_matcher;  ///< the scan_matched mode's keyframe correction
  nav::MapServerConfig map_server;      ///< which map holds the robot, in playback and replay

  template <class V>
  void Reflect(V& v) {
    v("control_rate_hz", control_rate_hz);
    v("mapper", mapper);
    v("scan_matcher", scan_matcher);
    v("localizer", localizer);
    v("follower", follower);
    v("avoidance", avoidance);
    v("map_server", map_server);
  }
  void Validate() const;
};

struct ScenarioConfig {
  std::string name;
  std::string world;  ///< world file
  RouteConfig route;
  std::uint64_t seed = 1;
  std::vector<MapMode> modes = {MapMode::kPartial, MapMode::kSingle, MapMode::kConsistent};
  TeachConfig teach;
  PlaybackConfig playback;
  LimitsConfig limits;
  sim::SimConfig sim;
  NavConfig nav;
  MetricsConfig metrics;
  PhaseObjectsConfig teach_only;
  PhaseObjectsConfig playback_only;
  /// Unmapped clutter drawn beside the route for playback (bench/engine/clutter.hpp); off by
  /// default.
  ClutterConfig clutter;
  std::vector<EventConfig> events;

  template <class V>
  void Reflect(V& v) {
    v("name", name);
    v("world", world);
    v("route", route);
    v("seed", seed);
    v("modes", modes);
    v("teach", teach);
    v("playback", playback);
    v("limits", limits);
    v("sim", sim);
    v("nav", nav);
    v("metrics", metrics);
    v("teach_only", teach_only);
    v("playback_only", playback_only);
    v("clutter", clutter);
    v("events", events);
  }
  void Validate() const;
};

/// A loaded scenario: its effective config, the robot as nav sees it, the route, the two worlds
/// (teaching and playback differ by the phase objects) and what was worth warning about.
struct Scenario {
  ScenarioConfig config;
  nav::RobotGeometry robot;  ///< RobotGeometryOf(config.sim)
  std::filesystem::path source;
  std::vector<core::Vec2> route;
  double route_length = 0.0;
  core::Pose2 X_W_start;  ///< the teaching start: the first route point, facing the second
  sim::World teach_world;
  sim::World playback_world;  ///< with the clutter's objects and standing people
  Clutter clutter;            ///< drawn from config.clutter and the seed (empty when off)
  std::vector<std::string> warnings;
  std::string playback_blocked;  ///< why the route is not drivable in the playback world, if so
  /// route.switch_points was `auto`: config.route.switch_points now holds the points chosen.
  bool switch_points_auto = false;

  /// route.switch_points is `online`: the teach recorders choose them while teaching.
  bool switching_online() const { return config.route.switch_points.is(SwitchPlanning::kOnline); }
};

/// The robot's geometry for the navigation stack: sim.robot.radius, sim.lidar.mount and
/// sim.lidar.range_min / range_max.
nav::RobotGeometry RobotGeometryOf(const sim::SimConfig& sim);

/// Loads and checks a scenario: strict keys (nav keys that would repeat the robot's geometry
/// are refused naming the sim key that holds it), overrides (`--set`), the world and route files,
/// the route drivable by the robot in both worlds, the clutter drawn (Rng(seed).Split("clutter"))
/// and added to the playback world, switch points inside the route (revisits
/// become warnings), the start free. Throws core::ConfigError / IoError / WorldError with one
/// message naming the file.
Scenario LoadScenario(const std::filesystem::path& file,
                      const std::vector<io::ConfigOverride>& overrides = {});

/// The timeouts with their automatic defaults resolved (s).
double TeachTimeout(const Scenario& scenario);
double PlaybackTimeout(const Scenario& scenario, double teach_duration_s);

}  // namespace retrace::bench

template <>
struct retrace::core::EnumTraits<retrace::bench::EventPhase> {
  static constexpr std::array<std::pair<retrace::bench::EventPhase, std::string_view>, 3> kNames{
      {{retrace::bench::EventPhase::kTeach, "teach"},
       {retrace::bench::EventPhase::kPlayback, "playback"},
       {retrace::bench::EventPhase::kBoth, "both"}}};
};

template <>
struct retrace::core::EnumTraits<retrace::bench::EventAction> {
  static constexpr std::array<std::pair<retrace::bench::EventAction, std::string_view>, 4> kNames{
      {{retrace::bench::EventAction::kPedestrians, "pedestrians"},
       {retrace::bench::EventAction::kCrossing, "crossing"},
       {retrace::bench::EventAction::kObstacle, "obstacle"},
       {retrace::bench::EventAction::kTakeover, "takeover"}}};
};
