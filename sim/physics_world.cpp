#include "sim/physics_world.hpp"

#include <box2d/box2d.h>

#include <cmath>
#include <cstdint>
#include <utility>

#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::sim {
namespace {

// Fixture user data: which body a fixture belongs to.
constexpr std::uintptr_t kStaticTag = 0;
constexpr std::uintptr_t kRobotTag = 1;
constexpr std::uintptr_t kFirstPedestrianTag = 2;

// Friction between the robot and walls makes a robot pushing into a wall at an angle slide
// along it only partly, like rubber wheels would; pedestrians have none so that they glide
// along walls and around each other instead of sticking.
constexpr float kStaticFriction = 0.5f;
constexpr float kRobotFriction = 0.5f;
constexpr float kPedestrianFriction = 0.0f;

// Edges shorter than this are skipped: Box2D gains nothing from them and their neighbours'
// end points already cover the spot.
constexpr double kMinEdgeLength = 1e-6;

b2Vec2 ToB2(const core::Vec2& p) { return {static_cast<float>(p.x()), static_cast<float>(p.y())}; }
core::Vec2 FromB2(const b2Vec2& p) { return {static_cast<double>(p.x), static_cast<double>(p.y)}; }

}  // namespace

// Records every contact that begins between the robot and anything else. Not in the anonymous
// namespace: PhysicsWorld::Impl holds one, and a class with external linkage should not have a
// member of an internal type.
class RobotContactListener final : public b2ContactListener {
 public:
  void BeginContact(b2Contact* contact) override {
    const std::uintptr_t a = contact->GetFixtureA()->GetUserData().pointer;
    const std::uintptr_t b = contact->GetFixtureB()->GetUserData().pointer;
    if (a != kRobotTag && b != kRobotTag) return;
    const std::uintptr_t other = a == kRobotTag ? b : a;
    CollisionEvent e;
    e.time = time;
    if (other == kStaticTag) {
      e.kind = CollisionKind::kStatic;
    } else {
      e.kind = CollisionKind::kPedestrian;
      e.pedestrian_id = static_cast<int>(other - kFirstPedestrianTag);
    }
    b2WorldManifold wm;
    contact->GetWorldManifold(&wm);
    const int n = contact->GetManifold()->pointCount;
    if (n > 0) {
      b2Vec2 sum(0.0f, 0.0f);
      for (int i = 0; i < n; ++i) sum += wm.points[i];
      e.point_W = FromB2(sum) / static_cast<double>(n);
    } else {
      // Not reachable for a touching contact; fall back to the robot's centre.
      const b2Body* robot =
          (a == kRobotTag ? contact->GetFixtureA() : contact->GetFixtureB())->GetBody();
      e.point_W = FromB2(robot->GetPosition());
    }
    events.push_back(e);
  }

  double time = 0.0;
  std::vector<CollisionEvent> events;
};

void PhysicsConfig::Validate() const {
  if (!(time_step > 0.0 && time_step <= 0.1)) {
    throw core::ConfigError("time_step",
                            "must be in (0, 0.1] s, got " + core::FormatNumber(time_step));
  }
  core::RequireIntInRange("velocity_iterations", velocity_iterations, 1, 100);
  core::RequireIntInRange("position_iterations", position_iterations, 1, 100);
}

struct PhysicsWorld::Impl {
  explicit Impl(const PhysicsConfig& c) : config(c), world(b2Vec2(0.0f, 0.0f)) {}

  PhysicsConfig config;
  b2World world;
  RobotContactListener listener;
  b2Body* ground = nullptr;  // the static body: world geometry and added obstacles
  b2Body* robot = nullptr;
  double robot_radius = 0.0;
  std::vector<b2Body*> pedestrians;
  std::vector<double> pedestrian_radii;
  std::uint64_t steps = 0;

  b2Body* Pedestrian(int id) const {
    RETRACE_CHECK(id >= 0 && id < static_cast<int>(pedestrians.size()));
    return pedestrians[static_cast<std::size_t>(id)];
  }
  b2Body* AddCircleBody(const core::Vec2& p_W, double angle, double radius, double mass,
                        float friction, std::uintptr_t tag, bool fixed_rotation) {
    RETRACE_CHECK(radius > 0.0 && mass > 0.0);
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position = ToB2(p_W);
    def.angle = static_cast<float>(angle);
    def.allowSleep = false;
    def.fixedRotation = fixed_rotation;
    b2Body* body = world.CreateBody(&def);
    b2CircleShape shape;
    shape.m_radius = static_cast<float>(radius);
    b2FixtureDef fixture;
    fixture.shape = &shape;
    fixture.density = static_cast<float>(mass / (core::kPi * radius * radius));
    fixture.friction = friction;
    fixture.restitution = 0.0f;
    fixture.userData.pointer = tag;
    body->CreateFixture(&fixture);
    return body;
  }
};

