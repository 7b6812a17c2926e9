#include "sim/pedestrians.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "core/format.hpp"
#include "core/segment.hpp"

namespace retrace::sim {
namespace {

// Samples drawn per attempt when looking for a wander goal, and attempts.
constexpr int kGoalSamples = 200;
constexpr int kGoalAttempts = 20;
// A pedestrian with nowhere to go stands for this long before looking again (s).
constexpr double kIdleTime = 2.0;
// How far (m) a loop waypoint may be moved to reach free space.
constexpr double kWaypointSnap = 1.5;
// Longest pause (s) of a pedestrian that got stuck, to let others through, and how far (m) it
// steps aside meanwhile.
constexpr double kYieldTime = 3.0;
constexpr double kYieldDistance = 0.8;
// How often (s) each pedestrian checks that it can still walk straight to its next waypoint
// (after being pushed aside); if not, it re-plans.
constexpr double kPathCheckPeriod = 0.25;

void ValidateNested(std::string_view prefix, const auto& config) {
  try {
    config.Validate();
  } catch (const core::ConfigError& e) {
    throw core::ConfigError(std::string(prefix) + "." + e.key_path(), e.detail());
  }
}

// Appends the closest point of every solid added at run time (polygon edge or circle) within
// `radius` of p, like GeometryIndex::NearbyClosestPoints does for the world's geometry (there are
// few of them: brute force). Inside a solid (one was dropped on a pedestrian) the point is
// mirrored through p, so that the repulsion points the way out instead of deeper in.
void AddedObstaclePoints(const StaticGeometry& solids, const Vec2& p, double radius,
                         std::vector<Vec2>* out) {
  const double r2 = radius * radius;
  for (const auto& ring : solids.polygons()) {
    const bool inside = PointInPolygon(ring, p);
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const Vec2 q = core::ClosestPointOnSegment(p, ring[k], ring[(k + 1) % ring.size()]);
      if ((q - p).squaredNorm() < r2) out->push_back(inside ? Vec2(2.0 * p - q) : q);
    }
  }
  for (const Circle& c : solids.circles()) {
    const Vec2 d = p - c.center;
    const double n = d.norm();
    if (n - c.radius >= radius) continue;
    const Vec2 q =
        n > 0.0 ? Vec2(c.center + d * (c.radius / n)) : Vec2(c.center + Vec2(c.radius, 0.0));
    out->push_back(n < c.radius ? Vec2(2.0 * p - q) : q);
  }
}

// Distance (m) from p to the next waypoint of s, 0 without one: what a progress window measures.
double DistanceToNextWaypoint(const PedestrianStatus& s, const Vec2& p) {
  return s.path.empty() ? 0.0 : (s.path.front() - p).norm();
}

// The loop waypoints of `group`, each moved to the nearest walkable point if it is not one;
// *component is their common connected component. Throws core::WorldError (prefixed with
// `name`) when a waypoint has no walkable point nearby or cannot be reached from waypoint 0.
std::vector<Vec2> SnapLoopWaypoints(const PedestrianGroupConfig& group, const char* name,
                                    const WalkPlanner& planner, int* component) {
  std::vector<Vec2> loop;
  int loop_component = -1;
  for (std::size_t k = 0; k < group.waypoints.size(); ++k) {
    const Vec2& w = group.waypoints[k];
    std::optional<Vec2> snapped =
        planner.IsFree(w) ? std::optional<Vec2>(w) : planner.NearestFree(w, kWaypointSnap);
    if (!snapped) {
      throw core::WorldError(core::Printf(
          "%s: loop waypoint %zu (%.2f, %.2f) is inside or too close to static geometry (no "
          "walkable point within %.1f m)",
          name, k, w.x(), w.y(), kWaypointSnap));
    }
    const int c = planner.Component(*snapped);
    if (k == 0) loop_component = c;
    if (c != loop_component) {
      throw core::WorldError(core::Printf(
          "%s: loop waypoint %zu (%.2f, %.2f) cannot be reached on foot from waypoint 0 "
          "(%.2f, %.2f)",
          name, k, w.x(), w.y(), group.waypoints[0].x(), group.waypoints[0].y()));
    }
    loop.push_back(*snapped);
  }
  *component = loop_component;
  return loop;
}

// Desired speed N(mean, std) clipped to two standard deviations and to a walking minimum.
double DrawDesiredSpeed(const PedestrianGroupConfig& group, core::Rng& rng) {
  const double lo = std::max(0.1 * group.speed_mean, group.speed_mean - 2.0 * group.speed_std);
  const double hi = group.speed_mean + 2.0 * group.speed_std;
  return std::clamp(rng.Normal(group.speed_mean, group.speed_std), lo, hi);
}

// Why member `n` (0-based) of `group` found no spawn point in max_tries samples: a probe (its
// own stream split from `rng`) tells a full region from one without reachable free space.
std::string PlacementFailure(const PedestrianGroupConfig& group, const char* name, int n,
                             int max_tries, const WalkPlanner& planner, int component,
                             const core::Rng& rng) {
  const Aabb region{group.region_min, group.region_max};
  core::Rng probe = rng.Split("probe");
  const bool any_free = planner.SampleFreePoint(region, probe, 10000, component).has_value();
  return core::Printf(
      "%s: cannot place pedestrian %d of %d in region [%.2f, %.2f]-[%.2f, %.2f] after %d "
      "tries: %s",
      name, n + 1, group.count, region.min.x(), region.min.y(), region.max.x(), region.max.y(),
      max_tries,
      any_free ? "the region is too full (fewer pedestrians, a larger region, or a robot "
                 "start too close)"
               : (group.mode == PedestrianMode::kLoop
                      ? "the region has no free space connected to the loop waypoints"
                      : "the region has no free space (inside walls or obstacles, or too "
                        "narrow for the pedestrian radius plus margin)"));
}

}  // namespace

