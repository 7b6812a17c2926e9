#pragma once
// The crowd: spawns the pedestrian groups into the physics world and drives them every step
// with the social-force model along waypoints from the walk planner. The velocity the model
// asks for is set on each pedestrian's Box2D body, so contacts keep them out of walls, out of
// each other and out of the robot. Deterministic: every random draw comes from the Rng given
// at construction, split per pedestrian.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "core/rng.hpp"
#include "sim/geometry_index.hpp"
#include "sim/lane_choice.hpp"
#include "sim/pedestrian_config.hpp"
#include "sim/physics_world.hpp"
#include "sim/social_force.hpp"
#include "sim/speed_headway.hpp"
#include "sim/static_geometry.hpp"
#include "sim/ttc_force.hpp"
#include "sim/walk_planner.hpp"

namespace retrace::sim {

/// How pedestrians react to each other: Helbing & Molnár's social force (social_force.hpp), or
/// Karamouzas et al.'s time-to-collision power law with the speed-headway rule (ttc_force.hpp,
/// speed_headway.hpp). Both treat walls and the robot alike (the social force's terms).
enum class CrowdModel { kSocialForce, kTtc };

}  // namespace retrace::sim

template <>
struct retrace::core::EnumTraits<retrace::sim::CrowdModel> {
  static constexpr std::array<std::pair<retrace::sim::CrowdModel, std::string_view>, 2> kNames{
      {{retrace::sim::CrowdModel::kSocialForce, "social_force"},
       {retrace::sim::CrowdModel::kTtc, "ttc"}}};
};

namespace retrace::sim {

/// Crowd-wide behaviour settings (the groups themselves come from the world file).
struct CrowdConfig {
  CrowdModel model = CrowdModel::kTtc;
  /// The social force; with model `ttc` only its robot, wall, field-of-view and cap terms.
  SocialForceConfig social_force;
  TtcForceConfig ttc;          ///< model `ttc`: the power law and its driving term
  LaneChoiceConfig lanes;      ///< model `ttc`: overtaking, keeping right, walking beside the line
  SpeedHeadwayConfig headway;  ///< model `ttc`: the speed the space ahead allows
  RobotBehaviourConfig behaviour;  ///< how the behaviours toward the robot play out
  WalkPlannerConfig planner;
  double mass = 70.0;               ///< kg per pedestrian (an adult)
  double waypoint_tolerance = 0.4;  ///< m: an intermediate waypoint closer than this is passed
  double goal_tolerance = 0.5;      ///< m: a goal or loop waypoint closer than this is reached
  double min_goal_distance = 2.0;   ///< m: wander goals are drawn at least this far away
  /// m: each pedestrian of a loop group aims at its own random point within this distance of
  /// every loop waypoint (so that they do not queue for one spot)
  double loop_spread = 0.5;
  double stuck_time = 3.0;      ///< s: window of the progress check
  double stuck_progress = 0.3;  ///< m towards the current waypoint expected per window
  double spawn_gap = 0.1;       ///< m of free space between spawned pedestrians
  /// m between spawned pedestrians and keep-clear circles, and between wander goals and the
  /// robot
  double keep_clear_gap = 1.0;
  int max_spawn_tries = 5000;  ///< random samples per pedestrian before giving up

