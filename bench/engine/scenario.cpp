#include "bench/engine/scenario.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "bench/engine/stack_registry.hpp"
#include "bench/engine/switch_points.hpp"
#include "bench/engine/switch_visibility.hpp"
#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/config_yaml.hpp"
#include "io/route_file.hpp"
#include "sim/route_check.hpp"

namespace retrace::bench {
namespace {

// The world of one phase: the world file's geometry plus that phase's own objects.
sim::World PhaseWorld(const sim::World& base, const PhaseObjectsConfig& objects) {
  if (objects.empty()) return base;
  sim::World world;
  world.config = base.config;
  world.source = base.source;
  auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  append(world.config.boxes, objects.boxes);
  append(world.config.circles, objects.circles);
  append(world.config.polygons, objects.polygons);
  append(world.config.walls, objects.walls);
  world.geometry = sim::BuildGeometry(world.config, base.source.parent_path());
  return world;
}

std::string Where(const std::filesystem::path& file) { return file.string() + ": "; }

// Keys that nav's configs once repeated from sim's (and the harness overwrote): refused with
// the key that states the value.
const std::vector<io::MovedKey> kRobotGeometryKeys = {
    {"nav.avoidance.robot_radius", "sim.robot.radius"},
    {"nav.avoidance.lidar_mount", "sim.lidar.mount"},
    {"nav.localizer.lidar_mount", "sim.lidar.mount"},
    {"nav.localizer.range_min", "sim.lidar.range_min"},
    {"nav.localizer.range_max", "sim.lidar.range_max"},
    {"nav.mapper.lidar_mount", "sim.lidar.mount"},
    {"nav.mapper.hit_range_max", "sim.lidar.range_max"},
};

}  // namespace

nav::RobotGeometry RobotGeometryOf(const sim::SimConfig& sim) {
  nav::RobotGeometry robot;
  robot.radius = sim.robot.radius;
  robot.X_RL = sim.lidar.mount;
  robot.range_min = sim.lidar.range_min;
  robot.range_max = sim.lidar.range_max;
  return robot;
}

void RouteConfig::Validate() const {
  core::RequireNonNegative("switch_window", switch_window);
  core::RequireNonNegative("min_switch_constraint", min_switch_constraint);
  core::RequireInRange("online_drift", online_drift, 0.0, 0.5);
  core::RequireNonNegative("online_drift_budget", online_drift_budget);
  if (!(OnlineSwitching().MaxMapLength() > switch_window)) {
    throw core::ConfigError(
        "online_drift_budget",
        "must allow maps longer than route.switch_window: " +
            core::FormatNumber(online_drift_budget) + " m / online_drift " +
            core::FormatNumber(online_drift) + " = " +
            core::FormatNumber(OnlineSwitching().MaxMapLength()) + " m of travel, window " +
            core::FormatNumber(switch_window) + " m (0: no budget)");
  }
  core::RequireNonNegative("revisit_tolerance", revisit_tolerance);
  const nav::OnlineSwitchingConfig online = OnlineSwitching();
  const double shortest = online.MinMapLength(), longest = online.MaxMapLength();
  if (std::isfinite(longest) && !(longest > shortest)) {
    throw core::ConfigError("revisit_tolerance",
                            "must be below online_drift_budget (" +
                                core::FormatNumber(online_drift_budget) + " m): a loop of " +
                                core::FormatNumber(std::round(shortest * 10.0) / 10.0) +
                                " m would be consistent, but maps end after " +
                                core::FormatNumber(std::round(longest * 10.0) / 10.0) + " m");
  }
  const std::vector<double>& points_at = switch_points.value;
  for (std::size_t i = 0; i < points_at.size(); ++i) {
    core::RequirePositive("switch_points", points_at[i]);
    if (i > 0 && !(points_at[i] > points_at[i - 1])) {
      throw core::ConfigError("switch_points", "must be strictly increasing, got " +
                                                   core::FormatNumber(points_at[i - 1]) + " then " +
                                                   core::FormatNumber(points_at[i]));
    }
  }
  core::RequirePositive("revisit_radius", revisit_radius);
}

nav::RouteLinkConfig RouteConfig::Link() const {
  nav::RouteLinkConfig link;
  link.drift = online_drift;
  link.revisit_radius = revisit_radius;
  return link;
}

nav::OnlineSwitchingConfig RouteConfig::OnlineSwitching() const {
  return nav::OnlineSwitchingConfig{revisit_radius, switch_window, online_drift,
                                    online_drift_budget, revisit_tolerance};
}

void CrossingConfig::Validate() const {
  core::RequireIntInRange("count", count, 1, 1000);
  core::RequireNonNegative("spread", spread);
  core::RequirePositive("speed_mean", speed_mean);
  core::RequireNonNegative("speed_std", speed_std);
  if ((to - from).norm() < 1.0) throw core::ConfigError("to", "must be at least 1 m from `from`");
}

void EventConfig::Validate() const {
  if (at_time.has_value() == at_route_s.has_value()) {
    throw core::ConfigError("at_time", "give exactly one trigger: at_time (s) or at_route_s (m)");
  }
  if (at_time) core::RequireNonNegative("at_time", *at_time);
  if (at_route_s) core::RequireNonNegative("at_route_s", *at_route_s);
  if (action == EventAction::kObstacle && boxes.empty() && circles.empty()) {
    throw core::ConfigError("boxes", "an obstacle event needs at least one box or circle");
  }
  if (action == EventAction::kTakeover) {
    if (drive.empty()) throw core::ConfigError("drive", "a takeover needs at least one point");
    if (phase != EventPhase::kPlayback) {
      throw core::ConfigError("phase", "a takeover happens in playback only");
    }
  }
  if (action != EventAction::kTakeover && !drive.empty()) {
    throw core::ConfigError("drive", "only a takeover drives the robot");
  }
}

void TeachConfig::Validate() const { core::RequireNonNegative("timeout_s", timeout_s); }

void PlaybackConfig::Validate() const {
  core::RequireIntInRange("repeats", repeats, 1, 10000);
  core::RequireNonNegative("start_offset_xy", start_offset_xy);
  core::RequireNonNegative("start_offset_yaw_deg", start_offset_yaw_deg);
  core::RequirePositive("initial_sigma_xy", initial_sigma_xy);
  core::RequirePositive("initial_sigma_yaw_deg", initial_sigma_yaw_deg);
  ValidateStackChoice(stack, stack_options);
}

void LimitsConfig::Validate() const {
  core::RequireNonNegative("timeout_s", timeout_s);
  core::RequirePositive("lost_distance", lost_distance);
  core::RequirePositive("lost_time", lost_time);
  core::RequirePositive("stall_time", stall_time);
}

void NavConfig::Validate() const {
  core::RequireInRange("control_rate_hz", control_rate_hz, 1.0, 1000.0);
}

void ScenarioConfig::Validate() const {
  if (name.empty()) throw core::ConfigError("name", "must not be empty");
  if (world.empty()) throw core::ConfigError("world", "must name a world file");
  if (route.file.empty() == route.points.empty()) {
    throw core::ConfigError(route.file.empty() ? "route.points" : "route.file",
                            "give the route either as `file` or as inline `points`, not both");
  }
  if (modes.empty()) throw core::ConfigError("modes", "must list at least one map mode");
  for (std::size_t i = 0; i < modes.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (modes[i] == modes[j]) {
        throw core::ConfigError("modes",
                                "lists '" + std::string(core::EnumName(modes[i])) + "' twice");
      }
    }
  }
  sim.Validate();
  // The control period must be a whole number of physics steps, like the sensors'.
  sim::PeriodInSteps("nav.control_rate_hz", nav.control_rate_hz, sim.physics.time_step);
  if (nav.follower.max_speed > sim.robot.max_speed) {
    throw core::ConfigError("nav.follower.max_speed", "must not exceed sim.robot.max_speed (" +
                                                          core::FormatNumber(sim.robot.max_speed) +
                                                          " m/s)");
  }
  const double corridor = sim.robot.radius + clutter.clearance;
  if (clutter.enabled() && !(clutter.band > corridor)) {
    throw core::ConfigError("clutter.band",
                            "must be wider than the corridor kept free along the route, "
                            "sim.robot.radius + clutter.clearance = " +
                                core::FormatNumber(corridor) + " m, got " +
                                core::FormatNumber(clutter.band) + " m");
  }
  if (teach.teacher.speed > sim.robot.max_speed) {
    throw core::ConfigError("teach.teacher.speed", "must not exceed sim.robot.max_speed (" +
                                                       core::FormatNumber(sim.robot.max_speed) +
                                                       " m/s)");
  }
}