void CrowdConfig::Validate() const {
  ValidateNested("social_force", social_force);
  ValidateNested("ttc", ttc);
  ValidateNested("lanes", lanes);
  ValidateNested("headway", headway);
  ValidateNested("behaviour", behaviour);
  ValidateNested("planner", planner);
  core::RequirePositive("mass", mass);
  core::RequirePositive("waypoint_tolerance", waypoint_tolerance);
  core::RequirePositive("goal_tolerance", goal_tolerance);
  core::RequireNonNegative("min_goal_distance", min_goal_distance);
  core::RequireNonNegative("loop_spread", loop_spread);
  core::RequirePositive("stuck_time", stuck_time);
  core::RequirePositive("stuck_progress", stuck_progress);
  core::RequireNonNegative("spawn_gap", spawn_gap);
  core::RequireNonNegative("keep_clear_gap", keep_clear_gap);
  if (max_spawn_tries < 1) {
    throw core::ConfigError("max_spawn_tries",
                            "must be >= 1, got " + std::to_string(max_spawn_tries));
  }
}

struct Pedestrians::Walker {
  core::Rng rng;
  Aabb region;
  PedestrianMode mode = PedestrianMode::kWander;
  std::size_t planner = 0;  // index into planners_
  std::vector<Vec2> loop;   // loop waypoints, snapped to free space
  std::size_t loop_index = 0;
  double idle_until = -1.0;    // standing with nowhere to go until then (s)
  double yield_until = -1.0;   // stepping aside after getting stuck until then (s)
  Vec2 yield_point{0.0, 0.0};  // where to stand meanwhile (W)
  bool line_clear = false;     // the straight line to the next waypoint was clear at last check
  // Model `ttc`: where the line of the route towards the next waypoint starts (the last waypoint
  // passed, or where the path was planned from), and whether the straight line to the point
  // beside the waypoint (LaneAimPoint) was clear at the last check.
  Vec2 segment_start{0.0, 0.0};
  bool aim_clear = false;
  // Progress window: distance to the current waypoint and waypoints passed at its start.
  double window_start = 0.0;
  double window_distance = 0.0;
  int window_passed = 0;
  int window_goals = 0;
  int stuck_count = 0;
  // The reaction to the robot: until when it lasts (s; scared: while the robot is near) and until
  // when the person does not react again.
  double react_until = 0.0;
  double rest_until = -1.0;
};

// A pedestrian drawn but not yet in the physics world.
struct Pedestrians::Placement {
  Walker walker;
  PedestrianStatus status;
  Vec2 spawn{0.0, 0.0};
};

