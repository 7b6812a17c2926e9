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
#include "tests/support/config_key.hpp"

namespace retrace::nav {
namespace {

using core::Pose2;
using core::Vec2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

constexpr double kInfD = std::numeric_limits<double>::infinity();

// An axis-aligned rectangle [x0, x1] x [y0, y1] (m) of the exact room geometry.
struct Rect {
  double x0, y0, x1, y1;
};

struct Circle {
  Vec2 c;
  double r;
};

// A 12 m x 9 m room with 0.2 m walls and asymmetric furniture.
std::vector<Rect> RoomGeometry() {
  return {{0, 0, 12, 0.2},  {0, 8.8, 12, 9},       {0, 0, 0.2, 9},       {11.8, 0, 12, 9},
          {2, 6, 3.5, 7},   {8.3, 1.0, 9.3, 1.8},  {5.0, 4.0, 5.6, 4.6}, {9.5, 6, 10.5, 6.4},
          {1, 1, 1.6, 2.5}, {10.6, 3.5, 11.8, 3.8}};
}

// Rasterises rectangles at 0.1 m: a cell is occupied (0.95) when its centre lies in one, free
// (0.05) otherwise.
core::OccupancyGrid Rasterise(const std::vector<Rect>& rects) {
  core::OccupancyGrid g(140, 110, 0.1, Vec2(-1.0, -1.0));
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Vec2 c = g.CellToWorld({x, y});
      bool occ = false;
      for (const Rect& r : rects) {
        occ = occ || (c.x() >= r.x0 && c.x() <= r.x1 && c.y() >= r.y0 && c.y() <= r.y1);
      }
      g.SetProbability({x, y}, occ ? 0.95 : 0.05);
    }
  }
  return g;
}

