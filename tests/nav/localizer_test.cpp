#include "nav/localizer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "tests/nav/localizer_room.hpp"
#include "tests/support/config_key.hpp"
#include "tests/support/particle_covariance.hpp"

namespace retrace::nav {
namespace {

using namespace testing_room;

TEST(Localizer, NoUpdateWhileStandingStill) {
  Drive drive(3);
  Localizer loc(TestConfig(), TestRobot(), core::Rng(3));
  loc.SetMap(drive.map);
  loc.Initialize(drive.X_WR, 0.1, 0.05);
  core::Rng noise(4);
  const Pose2 X_WL = drive.X_WR * TestRobot().X_RL;
  // The first scan after Initialize is used once.
  EXPECT_TRUE(loc.Update(MakeScan(drive.rects, {}, X_WL, noise)).ran);
  const std::vector<Particle> before = loc.particles();
  for (int i = 0; i < 50; ++i) {
    loc.Predict({0.0, 0.0});
    const LocalizerUpdate u = loc.Update(MakeScan(drive.rects, {}, X_WL, noise));
    EXPECT_FALSE(u.ran);
    EXPECT_TRUE(u.beams.empty());
  }
  const std::vector<Particle>& after = loc.particles();
  ASSERT_EQ(before.size(), after.size());
  for (std::size_t j = 0; j < before.size(); ++j) {
    EXPECT_EQ(before[j].X_MR, after[j].X_MR);
    EXPECT_EQ(before[j].weight, after[j].weight);
  }
  // Below the 0.2 m gate: still nothing; beyond it: one update.
  loc.Predict({0.15, 0.0});
  EXPECT_FALSE(loc.Update(MakeScan(drive.rects, {}, X_WL, noise)).ran);
  loc.Predict({0.06, 0.0});
  EXPECT_TRUE(loc.Update(MakeScan(drive.rects, {}, X_WL, noise)).ran);
  EXPECT_FALSE(loc.Update(MakeScan(drive.rects, {}, X_WL, noise)).ran);
  // Rotation in place opens the gate too (2°).
  loc.Predict({0.0, core::DegToRad(2.5)});
  EXPECT_TRUE(loc.Update(MakeScan(drive.rects, {}, X_WL, noise)).ran);
}

TEST(Localizer, ReportsTheBeliefsSpreadAndTheParticlesOfTheRejectionTest) {
  Drive drive(5);
  core::Rng noise(6);
  const Pose2 X_WL = drive.X_WR * TestRobot().X_RL;
  const auto first_update = [&](double sigma_xy, double sigma_theta, int sample) {
    LocalizerConfig config = TestConfig();
    config.rejection.particles = sample;
    Localizer loc(config, TestRobot(), core::Rng(5));
    loc.SetMap(drive.map);
    loc.Initialize(drive.X_WR, sigma_xy, sigma_theta);
    return loc.Update(MakeScan(drive.rects, {}, X_WL, noise));
  };
  // Position only: the spread is the RMS distance from the mean, √2·σ for independent x and y.
  const LocalizerUpdate tight = first_update(0.05, 0.0, 0);
  EXPECT_NEAR(tight.spread, 0.05 * std::sqrt(2.0), 0.01);
  EXPECT_EQ(tight.rejection_particles, TestConfig().particles);
  // A heading spread adds the mean tested range times its RMS (the room's ranges are metres).
  const LocalizerUpdate turned = first_update(0.05, 0.1, 0);
  EXPECT_GT(turned.spread, tight.spread + 0.1);
  // A sample of 100 drawn by weight: at most 100 distinct particles, and the same spread.
  const LocalizerUpdate sampled = first_update(0.05, 0.0, 100);
  EXPECT_LE(sampled.rejection_particles, 100);
  EXPECT_GT(sampled.rejection_particles, 50);
  EXPECT_EQ(sampled.spread, tight.spread);
}

TEST(Localizer, ApplyMapSwitchTransformsEveryParticleByEquationOne) {
  Drive drive(5);
  Localizer loc(TestConfig(), TestRobot(), core::Rng(5));
  loc.SetMap(drive.map);
  loc.Initialize(Pose2(6.0, 2.0, 0.3), 0.05, 0.02);
  const std::vector<Particle> before = loc.particles();
  const Pose2 estimate_before = loc.Estimate();
  const Pose2 X_MkS(4.0, 1.5, 0.7);  // switch pose in the old map
  const Pose2 X_new_old = X_MkS.Inverse();
  loc.ApplyMapSwitch(drive.map, X_new_old);
  const std::vector<Particle>& after = loc.particles();
  ASSERT_EQ(before.size(), after.size());
  for (std::size_t j = 0; j < before.size(); ++j) {
    EXPECT_EQ(after[j].X_MR, X_new_old * before[j].X_MR);
    EXPECT_EQ(after[j].weight, before[j].weight);
  }
  const Pose2 expected = X_new_old * estimate_before;
  EXPECT_NEAR(loc.Estimate().x, expected.x, 1e-9);
  EXPECT_NEAR(loc.Estimate().y, expected.y, 1e-9);
  EXPECT_NEAR(core::AngleDiff(loc.Estimate().theta, expected.theta), 0.0, 1e-9);
  // The new map's first scan is used without motion.
  core::Rng noise(6);
  EXPECT_TRUE(loc.Update(MakeScan(drive.rects, {}, drive.X_WR * TestRobot().X_RL, noise)).ran);
}

TEST(Localizer, EstimateFollowsTheMainCloudWhenItStraddlesHistogramCells) {
  // A converged cloud heading exactly -90 deg (a histogram border) around an xy corner splits
  // into eight cells of 10 % each; one injected particle 40 m away carries 20 %. The estimate
  // must stay with the cloud (the campus run whose estimate jumped 36 m for three ticks).
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(3));
  std::vector<Particle> particles;
  const double south = -0.5 * core::kPi;
  for (int i = 0; i < 400; ++i) {
    const double dx = (i % 2 ? 0.04 : -0.04) + 0.001 * (i % 7);
    const double dy = ((i / 2) % 2 ? 0.04 : -0.04) - 0.001 * (i % 5);
    const double dt = ((i / 4) % 2 ? 0.01 : -0.01);
    particles.push_back({core::Pose2(dx, dy, south + dt), 0.8 / 400});
  }
  particles.push_back({core::Pose2(30.0, 30.0, 1.6), 0.2});
  localizer.SetParticles(particles);
  const core::Pose2 estimate = localizer.Estimate();
  EXPECT_LT(estimate.translation().norm(), 0.05);
  EXPECT_NEAR(core::AngleDiff(estimate.theta, south), 0.0, 0.02);
}

TEST(Localizer, SetParticlesNormalisesAndRejectsBadSets) {
  Localizer localizer(LocalizerConfig{}, RobotGeometry{}, core::Rng(3));
  localizer.SetParticles({{core::Pose2(1, 0, 0), 2.0}, {core::Pose2(1, 0, 0), 6.0}});
  ASSERT_EQ(localizer.particles().size(), 2u);
  EXPECT_DOUBLE_EQ(localizer.particles()[0].weight, 0.25);
  EXPECT_THROW(localizer.SetParticles({}), core::ConfigError);
  EXPECT_THROW(localizer.SetParticles({{core::Pose2(0, 0, 0), 0.0}}), core::ConfigError);
  EXPECT_THROW(localizer.SetParticles({{core::Pose2(0, 0, 0), -1.0}}), core::ConfigError);
}

TEST(Localizer, DeterministicPerSeed) {
  // The same drive localized with seeds 9, 9 and 10: the first two give the same particles,
  // bit for bit; the third other ones (the seed is what decides, not the drive alone).
  const auto particles_after = [](std::uint64_t seed) {
    Drive drive(9);
    Localizer loc(TestConfig(), TestRobot(), core::Rng(seed));
    loc.SetMap(drive.map);
    loc.Initialize(Perturbed(drive.X_WR, 9), 0.5, 0.2);
    DriveAndLocalize(loc, drive, 8, true);
    return loc.particles();
  };
  const std::vector<Particle> a = particles_after(9);
  const std::vector<Particle> b = particles_after(9);
  const std::vector<Particle> other = particles_after(10);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t j = 0; j < a.size(); ++j) {
    EXPECT_EQ(a[j].X_MR, b[j].X_MR);
    EXPECT_EQ(a[j].weight, b[j].weight);
  }
  ASSERT_EQ(a.size(), other.size());
  std::size_t differ = 0;
  for (std::size_t j = 0; j < a.size(); ++j) differ += a[j].X_MR == other[j].X_MR ? 0 : 1;
  EXPECT_GT(differ, a.size() / 2);
}