Pedestrians::Pedestrians(const std::vector<PedestrianGroupConfig>& groups,
                         const CrowdConfig& config, const StaticGeometry& geometry,
                         const core::Rng& rng, const std::vector<Circle>& keep_clear,
                         PhysicsWorld& world)
    : config_(config),
      runtime_rng_(rng.Split("runtime")),
      constructor_groups_(static_cast<int>(groups.size())) {
  config_.Validate();
  scared_force_ = config_.social_force;
  scared_force_.robot_strength = config_.behaviour.scared_strength;
  scared_force_.robot_range = config_.behaviour.scared_range;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    try {
      groups[g].Validate();
    } catch (const core::ConfigError& e) {
      throw core::ConfigError("pedestrians[" + std::to_string(g) + "]." + e.key_path(), e.detail());
    }
  }
  index_ = std::make_unique<GeometryIndex>(geometry, 1.0);

  // One planner for everyone, inflated for the largest pedestrian.
  std::vector<Aabb> regions;
  std::vector<Vec2> points;
  double max_radius = 0.0;
  for (const auto& g : groups) {
    if (g.count == 0) continue;
    regions.push_back({g.region_min, g.region_max});
    if (g.mode == PedestrianMode::kLoop)
      points.insert(points.end(), g.waypoints.begin(), g.waypoints.end());
    max_radius = std::max(max_radius, g.radius);
  }
  if (regions.empty()) return;  // nobody to spawn: no planner either
  planners_.push_back(std::make_unique<WalkPlanner>(
      *index_, PlanningArea(regions, points, config_.planner.area_padding), max_radius,
      config_.planner));

  std::vector<Circle> occupied;  // spawned pedestrians so far
  std::uint64_t person = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].count == 0) continue;
    std::vector<Placement> placements =
        PlaceGroup(groups[g], static_cast<int>(g), core::Printf("pedestrian group %zu", g),
                   *planners_[0], 0, rng, person, keep_clear, &occupied);
    person += static_cast<std::uint64_t>(groups[g].count);
    Commit(std::move(placements), world);
  }
  // Goals are chosen after everyone is placed so that spawning alone decides positions.
  StartWalking(0, /*added=*/false, world);
}

std::vector<Pedestrians::Placement> Pedestrians::PlaceGroup(
    const PedestrianGroupConfig& group, int group_index, const std::string& label,
    const WalkPlanner& planner, std::size_t planner_index, const core::Rng& family,
    std::uint64_t first_member, const std::vector<Circle>& keep_clear,
    std::vector<Circle>* occupied) const {
  const Aabb region{group.region_min, group.region_max};
  const char* name = label.c_str();

  std::vector<Vec2> loop;
  int loop_component = -1;
  if (group.mode == PedestrianMode::kLoop) {
    loop = SnapLoopWaypoints(group, name, planner, &loop_component);
  }

  std::vector<Placement> out;
  for (int n = 0; n < group.count; ++n) {
    Walker walker{.rng = family.Split(first_member + static_cast<std::uint64_t>(n)),
                  .region = region,
                  .mode = group.mode,
                  .planner = planner_index,
                  .loop = loop};
    PedestrianStatus status;
    status.group = group_index;
    status.radius = group.radius;
    status.standing = group.mode == PedestrianMode::kStand;
    status.behaviour = group.behaviour;
    status.desired_speed = DrawDesiredSpeed(group, walker.rng);

    const std::optional<Vec2> spawn =
        DrawSpawnPoint(group, planner, loop_component, keep_clear, *occupied, walker.rng);
    if (!spawn) {
      throw core::WorldError(PlacementFailure(group, name, n, config_.max_spawn_tries, planner,
                                              loop_component, walker.rng));
    }
    occupied->push_back({*spawn, group.radius});
    if (group.mode == PedestrianMode::kLoop) {
      walker.loop_index = static_cast<std::size_t>(walker.rng.UniformIndex(loop.size()));
      SpreadLoop(planner, loop_component, group.radius, &walker);
    }
    out.push_back({std::move(walker), std::move(status), *spawn});
  }
  return out;
}

std::optional<Vec2> Pedestrians::DrawSpawnPoint(const PedestrianGroupConfig& group,
                                                const WalkPlanner& planner, int component,
                                                const std::vector<Circle>& keep_clear,
                                                const std::vector<Circle>& occupied,
                                                core::Rng& rng) const {
  const Aabb region{group.region_min, group.region_max};
  std::optional<Vec2> spawn;
  for (int t = 0; t < config_.max_spawn_tries && !spawn; ++t) {
    const auto p = planner.SampleFreePoint(region, rng, 1, component);
    if (!p) continue;
    bool ok = true;
    for (const Circle& c : occupied) {
      const double min_d = c.radius + group.radius + config_.spawn_gap;
      if ((c.center - *p).squaredNorm() < min_d * min_d) ok = false;
    }
    for (const Circle& c : keep_clear) {
      const double min_d = c.radius + group.radius + config_.keep_clear_gap;
      if ((c.center - *p).squaredNorm() < min_d * min_d) ok = false;
    }
    if (ok) spawn = p;
  }
  return spawn;
}