namespace {

// The route, validated, and whether it can be driven in each phase's world (blocked during
// playback is a warning: a closed gate on the route is a legitimate experiment, the robot must
// stop); the start pose faces along the first segment.
void LoadRoute(const std::filesystem::path& file, Scenario* scenario) {
  const ScenarioConfig& config = scenario->config;
  const std::filesystem::path dir = file.parent_path();
  scenario->route =
      config.route.file.empty() ? config.route.points : io::ReadRouteFile(dir / config.route.file);
  try {
    sim::ValidateRoute(scenario->route);
  } catch (const core::ConfigError& e) {
    throw core::ConfigError(e.key_path(), Where(file) + e.what(), true);
  }
  scenario->route_length = RouteLength(scenario->route);
  const double radius = config.sim.robot.radius;
  try {
    sim::CheckRouteIsDrivable(scenario->teach_world.geometry, scenario->route, radius);
  } catch (const core::WorldError& e) {
    throw core::WorldError(Where(file) + "the route is not drivable while teaching: " + e.what());
  }
  try {
    sim::CheckRouteIsDrivable(scenario->playback_world.geometry, scenario->route, radius);
  } catch (const core::WorldError& e) {
    scenario->playback_blocked = std::string("the route is blocked during playback: ") + e.what();
  }
  const core::Vec2 d = scenario->route[1] - scenario->route[0];
  scenario->X_W_start =
      core::Pose2(scenario->route[0].x(), scenario->route[0].y(), std::atan2(d.y(), d.x()));
}

// The switch points: `auto` resolved once, here (the effective config and the manifest hold the
// points chosen), checked against the route, and moved to (automatic) or warned about
// (hand-picked) the best-constrained place of their window.
void ResolveSwitchPoints(Scenario* scenario) {
  ScenarioConfig& config = scenario->config;
  if (config.route.switch_points.is(SwitchPlanning::kAuto)) {
    config.route.switch_points = {std::nullopt,
                                  SuggestSwitchPoints(scenario->route, config.route.revisit_radius)};
    scenario->switch_points_auto = true;
  }
  std::vector<double>& switch_points = config.route.switch_points.value;
  // Checked first: JudgeSwitchPlaces needs points inside the route. Online points are judged
  // after teaching, against the drive's ground truth (bench/metrics/switching.hpp).
  if (!scenario->switching_online()) {
    scenario->warnings =
        CheckSwitchPoints(scenario->route, switch_points, config.route.revisit_radius);
  }
  if (config.route.min_switch_constraint <= 0.0 || switch_points.empty()) return;
  // Automatic points move back to the best place of their window (switching earlier never
  // makes a map revisit itself); hand-picked ones stay and are warned about.
  std::vector<SwitchPlace> places =
      JudgeSwitchPlaces(*scenario, switch_points, config.route.switch_window);
  if (scenario->switch_points_auto) {
    for (std::size_t k = 0; k < places.size(); ++k) {
      switch_points[k] = places[k].best_s;
      places[k] = {places[k].best_s, places[k].best_constraint, places[k].best_s,
                   places[k].best_constraint};
    }
  }
  if (scenario->switch_points_auto)
    scenario->warnings =
        CheckSwitchPoints(scenario->route, switch_points, config.route.revisit_radius);
  for (std::string& w : SwitchPlaceWarnings(places, config.route.min_switch_constraint))
    scenario->warnings.push_back(std::move(w));
}

// The clutter, drawn from the scenario seed, added to the playback world: its objects as
// playback-only objects, its standing people as the first pedestrian groups (so that the
// world's walkers spawn clear of them). The corridor keeps the route drivable; checked again.
void AddClutter(const std::filesystem::path& file, Scenario* scenario) {
  const ScenarioConfig& config = scenario->config;
  if (!config.clutter.enabled()) return;
  const double radius = config.sim.robot.radius;
  // Standing people must spawn crowd.keep_clear_gap clear of the robot's start, which is
  // drawn within a few start_offset_xy of the route's first point.
  const ClutterSite site{&scenario->route, &scenario->playback_world.geometry, radius,
                         radius + config.sim.crowd.keep_clear_gap + config.clutter.person_radius +
                             5.0 * config.playback.start_offset_xy + 0.5};
  try {
    scenario->clutter =
        GenerateClutter(config.clutter, site, core::Rng(config.seed).Split("clutter"));
  } catch (const core::ConfigError& e) {
    throw core::ConfigError("clutter." + e.key_path(),
                            Where(file) + "clutter." + e.key_path() + ": " + e.detail(), true);
  }
  PhaseObjectsConfig objects;
  objects.boxes = scenario->clutter.boxes;
  objects.circles = scenario->clutter.circles;
  scenario->playback_world = PhaseWorld(scenario->playback_world, objects);
  const std::vector<sim::PedestrianGroupConfig> people =
      StandingGroups(scenario->clutter, config.clutter.person_radius);
  auto& groups = scenario->playback_world.config.pedestrians;
  groups.insert(groups.begin(), people.begin(), people.end());
  if (!scenario->playback_blocked.empty()) return;
  try {
    sim::CheckRouteIsDrivable(scenario->playback_world.geometry, scenario->route, radius);
  } catch (const core::WorldError& e) {
    throw core::WorldError(Where(file) + "the clutter blocks the route during playback: " +
                           e.what());
  }
}

// Every event placed along the route lies on it.
void CheckEventsOnRoute(const Scenario& scenario) {
  for (std::size_t i = 0; i < scenario.config.events.size(); ++i) {
    const EventConfig& event = scenario.config.events[i];
    if (event.at_route_s && *event.at_route_s > scenario.route_length) {
      throw core::ConfigError(
          "events." + std::to_string(i) + ".at_route_s",
          "lies beyond the route's end (" + core::FormatNumber(scenario.route_length) + " m)");
    }
  }
}

}  // namespace