TEST(Localizer, KldSamplingAdaptsTheParticleCount) {
  LocalizerConfig config = TestConfig();
  config.kld.enabled = true;
  config.kld.min_particles = 100;
  config.kld.max_particles = 3000;
  config.particles = 3000;
  Drive drive(11);
  Localizer loc(config, TestRobot(), core::Rng(11));
  loc.SetMap(drive.map);
  loc.Initialize(Perturbed(drive.X_WR, 11), 0.5, 0.2);
  EXPECT_EQ(loc.particles().size(), 3000u);
  const RunResult r = DriveAndLocalize(loc, drive, 20, false, 0);
  std::printf("[ report ] KLD-sampling: %zu particles after 20 updates, error %.3f m\n",
              loc.particles().size(), r.final_position_error);
  EXPECT_LT(loc.particles().size(), 1500u);
  EXPECT_GE(loc.particles().size(), 100u);
  EXPECT_LT(r.final_position_error, 0.2);
}

TEST(Localizer, CovarianceShrinksAsItConverges) {
  Drive drive(12);
  Localizer loc(TestConfig(), TestRobot(), core::Rng(12));
  loc.SetMap(drive.map);
  loc.Initialize(drive.X_WR, 0.5, 0.2);
  const Eigen::Matrix3d before = testing::ParticleCovariance(loc.particles(), loc.Estimate());
  EXPECT_NEAR(before(0, 0), 0.25, 0.05);
  EXPECT_NEAR(before(2, 2), 0.04, 0.01);
  DriveAndLocalize(loc, drive, 10, false);
  const Eigen::Matrix3d after = testing::ParticleCovariance(loc.particles(), loc.Estimate());
  EXPECT_LT(after(0, 0), 0.01);
  EXPECT_LT(after(1, 1), 0.01);
}