void Pedestrians::SpreadLoop(const WalkPlanner& planner, int component, double radius,
                             Walker* walker) const {
  // Everyone aims at their own spot near each waypoint: a shared point would make them
  // queue for it.
  for (Vec2& w : walker->loop) {
    const double angle = walker->rng.Uniform(0.0, 2.0 * core::kPi);
    const double dist = config_.loop_spread * std::sqrt(walker->rng.Uniform());
    const Vec2 q = w + dist * Vec2(std::cos(angle), std::sin(angle));
    if (planner.Component(q) == component && planner.ClearPath(w, q, radius)) w = q;
  }
}

std::vector<int> Pedestrians::Commit(std::vector<Placement>&& placements, PhysicsWorld& world) {
  std::vector<int> ids;
  for (Placement& p : placements) {
    p.status.id = world.AddPedestrian(p.spawn, p.status.radius, config_.mass);
    ids.push_back(p.status.id);
    status_.push_back(std::move(p.status));
    walkers_.push_back(std::move(p.walker));
  }
  return ids;
}

void Pedestrians::StartWalking(std::size_t first, bool added, const PhysicsWorld& world) {
  for (std::size_t i = first; i < status_.size(); ++i) {
    const Vec2 p = world.PedestrianPosition(status_[i].id);
    if (walkers_[i].mode == PedestrianMode::kStand) {
      status_[i].goal = p;  // nowhere to go: no path, no progress window
      continue;
    }
    if (walkers_[i].mode == PedestrianMode::kLoop) {
      status_[i].goal = walkers_[i].loop[walkers_[i].loop_index];
      Replan(i, p);
    } else {
      ChooseNextGoal(i, p, world.time());
    }
    // Stagger the progress windows so that two pedestrians blocking each other (in a door,
    // say) do not react at the same instant: one steps aside, the other passes. The world's
    // pedestrians start their first window in the past, so that some check within a fraction of
    // a second, before they are up to speed (kept as is: it is part of the pinned simulation);
    // added groups start it in the future instead, so that none of them mistakes accelerating
    // from rest for being stuck and pauses right after appearing (a scripted crossing would
    // lose its timing).
    const double stagger = walkers_[i].rng.Uniform(0.0, config_.stuck_time);
    walkers_[i].window_start = added ? world.time() + stagger : world.time() - stagger;
    walkers_[i].window_distance = DistanceToNextWaypoint(status_[i], p);
  }
}

std::vector<int> Pedestrians::AddGroup(const PedestrianGroupConfig& group,
                                       const std::vector<Circle>& keep_clear, PhysicsWorld& world) {
  group.Validate();
  // The stream index counts every call, so that a group's draws do not depend on whether an
  // earlier one failed or was empty.
  const std::uint64_t k = added_groups_++;
  if (group.count == 0) return {};
  const int group_index = constructor_groups_ + static_cast<int>(k);
  const std::string label =
      core::Printf("pedestrian group %d (added at t = %.2f s)", group_index, world.time());

  // A planner whose grid is inflated enough for this radius and covers the region and loop
  // waypoints with room for detours; else a new one (which must see the added obstacles too).
  const Aabb region{group.region_min, group.region_max};
  const Aabb area = PlanningArea(
      {region}, group.mode == PedestrianMode::kLoop ? group.waypoints : std::vector<Vec2>{},
      config_.planner.area_padding);
  const double inflation = group.radius + config_.planner.margin;
  std::size_t planner_index = planners_.size();
  for (std::size_t i = 0; i < planners_.size(); ++i) {
    const Aabb covered = planners_[i]->area();
    if (planners_[i]->inflation_radius() >= inflation && covered.Contains(area.min) &&
        covered.Contains(area.max)) {
      planner_index = i;
      break;
    }
  }
  std::unique_ptr<WalkPlanner> new_planner;
  if (planner_index == planners_.size()) {
    new_planner = std::make_unique<WalkPlanner>(*index_, area, group.radius, config_.planner);
    if (!obstacles_.empty()) new_planner->AddObstacles(obstacles_);
  }
  const WalkPlanner& planner = new_planner ? *new_planner : *planners_[planner_index];

  std::vector<Circle> occupied;
  for (const DynamicCircle& c : world.PedestrianCircles()) occupied.push_back({c.center, c.radius});
  std::vector<Placement> placements = PlaceGroup(group, group_index, label, planner, planner_index,
                                                 runtime_rng_.Split(k), 0, keep_clear, &occupied);

  // Placed: from here on nothing throws.
  if (new_planner) planners_.push_back(std::move(new_planner));
  const std::size_t first = status_.size();
  std::vector<int> ids = Commit(std::move(placements), world);
  // Wander goals keep away from the robot where it is now (Update refreshes this every step).
  if (world.has_robot()) {
    robot_ =
        SocialAgent{world.RobotPose().translation(), world.RobotVelocityW(), world.robot_radius()};
  }
  StartWalking(first, /*added=*/true, world);
  return ids;
}