Scenario LoadScenario(const std::filesystem::path& file,
                      const std::vector<io::ConfigOverride>& overrides) {
  Scenario scenario;
  scenario.source = file;
  YAML::Node root = io::LoadYamlFile(file);
  io::ApplyOverrides(root, overrides);
  io::RejectMovedKeys(root, file.string(), overrides, kRobotGeometryKeys,
                      "the robot's geometry is stated once, for the simulator and the navigation "
                      "stack alike: set");
  scenario.config = io::ReadConfig<ScenarioConfig>(root, file.string(), overrides);
  scenario.robot = RobotGeometryOf(scenario.config.sim);
  const sim::World world = sim::LoadWorld(file.parent_path() / scenario.config.world);
  scenario.teach_world = PhaseWorld(world, scenario.config.teach_only);
  scenario.playback_world = PhaseWorld(world, scenario.config.playback_only);
  LoadRoute(file, &scenario);
  AddClutter(file, &scenario);
  try {
    ResolveSwitchPoints(&scenario);
    CheckEventsOnRoute(scenario);
  } catch (const core::ConfigError& e) {
    if (e.located()) throw;
    throw core::ConfigError(e.key_path(), Where(file) + e.what(), true);
  }
  if (!scenario.playback_blocked.empty()) scenario.warnings.push_back(scenario.playback_blocked);
  return scenario;
}

double TeachTimeout(const Scenario& scenario) {
  const ScenarioConfig& c = scenario.config;
  if (c.teach.timeout_s > 0.0) return c.teach.timeout_s;
  return 3.0 * scenario.route_length / c.teach.teacher.speed + 60.0;
}

double PlaybackTimeout(const Scenario& scenario, double teach_duration_s) {
  const ScenarioConfig& c = scenario.config;
  if (c.limits.timeout_s > 0.0) return c.limits.timeout_s;
  return 2.0 * teach_duration_s + 60.0;
}

}  // namespace retrace::bench