PhysicsWorld::PhysicsWorld(const StaticGeometry& geometry, const PhysicsConfig& config) {
  config.Validate();
  impl_ = std::make_unique<Impl>(config);
  impl_->world.SetAllowSleeping(false);
  impl_->world.SetContactListener(&impl_->listener);

  b2BodyDef def;
  def.type = b2_staticBody;
  b2Body* ground = impl_->world.CreateBody(&def);
  impl_->ground = ground;
  b2FixtureDef fixture;
  fixture.friction = kStaticFriction;
  fixture.restitution = 0.0f;
  fixture.userData.pointer = kStaticTag;
  for (const Segment& s : geometry.segments()) {
    if ((s.b - s.a).norm() < kMinEdgeLength) continue;
    // Two-sided: chain shapes collide on one side only (docs/DESIGN.md §4).
    b2EdgeShape edge;
    edge.SetTwoSided(ToB2(s.a), ToB2(s.b));
    fixture.shape = &edge;
    ground->CreateFixture(&fixture);
  }
  for (const Circle& c : geometry.circles()) {
    b2CircleShape circle;
    circle.m_p = ToB2(c.center);
    // The same skin as edges get (b2_polygonRadius): Box2D's continuous collision lets bodies
    // sink up to 3 * b2_linearSlop into a shape, and the skin keeps that outside the circle.
    circle.m_radius = static_cast<float>(c.radius) + b2_polygonRadius;
    fixture.shape = &circle;
    ground->CreateFixture(&fixture);
  }
}

PhysicsWorld::~PhysicsWorld() = default;
PhysicsWorld::PhysicsWorld(PhysicsWorld&&) noexcept = default;
PhysicsWorld& PhysicsWorld::operator=(PhysicsWorld&&) noexcept = default;

const PhysicsConfig& PhysicsWorld::config() const { return impl_->config; }
double PhysicsWorld::time_step() const { return impl_->config.time_step; }
double PhysicsWorld::time() const {
  return static_cast<double>(impl_->steps) * impl_->config.time_step;
}
std::uint64_t PhysicsWorld::step_count() const { return impl_->steps; }

void PhysicsWorld::Step() {
  // Box2D reports a contact at the start of the step following the one that made it touch,
  // using the positions at this instant.
  impl_->listener.time = time();
  impl_->world.Step(static_cast<float>(impl_->config.time_step), impl_->config.velocity_iterations,
                    impl_->config.position_iterations);
  ++impl_->steps;
}

void PhysicsWorld::AddStaticBox(const core::Pose2& X_WB, const core::Vec2& size) {
  RETRACE_CHECK(std::isfinite(X_WB.x) && std::isfinite(X_WB.y) && std::isfinite(X_WB.theta));
  RETRACE_CHECK(size.x() > 0.0 && size.y() > 0.0 && size.allFinite());
  // SetAsBox rather than Set(points): Set computes a convex hull and welds close vertices, and
  // silently replaces a degenerate hull by a 2 m box. The polygon keeps Box2D's 1 cm skin, like
  // the world's edges.
  b2PolygonShape box;
  box.SetAsBox(static_cast<float>(0.5 * size.x()), static_cast<float>(0.5 * size.y()),
               ToB2(X_WB.translation()), static_cast<float>(X_WB.theta));
  b2FixtureDef fixture;
  fixture.shape = &box;
  fixture.friction = kStaticFriction;
  fixture.restitution = 0.0f;
  fixture.userData.pointer = kStaticTag;
  impl_->ground->CreateFixture(&fixture);
}

void PhysicsWorld::AddStaticCircle(const Circle& c) {
  RETRACE_CHECK(c.center.allFinite() && c.radius > 0.0 && std::isfinite(c.radius));
  b2CircleShape circle;
  circle.m_p = ToB2(c.center);
  circle.m_radius = static_cast<float>(c.radius) + b2_polygonRadius;  // skin, as in the ctor
  b2FixtureDef fixture;
  fixture.shape = &circle;
  fixture.friction = kStaticFriction;
  fixture.restitution = 0.0f;
  fixture.userData.pointer = kStaticTag;
  impl_->ground->CreateFixture(&fixture);
}

void PhysicsWorld::AddRobot(const core::Pose2& X_WR, double radius, double mass) {
  RETRACE_CHECK(impl_->robot == nullptr);
  impl_->robot = impl_->AddCircleBody(X_WR.translation(), X_WR.theta, radius, mass, kRobotFriction,
                                      kRobotTag, /*fixed_rotation=*/false);
  // Continuous collision against pedestrians too (Box2D does it against static bodies anyway):
  // the robot never overlaps a pedestrian, and contact times are exact.
  impl_->robot->SetBullet(true);
  impl_->robot_radius = radius;
}