void Pedestrians::AddObstacles(const StaticGeometry& solids, const PhysicsWorld& world) {
  for (const auto& ring : solids.polygons()) obstacles_.AddPolygon(ring);
  for (const Circle& c : solids.circles()) obstacles_.AddCircle(c);
  for (auto& planner : planners_) planner->AddObstacles(solids);
  // Like the periodic path check in Update, but now: nobody keeps walking into a new obstacle
  // for up to a check period because its straight line was clear a moment ago.
  for (std::size_t i = 0; i < status_.size(); ++i) {
    const PedestrianStatus& s = status_[i];
    if (s.path.empty()) continue;
    CheckLineToWaypoint(i, world.PedestrianPosition(s.id));
  }
}

const WalkPlanner& Pedestrians::PlannerOf(std::size_t i) const {
  return *planners_[walkers_[i].planner];
}

Pedestrians::~Pedestrians() = default;
Pedestrians::Pedestrians(Pedestrians&&) noexcept = default;
Pedestrians& Pedestrians::operator=(Pedestrians&&) noexcept = default;

void Pedestrians::ChooseNextGoal(std::size_t i, const Vec2& position, double time) {
  Walker& w = walkers_[i];
  PedestrianStatus& s = status_[i];
  if (w.mode == PedestrianMode::kLoop) {
    w.loop_index = (w.loop_index + 1) % w.loop.size();
    s.goal = w.loop[w.loop_index];
    Replan(i, position);
    return;
  }
  int component = PlannerOf(i).Component(position);
  if (component < 0) {
    const auto near = PlannerOf(i).NearestFree(position, 1.5);
    if (near) component = PlannerOf(i).Component(*near);
  }
  std::optional<Vec2> goal;
  std::optional<Vec2> fallback;  // a reachable goal closer than min_goal_distance
  for (int attempt = 0; attempt < kGoalAttempts && !goal && component >= 0; ++attempt) {
    const auto p = PlannerOf(i).SampleFreePoint(w.region, w.rng, kGoalSamples, component);
    if (!p) break;
    if (robot_ &&
        (*p - robot_->position).norm() < robot_->radius + s.radius + config_.keep_clear_gap) {
      continue;  // the planner does not know the robot: do not aim at it
    }
    if ((*p - position).norm() >= config_.min_goal_distance) {
      goal = p;
    } else if (!fallback) {
      fallback = p;
    }
  }
  if (!goal) goal = fallback;
  if (!goal) {
    // Nowhere to go from here (pushed out of the walkable area, or the region is tiny): stand
    // and look again later.
    s.goal = position;
    s.path.clear();
    w.idle_until = time + kIdleTime;
    return;
  }
  s.goal = *goal;
  Replan(i, position);
}

Vec2 Pedestrians::YieldPoint(std::size_t i, const Vec2& position, const Vec2& waypoint) const {
  const double radius = status_[i].radius;
  Vec2 ahead = waypoint - position;
  if (ahead.norm() < 1e-6) return position;
  ahead.normalize();
  const Vec2 right(ahead.y(), -ahead.x());
  // Keep right, like most people do; else left; else back off.
  for (const Vec2& dir : {right, Vec2(-right), Vec2(-ahead)}) {
    const Vec2 q = position + kYieldDistance * dir;
    if (PlannerOf(i).IsFree(q) && PlannerOf(i).ClearPath(position, q, radius)) return q;
  }
  return position;
}

void Pedestrians::Replan(std::size_t i, const Vec2& position) {
  PedestrianStatus& s = status_[i];
  auto path = PlannerOf(i).Plan(position, s.goal);
  // No walkable path (pushed off the grid, goal cut off): head straight for the goal; the
  // progress check will pick another goal if that does not work either.
  s.path = path ? std::move(*path) : std::vector<Vec2>{s.goal};
  walkers_[i].line_clear = PlannerOf(i).ClearPath(position, s.path.front(), s.radius);
  // The route's line: a loop walker heading straight for its loop waypoint keeps to the loop's
  // edge (from the waypoint before); otherwise the line starts here.
  Walker& w = walkers_[i];
  w.segment_start = position;
  if (w.mode == PedestrianMode::kLoop && s.path.size() == 1 && !w.loop.empty() &&
      (s.path.front() - w.loop[w.loop_index]).squaredNorm() < 1e-12) {
    w.segment_start = w.loop[(w.loop_index + w.loop.size() - 1) % w.loop.size()];
  }
  CheckAim(i, position);
}

