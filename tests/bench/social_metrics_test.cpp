// The social navigation metrics (bench/metrics/metrics.hpp, "social"), each on a constructed case
// whose answer is known in closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "bench/metrics/internal/social.hpp"
#include "bench/metrics/metrics.hpp"
#include "bench/metrics/metrics_json.hpp"

namespace retrace::bench {
namespace {

using core::Pose2;
using core::Vec2;
using internal::Social;
using internal::TimeToCollision;

constexpr double kSocialDt = 0.1;  // s between the constructed samples
constexpr double kSocialInf = std::numeric_limits<double>::infinity();

// A run of n samples kSocialDt apart standing at the origin, facing +x, commanding speed v.
RunTrace StandingRun(int n, double v = 0.0) {
  RunTrace run;
  run.robot_radius = 0.3;
  for (int i = 0; i < n; ++i) {
    PlaybackSample s;
    s.time = kSocialDt * i;
    s.command.v = v;
    s.pedestrian_gap = kSocialInf;
    run.samples.push_back(s);
  }
  return run;
}

// Adds pedestrian `id` (radius 0.3, desired speed 1.3 m/s) at sample i, with the sample's gap.
void AddPedestrian(RunTrace& run, int i, int id, const Vec2& p, const Vec2& v) {
  NearbyPedestrian n;
  n.sample = i;
  n.id = id;
  n.position = p;
  n.velocity = v;
  n.radius = 0.3;
  n.desired_speed = 1.3;
  run.nearby.push_back(n);
  PlaybackSample& s = run.samples[static_cast<std::size_t>(i)];
  s.pedestrian_gap = std::min(s.pedestrian_gap, p.norm() - n.radius - run.robot_radius);
}

SocialStats SocialOf(const RunTrace& run, bool success = true, double path_length = 0.0,
                     double time = 0.0) {
  return Social(run, 100.0, 200.0, success, path_length, time, MetricsConfig{});
}

TEST(SocialMetrics, TimeToCollisionOfTwoDiscs) {
  // Head on: 5 m apart, closing at 1 m/s, touching at 1 m: 4 s.
  EXPECT_DOUBLE_EQ(TimeToCollision({5, 0}, {-1, 0}, 1.0), 4.0);
  // Already touching or overlapping: 0.
  EXPECT_EQ(TimeToCollision({0.5, 0}, {1, 0}, 1.0), 0.0);
  // Moving apart, standing still, or passing 2 m to the side of a 1 m reach: never.
  EXPECT_EQ(TimeToCollision({5, 0}, {1, 0}, 1.0), kSocialInf);
  EXPECT_EQ(TimeToCollision({5, 0}, {0, 0}, 1.0), kSocialInf);
  EXPECT_EQ(TimeToCollision({5, 2}, {-1, 0}, 1.0), kSocialInf);
  // Offset by 0.6 m of a 1 m reach: touches when the along-track distance is 0.8 m.
  EXPECT_NEAR(TimeToCollision({5, 0.6}, {-2, 0}, 1.0), (5.0 - 0.8) / 2.0, 1e-12);
}

TEST(SocialMetrics, ZoneTimesCountEachSampleUntilTheNext) {
  RunTrace run = StandingRun(6);
  const std::vector<double> gaps = {2.0, 1.0, 0.4, 0.3, 1.3, kSocialInf};
  for (std::size_t i = 0; i < gaps.size(); ++i) run.samples[i].pedestrian_gap = gaps[i];
  const SocialStats s = SocialOf(run);
  EXPECT_NEAR(s.intimate_time_s, 2 * kSocialDt, 1e-12);  // 0.4 and 0.3 m
  EXPECT_NEAR(s.personal_time_s, 3 * kSocialDt, 1e-12);  // and 1.0 m
}

TEST(SocialMetrics, EfficienciesAreForSuccessfulRunsOnly) {
  const RunTrace run = StandingRun(3);
  const SocialStats ok = SocialOf(run, true, 125.0, 250.0);
  EXPECT_DOUBLE_EQ(ok.path_efficiency, 100.0 / 125.0);
  EXPECT_DOUBLE_EQ(ok.time_efficiency, 200.0 / 250.0);
  const SocialStats failed = SocialOf(run, false, 50.0, 80.0);
  EXPECT_TRUE(std::isnan(failed.path_efficiency));
  EXPECT_TRUE(std::isnan(failed.time_efficiency));
}

TEST(SocialMetrics, JerkIsTheThirdDerivativeOfThePosition) {
  // x = t³ / 6: jerk 1 m/s³ everywhere, exactly for third differences of a cubic.
  RunTrace cubic = StandingRun(40);
  for (PlaybackSample& s : cubic.samples) s.X_WR = Pose2(s.time * s.time * s.time / 6.0, 0.0, 0.0);
  const Summary jerk = SocialOf(cubic).jerk_m_s3;
  EXPECT_EQ(jerk.count, 37);
  EXPECT_NEAR(jerk.mean, 1.0, 1e-6);
  EXPECT_NEAR(jerk.max, 1.0, 1e-6);
  // Constant velocity: none.
  RunTrace steady = StandingRun(40);
  for (PlaybackSample& s : steady.samples) s.X_WR = Pose2(0.8 * s.time, 0.3 * s.time, 0.0);
  EXPECT_NEAR(SocialOf(steady).jerk_m_s3.max, 0.0, 1e-9);
}

TEST(SocialMetrics, MinimumTimeToCollisionAtTheCommandedVelocity) {
  // The robot commands 1 m/s along +x; a pedestrian stands 5 m ahead, another walks parallel
  // 3 m to the side: only the first is on a collision course, touching after 5 - 0.6 m.
  RunTrace run = StandingRun(3, 1.0);
  AddPedestrian(run, 1, 7, {5, 0}, {0, 0});
  AddPedestrian(run, 1, 8, {0, 3}, {1, 0});
  EXPECT_NEAR(SocialOf(run).min_ttc_s, 4.4, 1e-12);
  // Nobody on a collision course: the horizon.
  RunTrace clear = StandingRun(3, 1.0);
  AddPedestrian(clear, 1, 8, {0, 3}, {1, 0});
  EXPECT_EQ(SocialOf(clear).min_ttc_s, MetricsConfig{}.ttc_horizon);
}

TEST(SocialMetrics, PedestriansInThePersonalZonePassYieldOrWait) {
  RunTrace run = StandingRun(40);
  // Pedestrian 1 walks by 1 m from the robot's centre at its desired speed for 1 s: passed.
  for (int i = 0; i < 10; ++i) AddPedestrian(run, i, 1, {-0.65 + 0.13 * i, 1.0}, {1.3, 0});
  // Pedestrian 2 stands 1.2 m away for 1.5 s, then walks off: blocked, waited 1.5 s.
  for (int i = 5; i < 20; ++i) AddPedestrian(run, i, 2, {1.2, 0}, {0, 0});
  for (int i = 20; i < 30; ++i) AddPedestrian(run, i, 2, {1.2 + 0.13 * (i - 19), 0}, {1.3, 0});
  // Pedestrian 3 crawls at 0.5 m/s (below 0.7 × 1.3) for 1 s while 1 m away: yielded.
  for (int i = 20; i < 30; ++i) AddPedestrian(run, i, 3, {0, -1.0}, {0.5, 0});
  // Pedestrian 4 stays 4 m away: no encounter.
  for (int i = 0; i < 40; ++i) AddPedestrian(run, i, 4, {-4, 0}, {0, 0});
  std::stable_sort(
      run.nearby.begin(), run.nearby.end(),
      [](const NearbyPedestrian& a, const NearbyPedestrian& b) { return a.sample < b.sample; });
  const CrowdReaction c = SocialOf(run).crowd;
  EXPECT_EQ(c.encounters, 3);
  EXPECT_EQ(c.passed, 1);
  EXPECT_EQ(c.yielded, 1);
  EXPECT_EQ(c.blocked, 1);
  EXPECT_NEAR(c.wait_time_s, 1.5, 1e-9);
  EXPECT_NEAR(c.max_wait_s, 1.5, 1e-9);
}

TEST(SocialMetrics, PeopleStandingStillByDesignAreNeitherBlockedNorWaiting) {
  // Before the fix a person of pedestrian mode `stand` the robot drove past counted as blocked
  // (about 11 per campus run with clutter): its speed is 0 whatever the robot does.
  RunTrace run = StandingRun(40);
  for (int i = 0; i < 30; ++i) {
    AddPedestrian(run, i, 5, {0.9, 0.5}, {0, 0});
    run.nearby.back().standing = true;
  }
  // A walker standing as long in the same spot still counts as blocked.
  for (int i = 0; i < 30; ++i) AddPedestrian(run, i, 6, {-0.9, 0.5}, {0, 0});
  std::stable_sort(
      run.nearby.begin(), run.nearby.end(),
      [](const NearbyPedestrian& a, const NearbyPedestrian& b) { return a.sample < b.sample; });
  const SocialStats s = SocialOf(run);
  EXPECT_EQ(s.crowd.encounters, 2);
  EXPECT_EQ(s.crowd.standing, 1);
  EXPECT_EQ(s.crowd.blocked, 1);
  EXPECT_EQ(s.crowd.passed + s.crowd.yielded, 0);
  EXPECT_NEAR(s.crowd.wait_time_s, 3.0, 1e-9);  // the walker's 3 s only
  EXPECT_NEAR(s.crowd.max_wait_s, 3.0, 1e-9);
  // The zones still count time beside the standing person.
  EXPECT_NEAR(s.personal_time_s, 3.0, 1e-9);
}

TEST(SocialMetrics, AggregateAveragesZonesAndEfficienciesAndSumsTheCrowd) {
  RunMetrics a, b, c;
  a.social.intimate_time_s = 1.0;
  a.social.personal_time_s = 4.0;
  a.social.min_ttc_s = 3.0;
  a.social.path_efficiency = 0.9;
  a.social.time_efficiency = 0.8;
  a.social.crowd.encounters = 2;
  a.social.crowd.blocked = 1;
  a.social.crowd.max_wait_s = 2.0;
  a.social.crowd.wait_time_s = 2.0;
  b.social.intimate_time_s = 3.0;
  b.social.personal_time_s = 6.0;
  b.social.min_ttc_s = 1.5;
  b.social.path_efficiency = 0.7;
  b.social.time_efficiency = 0.6;
  b.social.crowd.encounters = 1;
  b.social.crowd.passed = 1;
  b.social.crowd.standing = 2;
  c.social.min_ttc_s = 10.0;  // a failed run: no efficiencies
  const SocialStats s = internal::AggregateSocial({a, b, c});
  EXPECT_NEAR(s.intimate_time_s, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.personal_time_s, 10.0 / 3.0, 1e-12);
  EXPECT_EQ(s.min_ttc_s, 1.5);
  EXPECT_NEAR(s.path_efficiency, 0.8, 1e-12);
  EXPECT_NEAR(s.time_efficiency, 0.7, 1e-12);
  EXPECT_EQ(s.crowd.encounters, 3);
  EXPECT_EQ(s.crowd.blocked, 1);
  EXPECT_EQ(s.crowd.passed, 1);
  EXPECT_EQ(s.crowd.standing, 2);
  EXPECT_EQ(s.crowd.max_wait_s, 2.0);
}

TEST(SocialMetrics, AreInTheRunsJson) {
  RunMetrics m;
  m.social.min_ttc_s = 2.5;
  const nlohmann::json j = ToJson(m);
  ASSERT_TRUE(j.contains("social"));
  EXPECT_EQ(j["social"]["min_ttc_s"], 2.5);
  EXPECT_TRUE(j["social"]["crowd"].contains("blocked"));
  EXPECT_TRUE(j["social"]["crowd"].contains("standing"));
  EXPECT_TRUE(j["social"]["path_efficiency"].is_null());
}

}  // namespace
}  // namespace retrace::bench