  template <class V>
  void Reflect(V& v) {
    v("model", model);
    v("social_force", social_force);
    v("ttc", ttc);
    v("lanes", lanes);
    v("headway", headway);
    v("behaviour", behaviour);
    v("planner", planner);
    v("mass", mass);
    v("waypoint_tolerance", waypoint_tolerance);
    v("goal_tolerance", goal_tolerance);
    v("min_goal_distance", min_goal_distance);
    v("loop_spread", loop_spread);
    v("stuck_time", stuck_time);
    v("stuck_progress", stuck_progress);
    v("spawn_gap", spawn_gap);
    v("keep_clear_gap", keep_clear_gap);
    v("max_spawn_tries", max_spawn_tries);
  }
  /// Throws core::ConfigError naming the key (nested keys as "social_force.fov_deg").
  void Validate() const;
};

/// What one pedestrian is doing and has done, for tests and diagnostics.
struct PedestrianStatus {
  int id = 0;                  ///< pedestrian id in the PhysicsWorld (DynamicCircle id)
  int group = 0;               ///< index into the groups: the world's, then added ones in order
  double radius = 0.3;         ///< m
  double desired_speed = 0.0;  ///< m/s (drawn, but unused when `standing`)
  bool standing = false;       ///< of a group of mode `stand`: stands still by design
  RobotBehaviour behaviour = RobotBehaviour::kRegular;  ///< toward the robot, from its group
  bool reacting = false;     ///< reacting to the robot now (its behaviour's reaction)
  int reactions = 0;         ///< reactions to the robot started
  Vec2 goal{0.0, 0.0};       ///< current goal (W, m): wander target or loop waypoint
  std::vector<Vec2> path;    ///< remaining waypoints to the goal (W, m), goal last
  int goals_reached = 0;     ///< wander goals or loop waypoints reached
  int waypoints_passed = 0;  ///< intermediate waypoints passed
  int replans = 0;           ///< steps aside and re-plans after making no progress
  int goals_abandoned = 0;   ///< goals given up after making no progress twice
};

class Pedestrians {
 public:
  /// Spawns every group's pedestrians at random free points of its region, clear of walls
  /// (by radius + planner margin), of each other (by spawn_gap) and of the `keep_clear`
  /// circles (the robot's start, by keep_clear_gap), and adds them to `world`.
  /// `geometry` must outlive this object (the crowd keeps a proximity index over it).
  /// Throws core::ConfigError on an invalid config or group, core::WorldError when a
  /// pedestrian cannot be placed (region inside walls or too full) or a loop waypoint is
  /// unreachable.
  Pedestrians(const std::vector<PedestrianGroupConfig>& groups, const CrowdConfig& config,
              const StaticGeometry& geometry, const core::Rng& rng,
              const std::vector<Circle>& keep_clear, PhysicsWorld& world);
  ~Pedestrians();
  Pedestrians(Pedestrians&&) noexcept;
  Pedestrians& operator=(Pedestrians&&) noexcept;

  /// Spawns one more group now (a scripted event), by the constructor's rules: random free
  /// points of its region, clear of static geometry and of the obstacles added so far (by radius
  /// + planner margin), of every pedestrian in `world` (by spawn_gap) and of the `keep_clear`
  /// circles (by keep_clear_gap). They walk from the next Update on. Randomness comes from the
  /// k-th added group's own stream (the crowd's Rng split "runtime", then k), so the constructor's
  /// pedestrians draw exactly the numbers they would without it. Their status().group is the
  /// number of constructor groups plus k. The group reuses a walk planner whose grid covers its
  /// region (and loop waypoints) with area_padding to spare, else gets its own.
  /// Returns their DynamicCircle ids (empty for count 0). Throws core::ConfigError on an invalid
  /// group (key as in PedestrianGroupConfig::Validate) and core::WorldError when the group cannot
  /// be placed or a loop waypoint is unreachable; nothing is added then.
  std::vector<int> AddGroup(const PedestrianGroupConfig& group,
                            const std::vector<Circle>& keep_clear, PhysicsWorld& world);

  /// Makes the crowd aware of solids added to the world at run time (the polygons and circles of
  /// `solids`, W; physics keeps bodies out of them anyway): their surfaces repel like walls in the
  /// social force, the walk planners block the cells around them (so paths, wander goals and
  /// spawn points avoid them), and every pedestrian whose way to its next waypoint they block
  /// re-plans now (positions from `world`). Open edges are not supported (checked).
  void AddObstacles(const StaticGeometry& solids, const PhysicsWorld& world);

  /// Advances goals and waypoints, re-plans when pushed off the straight line to the next
  /// waypoint, handles lack of progress (first step aside for a moment and re-plan, then give
  /// the goal up), and sets every pedestrian's velocity from the social force (reacting to the
  /// robot if the world has one). Call once before every PhysicsWorld::Step().
  void Update(PhysicsWorld& world);

  int size() const { return static_cast<int>(status_.size()); }
  const std::vector<PedestrianStatus>& status() const { return status_; }
  /// The walk planner shared by the constructor's groups (or the first one built for an added
  /// group); nullptr when there are no pedestrians.
  const WalkPlanner* planner() const { return planners_.empty() ? nullptr : planners_[0].get(); }
  /// Every solid added by AddObstacles so far.
  const StaticGeometry& obstacles() const { return obstacles_; }