bool PhysicsWorld::has_robot() const { return impl_->robot != nullptr; }

double PhysicsWorld::robot_radius() const {
  RETRACE_CHECK(has_robot());
  return impl_->robot_radius;
}

core::Pose2 PhysicsWorld::RobotPose() const {
  RETRACE_CHECK(has_robot());
  const b2Vec2 p = impl_->robot->GetPosition();
  return {static_cast<double>(p.x), static_cast<double>(p.y),
          static_cast<double>(impl_->robot->GetAngle())};
}

core::Twist PhysicsWorld::RobotTwist() const {
  RETRACE_CHECK(has_robot());
  const double theta = static_cast<double>(impl_->robot->GetAngle());
  const core::Vec2 v = FromB2(impl_->robot->GetLinearVelocity());
  return {v.x() * std::cos(theta) + v.y() * std::sin(theta),
          static_cast<double>(impl_->robot->GetAngularVelocity())};
}

core::Vec2 PhysicsWorld::RobotVelocityW() const {
  RETRACE_CHECK(has_robot());
  return FromB2(impl_->robot->GetLinearVelocity());
}

void PhysicsWorld::SetRobotVelocity(const core::Twist& twist_R) {
  RETRACE_CHECK(has_robot());
  RETRACE_CHECK(std::isfinite(twist_R.v) && std::isfinite(twist_R.omega));
  const double theta = static_cast<double>(impl_->robot->GetAngle());
  impl_->robot->SetLinearVelocity(
      ToB2(core::Vec2(twist_R.v * std::cos(theta), twist_R.v * std::sin(theta))));
  impl_->robot->SetAngularVelocity(static_cast<float>(twist_R.omega));
}

void PhysicsWorld::TeleportRobot(const core::Pose2& X_WR) {
  RETRACE_CHECK(has_robot());
  impl_->robot->SetTransform(ToB2(X_WR.translation()), static_cast<float>(X_WR.theta));
  impl_->robot->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
  impl_->robot->SetAngularVelocity(0.0f);
}

int PhysicsWorld::AddPedestrian(const core::Vec2& p_W, double radius, double mass) {
  const int id = static_cast<int>(impl_->pedestrians.size());
  impl_->pedestrians.push_back(impl_->AddCircleBody(
      p_W, 0.0, radius, mass, kPedestrianFriction,
      kFirstPedestrianTag + static_cast<std::uintptr_t>(id), /*fixed_rotation=*/true));
  impl_->pedestrian_radii.push_back(radius);
  return id;
}

core::Vec2 PhysicsWorld::PedestrianPosition(int id) const {
  return FromB2(impl_->Pedestrian(id)->GetPosition());
}

core::Vec2 PhysicsWorld::PedestrianVelocity(int id) const {
  return FromB2(impl_->Pedestrian(id)->GetLinearVelocity());
}

void PhysicsWorld::SetPedestrianVelocity(int id, const core::Vec2& v_W) {
  RETRACE_CHECK(std::isfinite(v_W.x()) && std::isfinite(v_W.y()));
  impl_->Pedestrian(id)->SetLinearVelocity(ToB2(v_W));
}

std::vector<DynamicCircle> PhysicsWorld::PedestrianCircles() const {
  std::vector<DynamicCircle> out;
  out.reserve(impl_->pedestrians.size());
  for (std::size_t i = 0; i < impl_->pedestrians.size(); ++i) {
    out.push_back({FromB2(impl_->pedestrians[i]->GetPosition()), impl_->pedestrian_radii[i],
                   static_cast<int>(i)});
  }
  return out;
}

std::vector<CollisionEvent> PhysicsWorld::TakeCollisions() {
  return std::exchange(impl_->listener.events, {});
}

}  // namespace retrace::sim

// Box2D times every b2World::Step for its b2Profile, reading the clock (gettimeofday) at each
// phase. retrace never reads the profile, so the timer's three methods are defined here without a
// clock: Debian's libbox2d calls them through its procedure linkage table, and these definitions,
// linked into every program that steps a PhysicsWorld (this file is), take their place (ELF
// symbol interposition; docs/BENCHMARKS.md, "Box2D's step timer"). A Box2D that does not export
// its timer (a static or hidden-visibility build) keeps its own: nothing changes but the cost.
// b2World::GetProfile() reads 0 ms.
b2Timer::b2Timer() {}
void b2Timer::Reset() {}
float b2Timer::GetMilliseconds() const { return 0.0f; }