void Pedestrians::Update(PhysicsWorld& world) {
  if (status_.empty()) return;
  const double t = world.time();
  const double dt = world.time_step();

  agents_.resize(status_.size());
  headings_.resize(status_.size(), Vec2::Zero());
  for (std::size_t i = 0; i < status_.size(); ++i) {
    agents_[i] = {world.PedestrianPosition(status_[i].id), world.PedestrianVelocity(status_[i].id),
                  status_[i].radius, headings_[i]};
  }
  const bool has_robot = world.has_robot();
  if (has_robot) {
    robot_ =
        SocialAgent{world.RobotPose().translation(), world.RobotVelocityW(), world.robot_radius()};
    const double theta = world.RobotPose().theta;
    robot_disc_ = {robot_->position, robot_->radius, Vec2(std::cos(theta), std::sin(theta)),
                   robot_->velocity};
  }
  const SocialAgent* robot = has_robot ? &*robot_ : nullptr;
  const auto check_period =
      static_cast<std::uint64_t>(std::max(1.0, std::round(kPathCheckPeriod / dt)));

  new_velocities_.resize(status_.size());
  for (std::size_t i = 0; i < status_.size(); ++i) {
    const Vec2 p = agents_[i].position;
    if (walkers_[i].mode == PedestrianMode::kStand) {
      new_velocities_[i] = Vec2::Zero();  // standing still, whatever pushed it
      headings_[i] = Vec2::Zero();
      continue;
    }
    if (Reacts(status_[i].behaviour)) {
      if (has_robot) {
        UpdateReaction(i, p, t, robot_disc_);
      } else if (status_[i].reacting) {
        status_[i].reacting = false;
        Replan(i, p);
      }
    }
    // The line to the next waypoint is checked every check_period steps, staggered over
    // pedestrians to spread the cost. A reacting person follows its reaction instead.
    if (!status_[i].reacting) {
      UpdateWaypoints(i, p, t, (world.step_count() + i) % check_period == 0);
    }
    new_velocities_[i] = SocialVelocity(i, dt, robot);
  }
  // Set after computing all, so that the result does not depend on the update order.
  for (std::size_t i = 0; i < status_.size(); ++i) {
    world.SetPedestrianVelocity(status_[i].id, new_velocities_[i]);
  }
}

// Waypoints and goals of walking pedestrian i: a new goal when its idle time is over, else the
// waypoints it passed, its line to the next one (if `check_line`) and its progress; then a new
// path when it has yielded long enough.
void Pedestrians::UpdateWaypoints(std::size_t i, const Vec2& p, double t, bool check_line) {
  PedestrianStatus& s = status_[i];
  Walker& w = walkers_[i];
  if (w.idle_until >= 0.0) {
    if (t >= w.idle_until) {
      w.idle_until = -1.0;
      ChooseNextGoal(i, p, t);
      w.window_start = t;
      w.window_distance = DistanceToNextWaypoint(s, p);
    }
  } else {
    PassReachedWaypoints(i, p, t);
    // Pushed off the straight line to the next waypoint (behind a corner, say): re-plan.
    if (!s.path.empty() && check_line) CheckLineToWaypoint(i, p);
    // Progress check: within stuck_time, pass a waypoint or get stuck_progress closer to it.
    if (t - w.window_start >= config_.stuck_time) CheckProgress(i, p, t);
  }

  if (w.yield_until >= 0.0 && t >= w.yield_until) {
    w.yield_until = -1.0;
    Replan(i, p);
    w.window_distance = DistanceToNextWaypoint(s, p);
  }
}