double RayRect(const Vec2& o, const Vec2& d, const Rect& r) {
  double t0 = 0.0, t1 = kInfD;
  const double lo[2] = {r.x0, r.y0}, hi[2] = {r.x1, r.y1};
  for (int k = 0; k < 2; ++k) {
    if (std::abs(d[k]) < 1e-15) {
      if (o[k] < lo[k] || o[k] > hi[k]) return kInfD;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1 ? t0 : kInfD;
}

double RayCircle(const Vec2& o, const Vec2& d, const Circle& c) {
  const Vec2 m = o - c.c;
  const double b = m.dot(d), cc = m.squaredNorm() - c.r * c.r;
  const double disc = b * b - cc;
  if (disc < 0.0) return kInfD;
  const double t = -b - std::sqrt(disc);
  return t >= 0.0 ? t : kInfD;
}

// A scan like the simulated Hokuyo (270°, 1081 beams, 0.05-30 m) from X_WL, cast against the
// exact rectangles and the unmapped circles, Gaussian noise σ = 0.01 + 0.001 r. blocked[i] says
// whether beam i truly hit a circle first.
core::LaserScan MakeScan(const std::vector<Rect>& rects, const std::vector<Circle>& circles,
                         const Pose2& X_WL, core::Rng& rng, std::vector<bool>* blocked = nullptr) {
  core::LaserScan scan;
  scan.angle_min = -core::DegToRad(135.0);
  scan.angle_increment = core::DegToRad(270.0) / 1080.0;
  scan.range_min = 0.05;
  scan.range_max = 30.0;
  scan.ranges.resize(1081);
  if (blocked != nullptr) blocked->assign(1081, false);
  for (std::size_t i = 0; i < 1081; ++i) {
    const double a = X_WL.theta + scan.Angle(i);
    const Vec2 d(std::cos(a), std::sin(a));
    double t_static = kInfD, t_dyn = kInfD;
    for (const Rect& r : rects) t_static = std::min(t_static, RayRect(X_WL.translation(), d, r));
    for (const Circle& c : circles) t_dyn = std::min(t_dyn, RayCircle(X_WL.translation(), d, c));
    const double t = std::min(t_static, t_dyn);
    if (blocked != nullptr) (*blocked)[i] = t_dyn < t_static;
    const double r = t + (0.01 + 0.001 * t) * rng.Normal();
    scan.ranges[i] = r > 30.0 ? std::numeric_limits<float>::infinity() : static_cast<float>(r);
  }
  return scan;
}

LocalizerConfig TestConfig() {
  LocalizerConfig c;
  c.lidar_mount = Pose2(0.2, 0.0, 0.0);
  return c;
}

// The robot drives a circle of radius 2.5 m around the room centre, counter-clockwise, at
// 0.025 m per odometry tick; odometry readings carry the simulator's error model (1 % scale,
// α noise). A scan comes every second tick.
struct Drive {
  std::vector<Rect> rects = RoomGeometry();
  core::OccupancyGrid map = Rasterise(rects);
  Pose2 X_WR{6.0, 2.0, 0.0};
  core::Rng rng;
  explicit Drive(std::uint64_t seed) : rng(core::Rng(seed).Split("world")) {}

  core::OdometryDelta Step() {
    const core::OdometryDelta truth{0.025, 0.025 / 2.5};
    X_WR = core::IntegrateOdometry(X_WR, truth);
    core::OdometryDelta measured;
    measured.distance = 1.01 * truth.distance + std::sqrt(1e-3 * truth.distance) * rng.Normal();
    measured.dtheta =
        1.01 * truth.dtheta +
        std::sqrt(2e-4 * std::abs(truth.dtheta) + 1e-5 * truth.distance) * rng.Normal();
    return measured;
  }
  // Pedestrian-sized unmapped circles walking with the robot 1.4-1.6 m away, spread over the
  // field of view and blocking over 30 % of the tested beams (36.5 % measured).
  std::vector<Circle> Walkers() const {
    std::vector<Circle> out;
    for (const double bearing_deg : {-95.0, -35.0, 25.0, 85.0}) {
      const double b = X_WR.theta + core::DegToRad(bearing_deg);
      const double dist = bearing_deg < 0.0 ? 1.4 : 1.6;
      out.push_back({X_WR.translation() + dist * Vec2(std::cos(b), std::sin(b)), 0.3});
    }
    return out;
  }
};

double PositionError(const Pose2& a, const Pose2& b) { return core::Distance(a, b); }
double HeadingError(const Pose2& a, const Pose2& b) {
  return std::abs(core::AngleDiff(a.theta, b.theta));
}

// Drives until `updates` measurement updates have run; returns the final errors.
struct RunResult {
  double final_position_error = 0.0;
  double final_heading_error = 0.0;
  double mean_position_error = 0.0;  // over updates after the first `skip`
  int updates = 0;
  int tp = 0, fp = 0, fn = 0;
  int tested = 0;  // beams tested for rejection
  int injected = 0;
};

RunResult DriveAndLocalize(Localizer& loc, Drive& drive, int updates, bool walkers, int skip = 0,
                           const LocalizerConfig& config = TestConfig()) {
  RunResult res;
  double sum = 0.0;
  int counted = 0;
  for (int tick = 0; res.updates < updates && tick < 100000; ++tick) {
    loc.Predict(drive.Step());
    if (tick % 2 != 0) continue;
    std::vector<bool> blocked;
    const Pose2 X_WL = drive.X_WR * config.lidar_mount;
    const core::LaserScan scan = MakeScan(
        drive.rects, walkers ? drive.Walkers() : std::vector<Circle>{}, X_WL, drive.rng, &blocked);
    const LocalizerUpdate u = loc.Update(scan);
    if (!u.ran) continue;
    ++res.updates;
    res.injected += u.injected;
    for (std::size_t i = 0; i < u.beams.size(); ++i) {
      if (u.beams[i] == BeamUse::kUnused) continue;
      const bool rejected = u.beams[i] == BeamUse::kRejected;
      ++res.tested;
      res.tp += rejected && blocked[i];
      res.fp += rejected && !blocked[i];
      res.fn += !rejected && blocked[i];
    }
    if (res.updates > skip) {
      sum += PositionError(loc.Estimate(), drive.X_WR);
      ++counted;
    }
  }
  res.final_position_error = PositionError(loc.Estimate(), drive.X_WR);
  res.final_heading_error = HeadingError(loc.Estimate(), drive.X_WR);
  res.mean_position_error = counted > 0 ? sum / counted : 0.0;
  return res;
}

// Initial estimate 0.5 m and 10° off the truth, in a seed-dependent direction.
Pose2 Perturbed(const Pose2& truth, std::uint64_t seed) {
  core::Rng r(seed * 7919 + 1);
  const double dir = r.Uniform(-core::kPi, core::kPi);
  const double sign = r.Bernoulli(0.5) ? 1.0 : -1.0;
  return {truth.x + 0.5 * std::cos(dir), truth.y + 0.5 * std::sin(dir),
          truth.theta + sign * core::DegToRad(10.0)};
}

TEST(Localizer, ConvergesInRoomFromHalfMetreTenDegreesWithinTenUpdates) {
  int converged = 0;
  double worst = 0.0, sum = 0.0, worst_heading = 0.0;
  const int kSeeds = 20;
  for (int seed = 0; seed < kSeeds; ++seed) {
    Drive drive(static_cast<std::uint64_t>(seed));
    Localizer loc(TestConfig(), core::Rng(static_cast<std::uint64_t>(seed)).Split("localizer"));
    loc.SetMap(drive.map);
    loc.Initialize(Perturbed(drive.X_WR, static_cast<std::uint64_t>(seed)), 0.5, 0.2);
    const RunResult r = DriveAndLocalize(loc, drive, 10, false);
    ASSERT_EQ(r.updates, 10);
    const bool ok = r.final_position_error < 0.15 && r.final_heading_error < core::DegToRad(3.0);
    converged += ok ? 1 : 0;
    worst = std::max(worst, r.final_position_error);
    worst_heading = std::max(worst_heading, r.final_heading_error);
    sum += r.final_position_error;
  }
  std::printf(
      "[ report ] convergence within 10 updates: %d/%d seeds; final position error mean "
      "%.3f m, max %.3f m; max heading error %.2f deg\n",
      converged, kSeeds, sum / kSeeds, worst, core::RadToDeg(worst_heading));
  EXPECT_GE(converged, 19);  // >= 95 %
}

TEST(Localizer, RejectionKeepsErrorLowWithThirtyPercentOfBeamsBlocked) {
  const int kSeeds = 10;
  double mean_on = 0.0, mean_off = 0.0;
  int tp = 0, fp = 0, fn = 0, tested = 0;
  int worse = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    double err[2] = {0.0, 0.0};
    for (const bool on : {true, false}) {
      LocalizerConfig config = TestConfig();
      config.rejection.enabled = on;
      Drive drive(static_cast<std::uint64_t>(100 + seed));
      Localizer loc(config, core::Rng(static_cast<std::uint64_t>(seed)).Split("localizer"));
      loc.SetMap(drive.map);
      loc.Initialize(drive.X_WR, 0.05, 0.02);
      const RunResult r = DriveAndLocalize(loc, drive, 60, true, 5, config);
      err[on ? 0 : 1] = r.mean_position_error;
      if (on) {
        tp += r.tp;
        fp += r.fp;
        fn += r.fn;
        tested += r.tested;
      }
    }
    mean_on += err[0] / kSeeds;
    mean_off += err[1] / kSeeds;
    worse += err[1] > err[0] ? 1 : 0;
  }
  const double precision = tp / static_cast<double>(tp + fp);
  const double recall = tp / static_cast<double>(tp + fn);
  std::printf(
      "[ report ] 30 %% beams blocked: mean position error rejection ON %.3f m, OFF %.3f m "
      "(OFF worse on %d/%d seeds); %.1f %% of tested beams blocked; mask precision %.3f recall "
      "%.3f "
      "(tp %d fp %d fn %d)\n",
      mean_on, mean_off, worse, kSeeds, 100.0 * (tp + fn) / tested, precision, recall, tp, fp, fn);
  EXPECT_LT(mean_on, 0.1);
  EXPECT_GT(mean_off, 1.5 * mean_on);
  EXPECT_GE(worse, 8);
  EXPECT_GT(precision, 0.9);
  EXPECT_GT(recall, 0.5);
}

TEST(Localizer, NoUpdateWhileStandingStill) {
  Drive drive(3);
  Localizer loc(TestConfig(), core::Rng(3));
  loc.SetMap(drive.map);
  loc.Initialize(drive.X_WR, 0.1, 0.05);
  core::Rng noise(4);
  const Pose2 X_WL = drive.X_WR * TestConfig().lidar_mount;
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

TEST(Localizer, ApplyMapSwitchTransformsEveryParticleByEquationOne) {
  Drive drive(5);
  Localizer loc(TestConfig(), core::Rng(5));
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
  EXPECT_TRUE(
      loc.Update(MakeScan(drive.rects, {}, drive.X_WR * TestConfig().lidar_mount, noise)).ran);
}

TEST(Localizer, AugmentedMclInjectsAfterKidnappingAndRecovers) {
  const int kSeeds = 10;
  int recovered = 0, injected_any = 0, ok_without = 0;
  double sum_err = 0.0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    for (const bool augmented : {true, false}) {
      LocalizerConfig config = TestConfig();
      config.augmented.enabled = augmented;
      Drive drive(static_cast<std::uint64_t>(200 + seed));
      Localizer loc(config, core::Rng(static_cast<std::uint64_t>(seed)).Split("localizer"));
      loc.SetMap(drive.map);
      loc.Initialize(drive.X_WR, 0.05, 0.02);
      DriveAndLocalize(loc, drive, 15, false);
      // Kidnapping: the robot is carried 1.5 m sideways and turned by 20° without the
      // localizer knowing.
      drive.X_WR = drive.X_WR * Pose2(0.0, 1.5, core::DegToRad(20.0));
      const RunResult r = DriveAndLocalize(loc, drive, 40, false);
      const bool ok = r.final_position_error < 0.2 && r.final_heading_error < core::DegToRad(5.0);
      if (augmented) {
        recovered += ok ? 1 : 0;
        injected_any += r.injected > 0 ? 1 : 0;
        sum_err += r.final_position_error;
      } else {
        ok_without += ok ? 1 : 0;
      }
    }
  }
  std::printf(
      "[ report ] kidnapping by 1.5 m and 20 deg: augmented MCL recovered on %d/%d seeds (mean "
      "final "
      "error %.3f m), injected on %d/%d; without augmentation recovered on %d/%d\n",
      recovered, kSeeds, sum_err / kSeeds, injected_any, kSeeds, ok_without, kSeeds);
  EXPECT_EQ(injected_any, kSeeds);
  EXPECT_GE(recovered, 8);
  EXPECT_GT(recovered, ok_without);
}

TEST(Localizer, EstimateFollowsTheMainCloudWhenItStraddlesHistogramCells) {
  // A converged cloud heading exactly -90 deg (a histogram border) around an xy corner splits
  // into eight cells of 10 % each; one injected particle 40 m away carries 20 %. The estimate
  // must stay with the cloud (the campus run whose estimate jumped 36 m for three ticks).
  Localizer localizer(LocalizerConfig{}, core::Rng(3));
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
  Localizer localizer(LocalizerConfig{}, core::Rng(3));
  localizer.SetParticles({{core::Pose2(1, 0, 0), 2.0}, {core::Pose2(1, 0, 0), 6.0}});
  ASSERT_EQ(localizer.particles().size(), 2u);
  EXPECT_DOUBLE_EQ(localizer.particles()[0].weight, 0.25);
  EXPECT_THROW(localizer.SetParticles({}), core::ConfigError);
  EXPECT_THROW(localizer.SetParticles({{core::Pose2(0, 0, 0), 0.0}}), core::ConfigError);
  EXPECT_THROW(localizer.SetParticles({{core::Pose2(0, 0, 0), -1.0}}), core::ConfigError);
}

TEST(Localizer, DeterministicPerSeed) {
  std::vector<Particle> runs[2];
  for (int k = 0; k < 2; ++k) {
    Drive drive(9);
    Localizer loc(TestConfig(), core::Rng(9));
    loc.SetMap(drive.map);
    loc.Initialize(Perturbed(drive.X_WR, 9), 0.5, 0.2);
    DriveAndLocalize(loc, drive, 8, true);
    runs[k] = loc.particles();
  }
  ASSERT_EQ(runs[0].size(), runs[1].size());
  for (std::size_t j = 0; j < runs[0].size(); ++j) {
    EXPECT_EQ(runs[0][j].X_MR, runs[1][j].X_MR);
    EXPECT_EQ(runs[0][j].weight, runs[1][j].weight);
  }
}

TEST(Localizer, KldSamplingAdaptsTheParticleCount) {
  LocalizerConfig config = TestConfig();
  config.kld.enabled = true;
  config.kld.min_particles = 100;
  config.kld.max_particles = 3000;
  config.particles = 3000;
  Drive drive(11);
  Localizer loc(config, core::Rng(11));
  loc.SetMap(drive.map);
  loc.Initialize(Perturbed(drive.X_WR, 11), 0.5, 0.2);
  EXPECT_EQ(loc.particles().size(), 3000u);
  const RunResult r = DriveAndLocalize(loc, drive, 20, false, 0, config);
  std::printf("[ report ] KLD-sampling: %zu particles after 20 updates, error %.3f m\n",
              loc.particles().size(), r.final_position_error);
  EXPECT_LT(loc.particles().size(), 1500u);
  EXPECT_GE(loc.particles().size(), 100u);
  EXPECT_LT(r.final_position_error, 0.2);
}

TEST(Localizer, CovarianceShrinksAsItConverges) {
  Drive drive(12);
  Localizer loc(TestConfig(), core::Rng(12));
  loc.SetMap(drive.map);
  loc.Initialize(drive.X_WR, 0.5, 0.2);
  const Eigen::Matrix3d before = loc.Covariance();
  EXPECT_NEAR(before(0, 0), 0.25, 0.05);
  EXPECT_NEAR(before(2, 2), 0.04, 0.01);
  DriveAndLocalize(loc, drive, 10, false);
  const Eigen::Matrix3d after = loc.Covariance();
  EXPECT_LT(after(0, 0), 0.01);
  EXPECT_LT(after(1, 1), 0.01);
}

TEST(Localizer, ConfigErrorsNameTheKey) {
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto&) {}), kValid);
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.particles = 0; }), "particles");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.beam_step = 0; }), "beam_step");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.range_max = 0.01; }), "range_max");
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.rejection.chi = 1.5; }),
            "rejection.chi");
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
  EXPECT_EQ(ValidationErrorKey<LocalizerConfig>([](auto& c) { c.kld.max_particles = 10; }),
            "kld.max_particles");
  LocalizerConfig bad;
  bad.particles = -3;
  EXPECT_THROW(Localizer(bad, core::Rng(1)), core::ConfigError);
  Localizer loc(LocalizerConfig{}, core::Rng(1));
  EXPECT_THROW(loc.Initialize(Pose2(), -1.0, 0.1), core::ConfigError);
}

}  // namespace
}  // namespace retrace::nav