TEST(Localizer, ConfigErrorsNameTheKey) {
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto&) {}), kValid);
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.particles = 0; }), "particles");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.beam_step = 0; }), "beam_step");
  EXPECT_EQ(ValidationErrorKey<RobotGeometry>([](auto& r) { r.range_max = 0.01; }), "range_max");
  EXPECT_EQ(ValidationErrorKey<RobotGeometry>([](auto& r) { r.radius = 0.0; }), "radius");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.rejection.chi = 1.5; }),
            "rejection.chi");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.rejection.particles = -1; }),
            "rejection.particles");
  EXPECT_EQ(
      ValidationErrorKey<LocalizerConfig>([](auto& c) { c.rejection.beam_model.sigma_hit = 0.0; }),
      "rejection.beam_model.sigma_hit");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.motion.alpha3 = -1.0; }),
            "motion.alpha3");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>(
                [](auto& c) { c.likelihood_field.sigma_hit = std::nan(""); }),
            "likelihood_field.sigma_hit");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.augmented.alpha_fast = 1e-5; }),
            "augmented.alpha_fast");
  EXPECT_EQ(
      ValidationErrorKey<LocalizerConfig>([](auto& c) { c.augmented.reach_per_metre = -0.1; }),
      "augmented.reach_per_metre");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.kld.max_particles = 10; }),
            "kld.max_particles");
  LocalizerConfig bad;
  bad.particles = -3;
  EXPECT_THROW(Localizer(bad, RobotGeometry{}, core::Rng(1)), core::ConfigError);
  RobotGeometry bad_robot;
  bad_robot.range_min = 40.0;
  EXPECT_THROW(Localizer(LocalizerConfig{}, bad_robot, core::Rng(1)), core::ConfigError);
  Localizer loc(LocalizerConfig{}, RobotGeometry{}, core::Rng(1));
  EXPECT_THROW(loc.Initialize(Pose2(), -1.0, 0.1), core::ConfigError);
}

}  // namespace
}  // namespace retrace::nav