void Pedestrians::PassReachedWaypoints(std::size_t i, const Vec2& p, double t) {
  PedestrianStatus& s = status_[i];
  while (!s.path.empty()) {
    const bool last = s.path.size() == 1;
    if (!Reached(i, p, last)) break;
    if (last) {
      ++s.goals_reached;
      const Vec2 reached = s.path.front();
      ChooseNextGoal(i, p, t);
      // The route's line goes on from the goal reached, not from where the walker stands.
      if (!s.path.empty()) {
        walkers_[i].segment_start = reached;
        CheckAim(i, p);
      }
      break;  // the new path starts afresh; checked next step
    }
    ++s.waypoints_passed;
    walkers_[i].segment_start = s.path.front();
    s.path.erase(s.path.begin());
    CheckAim(i, p);
    walkers_[i].line_clear = PlannerOf(i).ClearPath(p, s.path.front(), s.radius);
  }
}

bool Pedestrians::Reached(std::size_t i, const Vec2& p, bool last) const {
  const Vec2& w = status_[i].path.front();
  const double distance = (w - p).norm();
  if (config_.model != CrowdModel::kTtc || config_.lanes.tolerance <= 0.0) {
    return distance < (last ? config_.goal_tolerance : config_.waypoint_tolerance);
  }
  // Walking beside the route's line, a waypoint is passed once the walker is abreast of it.
  const Vec2 line = w - walkers_[i].segment_start;
  return distance < config_.waypoint_tolerance ||
         (p - walkers_[i].segment_start).dot(line) >= line.squaredNorm();
}

void Pedestrians::CheckLineToWaypoint(std::size_t i, const Vec2& p) {
  const PedestrianStatus& s = status_[i];
  Walker& w = walkers_[i];
  w.line_clear = PlannerOf(i).ClearPath(p, s.path.front(), s.radius);
  if (!w.line_clear) {
    Replan(i, p);
    w.window_distance = DistanceToNextWaypoint(s, p);
  }
  CheckAim(i, p);
}

void Pedestrians::CheckAim(std::size_t i, const Vec2& p) {
  const PedestrianStatus& s = status_[i];
  Walker& w = walkers_[i];
  w.aim_clear = false;
  if (config_.model != CrowdModel::kTtc || config_.lanes.tolerance <= 0.0 || s.path.empty()) return;
  w.aim_clear = PlannerOf(i).ClearPath(
      p, LaneAimPoint(p, w.segment_start, s.path.front(), config_.lanes), s.radius);
}

Vec2 Pedestrians::AimPoint(std::size_t i, const Vec2& p) const {
  const PedestrianStatus& s = status_[i];
  const Walker& w = walkers_[i];
  if (!w.aim_clear) return s.path.front();
  return LaneAimPoint(p, w.segment_start, s.path.front(), config_.lanes);
}

void Pedestrians::CheckProgress(std::size_t i, const Vec2& p, double t) {
  PedestrianStatus& s = status_[i];
  Walker& w = walkers_[i];
  const double d = DistanceToNextWaypoint(s, p);
  const bool progressed = s.waypoints_passed != w.window_passed ||
                          s.goals_reached != w.window_goals ||
                          w.window_distance - d >= config_.stuck_progress;
  if (progressed || s.path.empty()) {
    w.stuck_count = 0;
  } else if (++w.stuck_count == 1) {
    // Blocked (typically two people meeting head-on in a door): step aside for a moment
    // to let the other one through, then re-plan. The next check comes a full window
    // after the pause.
    ++s.replans;
    w.yield_until = t + w.rng.Uniform(0.5 * kYieldTime, kYieldTime);
    w.yield_point = YieldPoint(i, p, s.path.empty() ? p : s.path.front());
  } else {
    ++s.goals_abandoned;
    w.stuck_count = 0;
    ChooseNextGoal(i, p, t);
  }
  w.window_start = std::max(t, w.yield_until);
  w.window_passed = s.waypoints_passed;
  w.window_goals = s.goals_reached;
  w.window_distance = DistanceToNextWaypoint(s, p);
}

void Pedestrians::UpdateReaction(std::size_t i, const Vec2& p, double t, const RobotDisc& robot) {
  PedestrianStatus& s = status_[i];
  Walker& w = walkers_[i];
  const double gap = (p - robot.center).norm() - s.radius - robot.radius;
  const RobotBehaviourConfig& b = config_.behaviour;
  if (!s.reacting) {
    if (t < w.rest_until || gap >= b.notice_distance) return;
    s.reacting = true;
    ++s.reactions;
    w.react_until = t + ReactionTime(s.behaviour, b);
    w.yield_until = -1.0;
    return;
  }
  const bool over =
      s.behaviour == RobotBehaviour::kScared ? gap >= b.notice_distance : t >= w.react_until;
  if (!over) return;
  // Back to the route, from here, with a fresh progress window.
  s.reacting = false;
  w.rest_until = t + b.rest_time;
  w.stuck_count = 0;
  if (w.idle_until < 0.0) Replan(i, p);
  w.window_start = t;
  w.window_passed = s.waypoints_passed;
  w.window_goals = s.goals_reached;
  w.window_distance = DistanceToNextWaypoint(s, p);
}