 private:
  struct Walker;  // per-pedestrian state not worth publishing (rng, progress window)
  struct Placement;

  std::vector<Placement> PlaceGroup(const PedestrianGroupConfig& group, int group_index,
                                    const std::string& label, const WalkPlanner& planner,
                                    std::size_t planner_index, const core::Rng& family,
                                    std::uint64_t first_member,
                                    const std::vector<Circle>& keep_clear,
                                    std::vector<Circle>* occupied) const;
  // Steps of PlaceGroup: a spawn point clear of `occupied` and `keep_clear` (nullopt after
  // max_spawn_tries samples), and the pedestrian's own spot near every loop waypoint.
  std::optional<Vec2> DrawSpawnPoint(const PedestrianGroupConfig& group, const WalkPlanner& planner,
                                     int component, const std::vector<Circle>& keep_clear,
                                     const std::vector<Circle>& occupied, core::Rng& rng) const;
  void SpreadLoop(const WalkPlanner& planner, int component, double radius, Walker* walker) const;
  std::vector<int> Commit(std::vector<Placement>&& placements, PhysicsWorld& world);
  void StartWalking(std::size_t first, bool added, const PhysicsWorld& world);
  const WalkPlanner& PlannerOf(std::size_t i) const;
  void ChooseNextGoal(std::size_t i, const Vec2& position, double time);
  void Replan(std::size_t i, const Vec2& position);
  Vec2 YieldPoint(std::size_t i, const Vec2& position, const Vec2& waypoint) const;
  // Steps of Update for pedestrian i at p (W), at time t (s).
  void UpdateWaypoints(std::size_t i, const Vec2& p, double t, bool check_line);
  void PassReachedWaypoints(std::size_t i, const Vec2& p, double t);
  // Whether pedestrian i at p has reached its next waypoint (`last`: its goal).
  bool Reached(std::size_t i, const Vec2& p, bool last) const;
  void CheckLineToWaypoint(std::size_t i, const Vec2& p);
  void CheckProgress(std::size_t i, const Vec2& p, double t);
  Vec2 SocialVelocity(std::size_t i, double dt, const SocialAgent* robot);
  // Where pedestrian i at p means to walk: a unit direction (zero: stand) and a speed (m/s), from
  // its reaction to the robot, its step aside, or its route.
  void WalkTarget(std::size_t i, const Vec2& p, Vec2* direction, double* speed) const;
  // Starts and ends pedestrian i's reaction to the robot at time t (its behaviour's).
  void UpdateReaction(std::size_t i, const Vec2& p, double t, const RobotDisc& robot);
  // The robot term of pedestrian i's behaviour: the robot as an agent (or nullptr), and the
  // social-force config whose robot strength and range apply; an impassive person gets the
  // robot's surface as an obstacle point instead.
  const SocialAgent* RobotFor(std::size_t i, const SocialAgent* robot,
                              const SocialForceConfig** config);
  // Model `ttc`: the point pedestrian i at p walks towards (its next waypoint, or beside it), and
  // the check that the straight line to it is clear.
  Vec2 AimPoint(std::size_t i, const Vec2& p) const;
  void CheckAim(std::size_t i, const Vec2& p);

  CrowdConfig config_;
  std::unique_ptr<GeometryIndex> index_;
  std::vector<std::unique_ptr<WalkPlanner>> planners_;  // [0]: the constructor groups'
  StaticGeometry obstacles_;                            // solids added at run time
  core::Rng runtime_rng_;                               // parent of the added groups' streams
  int constructor_groups_ = 0;
  std::uint64_t added_groups_ = 0;
  std::vector<PedestrianStatus> status_;
  std::vector<Walker> walkers_;
  std::optional<SocialAgent> robot_;  // as of the last Update
  RobotDisc robot_disc_;              // the same, with its heading
  SocialForceConfig scared_force_;    // social_force with the scared behaviour's robot term
  // Scratch buffers reused every step.
  std::vector<SocialAgent> agents_;
  std::vector<SocialAgent> neighbours_;
  std::vector<Vec2> obstacle_points_;
  std::vector<Vec2> new_velocities_;
  // The way each pedestrian meant to walk in the last Update (zero: standing, or not yet): what
  // the others see of it (SocialAgent::heading).
  std::vector<Vec2> headings_;
};

}  // namespace retrace::sim