const SocialAgent* Pedestrians::RobotFor(std::size_t i, const SocialAgent* robot,
                                         const SocialForceConfig** config) {
  *config = &config_.social_force;
  if (robot == nullptr) return nullptr;
  const PedestrianStatus& s = status_[i];
  switch (s.behaviour) {
    case RobotBehaviour::kImpassive: {
      // The robot's surface as an obstacle: kept off like a wall, not anticipated.
      const Vec2 p = agents_[i].position;
      const Vec2 d = p - robot->position;
      const double n = d.norm();
      if (n > 1e-9) obstacle_points_.push_back(robot->position + robot->radius * (d / n));
      return nullptr;
    }
    case RobotBehaviour::kScared:
      *config = &scared_force_;
      return robot;
    case RobotBehaviour::kCurious:
    case RobotBehaviour::kThreatening:
      return s.reacting ? nullptr : robot;  // they mean to come close
    default:
      return robot;
  }
}

void Pedestrians::WalkTarget(std::size_t i, const Vec2& p, Vec2* direction, double* speed) const {
  const PedestrianStatus& s = status_[i];
  const Walker& w = walkers_[i];
  *direction = Vec2::Zero();
  *speed = s.desired_speed;
  Vec2 target = p;
  double min_distance = 1e-6;
  if (s.reacting) {
    const ReactionTarget r =
        ReactionGoal(s.behaviour, p, s.radius, s.desired_speed, robot_disc_, config_.behaviour);
    target = r.point;
    *speed = r.speed;
    min_distance = 0.05;
  } else if (w.idle_until < 0.0 && w.yield_until >= 0.0) {
    target = w.yield_point;
    min_distance = 0.1;
  } else if (w.idle_until < 0.0 && !s.path.empty()) {
    target = config_.model == CrowdModel::kTtc ? AimPoint(i, p) : s.path.front();
  }
  const Vec2 to = target - p;
  const double n = to.norm();
  if (n > min_distance) *direction = to / n;
}

Vec2 Pedestrians::SocialVelocity(std::size_t i, double dt, const SocialAgent* robot) {
  const SocialForceConfig& sf = config_.social_force;
  const PedestrianStatus& s = status_[i];
  const Walker& w = walkers_[i];
  const Vec2 p = agents_[i].position;
  Vec2 direction;
  double speed = 0.0;
  WalkTarget(i, p, &direction, &speed);
  neighbours_.clear();
  const double range = config_.model == CrowdModel::kTtc ? config_.ttc.range : sf.interaction_range;
  const double range2 = range * range;
  for (std::size_t j = 0; j < agents_.size(); ++j) {
    if (j != i && (agents_[j].position - p).squaredNorm() < range2)
      neighbours_.push_back(agents_[j]);
  }
  obstacle_points_.clear();
  index_->NearbyClosestPoints(p, sf.obstacle_cutoff, &obstacle_points_);
  if (!obstacles_.empty()) {
    AddedObstaclePoints(obstacles_, p, sf.obstacle_cutoff, &obstacle_points_);
  }
  SelectObstaclePoints(p, &obstacle_points_);
  SocialForceInputs in;
  const SocialForceConfig* forces = &sf;
  in.robot = RobotFor(i, robot, &forces);  // may add the robot's surface to the obstacles
  in.self = agents_[i];
  in.direction = direction;
  in.desired_speed = speed;
  in.others = neighbours_;
  in.obstacle_points = obstacle_points_;
  in.walking_line_clear = w.line_clear && w.yield_until < 0.0 && !s.reacting;
  Vec2 a = Vec2::Zero();
  if (config_.model == CrowdModel::kTtc) {
    const WalkingChoice walk = s.reacting ? WalkingChoice{direction, speed}
                                          : ChooseLane(in.self, direction, speed, neighbours_,
                                                       in.robot, config_.lanes, config_.headway);
    headings_[i] = walk.direction;
    a = TtcForce(in, walk.speed * walk.direction, config_.ttc, *forces);
  } else {
    headings_[i] = direction;
    a = SocialForce(in, *forces);
  }
  return IntegrateVelocity(agents_[i].velocity, a, dt, sf.max_speed_factor * s.desired_speed);
}

}  // namespace retrace::sim
