#include "sim/odometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/config_yaml.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using core::Pose2;
using retrace::testing::kValid;
using retrace::testing::ValidationErrorKey;

// One exact unicycle step: a circular arc of length v·dt turning by omega·dt.
Pose2 ArcStep(const Pose2& X_WR, double v, double omega, double dt) {
  return core::IntegrateOdometry(X_WR, {v * dt, omega * dt});
}

struct RunResult {
  Pose2 X_OR;                    // final odometry pose
  Pose2 X_OR_true;               // final ground truth relative to the start
  double theta_unwrapped = 0.0;  // odometry heading without wrapping (rad)
  double max_error = 0.0;        // largest |odometry - truth| component over the run
  double path_length = 0.0;      // true path length (m)
};

// Drives the odometry along a ground-truth trajectory given by (v, omega) as functions of time
// at rate_hz for duration seconds, starting at X_WR0; returns the final odometry pose and, if
// check_truth, the largest deviation from ground truth at any step.

RunResult Drive(const OdometryConfig& config, std::uint64_t seed, double rate_hz, double duration,
                const std::function<core::Twist(double)>& command, const Pose2& X_WR0 = Pose2(),
                bool check_truth = false) {
  Odometry odometry(config, core::Rng(seed).Split("odometry"));
  const double dt = 1.0 / rate_hz;
  const auto steps = static_cast<long>(std::llround(duration * rate_hz));
  Pose2 X_WR = X_WR0;
  RunResult result;
  for (long k = 0; k < steps; ++k) {
    const core::Twist u = command(k * dt);
    const Pose2 next = ArcStep(X_WR, u.v, u.omega, dt);
    const core::OdometryDelta d = odometry.Update(X_WR, next);
    result.theta_unwrapped += d.dtheta;
    result.path_length += Distance(X_WR, next);
    X_WR = next;
    if (check_truth) {
      const Pose2 expected = X_WR0.Inverse() * X_WR;
      const Pose2& got = odometry.pose();
      result.max_error =
          std::max({result.max_error, std::abs(got.x - expected.x), std::abs(got.y - expected.y),
                    std::abs(core::AngleDiff(got.theta, expected.theta))});
    }
  }
  result.X_OR = odometry.pose();
  result.X_OR_true = X_WR0.Inverse() * X_WR;
  return result;
}

OdometryConfig NoiseFree() {
  OdometryConfig c;
  c.alpha1 = c.alpha2 = c.alpha3 = c.alpha4 = 0.0;
  c.scale_error = 0.0;
  c.radius_mismatch = 0.0;
  return c;
}

struct Stats {
  double mean = 0.0;
  double std = 0.0;
};

Stats Summarize(const std::vector<double>& xs) {
  Stats s;
  for (double x : xs) s.mean += x;
  s.mean /= static_cast<double>(xs.size());
  double ss = 0.0;
  for (double x : xs) ss += (x - s.mean) * (x - s.mean);
  s.std = std::sqrt(ss / static_cast<double>(xs.size() - 1));
  return s;
}

constexpr int kDriveSeeds = 200;
constexpr double kSpeed = 0.8;       // m/s
constexpr double kStraight = 100.0;  // m

core::Twist StraightAhead(double) { return {kSpeed, 0.0}; }

// Final poses of kDriveSeeds straight 100 m runs.
struct Ensemble {
  std::vector<double> x, y, theta;
};
Ensemble StraightRuns(const OdometryConfig& config, double rate_hz) {
  Ensemble e;
  for (int seed = 0; seed < kDriveSeeds; ++seed) {
    const RunResult r = Drive(config, 1000 + seed, rate_hz, kStraight / kSpeed, StraightAhead);
    e.x.push_back(r.X_OR.x);
    e.y.push_back(r.X_OR.y);
    e.theta.push_back(r.theta_unwrapped);
  }
  return e;
}

// Analytic predictions for a straight run of true length L (docs/DESIGN.md §4 model, header
// formulas).
struct StraightPrediction {
  double mean_theta, std_theta, mean_x, std_x, mean_y, std_y;
};
StraightPrediction PredictStraight(const OdometryConfig& c, double L) {
  const double Lm = (1.0 + c.scale_error) * L;         // measured distance
  const double k = c.radius_mismatch / c.wheel_base;   // rad per measured metre
  const double q = c.alpha2 + c.alpha1 * std::abs(k);  // heading variance per measured metre
  StraightPrediction p;
  p.mean_theta = k * Lm;
  p.std_theta = std::sqrt(q * Lm);
  // x = ∫cos θ ≈ ∫(1 - θ²/2), E θ(u)² = k²u² + q u.
  p.mean_x = Lm - k * k * Lm * Lm * Lm / 6.0 - q * Lm * Lm / 4.0;
  p.std_x = std::sqrt(c.alpha3 * Lm + c.alpha4 * std::abs(k) * Lm);
  // y = ∫sin θ ≈ ∫θ: deterministic bend plus the integral of a random walk.
  p.mean_y = k * Lm * Lm / 2.0;
  p.std_y = std::sqrt(q * Lm * Lm * Lm / 3.0);
  return p;
}

TEST(Odometry, NoiseFreeReproducesGroundTruthOnCurvedTrajectory) {
  // Forward and backward driving, arcs of varying curvature and turns on the spot.
  const auto command = [](double t) -> core::Twist {
    if (t > 20.0 && t < 23.0) return {0.0, -0.9};  // turn in place
    return {0.8 * std::cos(0.13 * t) + 0.1, 0.6 * std::sin(0.31 * t)};
  };
  const Pose2 X_WR0(3.0, -2.0, 0.7);
  const RunResult r = Drive(NoiseFree(), 1, 50.0, 120.0, command, X_WR0, true);
  EXPECT_LT(r.max_error, 1e-9);
  EXPECT_GT(r.path_length, 50.0);  // it went somewhere
}

TEST(Odometry, StartsAtIdentityAndResets) {
  Odometry odometry(NoiseFree(), core::Rng(3));
  EXPECT_EQ(odometry.pose(), Pose2());
  const Pose2 a(10.0, 5.0, 1.0);
  const Pose2 b = ArcStep(a, 1.0, 0.5, 0.1);
  odometry.Update(a, b);
  const Pose2 expected = a.Inverse() * b;
  EXPECT_NEAR(odometry.pose().x, expected.x, 1e-12);
  EXPECT_NEAR(odometry.pose().y, expected.y, 1e-12);
  EXPECT_NEAR(odometry.pose().theta, expected.theta, 1e-12);
  odometry.Reset();
  EXPECT_EQ(odometry.pose(), Pose2());
  odometry.Reset(Pose2(1.0, 2.0, 0.5));
  EXPECT_EQ(odometry.pose(), Pose2(1.0, 2.0, 0.5));
}

TEST(Odometry, LateralSlipIsNotMeasured) {
  Odometry odometry(NoiseFree(), core::Rng(3));
  const Pose2 a(0.0, 0.0, core::kPi / 2.0);
  const core::OdometryDelta d =
      odometry.Update(a, Pose2(-0.05, 0.1, core::kPi / 2.0));  // 5 cm left
  EXPECT_NEAR(d.distance, 0.1, 1e-12);
  EXPECT_NEAR(d.dtheta, 0.0, 1e-12);
  EXPECT_NEAR(odometry.pose().x, 0.1, 1e-12);
  EXPECT_NEAR(odometry.pose().y, 0.0, 1e-12);
}

TEST(Odometry, StandingStillDoesNotDrift) {
  // The noise variance is proportional to the motion, so rounding-level "motion" of a robot
  // at rest (X_WR^-1 * X_WR is not exactly the identity in floating point) adds noise of
  // standard deviation sqrt(alpha * 1e-16), which stays far below a micrometre.
  Odometry odometry(OdometryConfig{}, core::Rng(5));
  const Pose2 X_WR(1.0, 2.0, 3.0);
  for (int k = 0; k < 50 * 3600; ++k) odometry.Update(X_WR, X_WR);  // one hour at 50 Hz
  EXPECT_LT(std::abs(odometry.pose().x), 1e-6);
  EXPECT_LT(std::abs(odometry.pose().y), 1e-6);
  EXPECT_LT(std::abs(odometry.pose().theta), 1e-6);
  Odometry exact(OdometryConfig{}, core::Rng(5));
  for (int k = 0; k < 1000; ++k) exact.Update(Pose2(), Pose2());
  EXPECT_EQ(exact.pose(), Pose2());
}

TEST(Odometry, SystematicErrorsMatchTheWheelModel) {
  OdometryConfig c = NoiseFree();
  c.scale_error = 0.02;
  c.radius_mismatch = 1e-3;
  // Straight 10 m: measured length and heading drift from the wheels.
  Odometry odometry(c, core::Rng(1));
  double theta = 0.0, dist = 0.0;
  Pose2 X_WR;
  for (int k = 0; k < 1000; ++k) {
    const Pose2 next = ArcStep(X_WR, 1.0, 0.0, 0.01);
    const core::OdometryDelta d = odometry.Update(X_WR, next);
    theta += d.dtheta;
    dist += d.distance;
    X_WR = next;
  }
  EXPECT_NEAR(dist, 1.02 * 10.0, 1e-9);
  EXPECT_NEAR(theta, 1.02 * 1e-3 * 10.0 / c.wheel_base,
              1e-9);  // to the left: right wheel reads long
  // A turn on the spot by pi: heading scaled by the radius error.
  Odometry spin(c, core::Rng(1));
  double spun = 0.0;
  Pose2 X;
  for (int k = 0; k < 100; ++k) {
    const Pose2 next = ArcStep(X, 0.0, core::kPi, 0.01);
    spun += spin.Update(X, next).dtheta;
    X = next;
  }
  EXPECT_NEAR(spun, 1.02 * core::kPi, 1e-9);
}

TEST(Odometry, StraightRunDriftMatchesModelOverSeeds) {
  const OdometryConfig c;  // defaults
  const Ensemble e = StraightRuns(c, 50.0);
  const StraightPrediction p = PredictStraight(c, kStraight);
  const Stats th = Summarize(e.theta), x = Summarize(e.x), y = Summarize(e.y);
  const double n_sqrt = std::sqrt(static_cast<double>(kDriveSeeds));
  // Means within 4 standard errors; standard deviations within 20 % (the standard error of a
  // standard deviation over 200 samples is 5 %).
  EXPECT_NEAR(th.mean, p.mean_theta, 4.0 * p.std_theta / n_sqrt);
  EXPECT_NEAR(x.mean, p.mean_x, 4.0 * p.std_x / n_sqrt);
  EXPECT_NEAR(y.mean, p.mean_y, 4.0 * p.std_y / n_sqrt);
  EXPECT_NEAR(th.std / p.std_theta, 1.0, 0.2);
  EXPECT_NEAR(x.std / p.std_x, 1.0, 0.2);
  EXPECT_NEAR(y.std / p.std_y, 1.0, 0.2);
  std::printf(
      "[ info     ] straight 100 m, %d seeds: heading %.4f ± %.4f rad (predicted %.4f ± %.4f), "
      "x %.3f ± %.3f m (%.3f ± %.3f), y %.3f ± %.3f m (%.3f ± %.3f)\n",
      kDriveSeeds, th.mean, th.std, p.mean_theta, p.std_theta, x.mean, x.std, p.mean_x, p.std_x, y.mean,
      y.std, p.mean_y, p.std_y);
}

TEST(Odometry, DriftDoesNotDependOnTheRate) {
  // The original code's noise shrank as the rate grew; here 50 Hz and 10 Hz must agree, on a
  // straight run (translation noise) and on turns on the spot (rotation noise).
  OdometryConfig c;
  c.alpha2 = 4e-5;  // make the random walk dominate the lateral error
  const Ensemble fast = StraightRuns(c, 50.0);
  const Ensemble slow = StraightRuns(c, 10.0);
  const StraightPrediction p = PredictStraight(c, kStraight);
  for (const Ensemble* e : {&fast, &slow}) {
    EXPECT_NEAR(Summarize(e->theta).std / p.std_theta, 1.0, 0.2);
    EXPECT_NEAR(Summarize(e->y).std / p.std_y, 1.0, 0.2);
    EXPECT_NEAR(Summarize(e->x).std / p.std_x, 1.0, 0.2);
  }
  EXPECT_NEAR(Summarize(fast.theta).std / Summarize(slow.theta).std, 1.0, 0.25);
  EXPECT_NEAR(Summarize(fast.y).std / Summarize(slow.y).std, 1.0, 0.25);
  EXPECT_NEAR(Summarize(fast.x).std / Summarize(slow.x).std, 1.0, 0.25);

  // About ten turns on the spot at 1 rad/s (a whole number of steps at both rates).
  const double turned = 63.0;
  std::vector<double> spin_fast, spin_slow;
  for (int seed = 0; seed < kDriveSeeds; ++seed) {
    const auto spin = [](double) { return core::Twist{0.0, 1.0}; };
    spin_fast.push_back(Drive(c, 5000 + seed, 50.0, turned, spin).theta_unwrapped);
    spin_slow.push_back(Drive(c, 5000 + seed, 10.0, turned, spin).theta_unwrapped);
  }
  const double measured_turn = (1.0 + c.scale_error) * turned;
  const double expected_std = std::sqrt(c.alpha1 * measured_turn);
  const double n_sqrt = std::sqrt(static_cast<double>(kDriveSeeds));
  for (const auto* s : {&spin_fast, &spin_slow}) {
    EXPECT_NEAR(Summarize(*s).mean, measured_turn, 4.0 * expected_std / n_sqrt);
    EXPECT_NEAR(Summarize(*s).std / expected_std, 1.0, 0.2);
  }
}

// RMS over kDriveSeeds runs (seeds first_seed, first_seed + 1, ...) of the odometry's final position
// error (% of `distance`) and heading error (deg).
struct DriftRms {
  double position_percent = 0.0;
  double heading_deg = 0.0;
};
DriftRms RmsDrift(const OdometryConfig& c, std::uint64_t first_seed, double distance,
                  const std::function<core::Twist(double)>& command) {
  double sum_pos2 = 0.0, sum_th2 = 0.0;
  for (int seed = 0; seed < kDriveSeeds; ++seed) {
    const RunResult r =
        Drive(c, first_seed + static_cast<std::uint64_t>(seed), 50.0, distance / kSpeed, command);
    const double e_pos = std::hypot(r.X_OR.x - r.X_OR_true.x, r.X_OR.y - r.X_OR_true.y);
    const double e_th = core::AngleDiff(r.X_OR.theta, r.X_OR_true.theta);
    sum_pos2 += e_pos * e_pos;
    sum_th2 += e_th * e_th;
  }
  return {100.0 * std::sqrt(sum_pos2 / kDriveSeeds) / distance,
          core::RadToDeg(std::sqrt(sum_th2 / kDriveSeeds))};
}

TEST(Odometry, DefaultsDriftLikeARealRobot) {
  // docs/DESIGN.md §4: a few percent of the distance and several degrees of heading per 100 m.
  const OdometryConfig c;
  const DriftRms straight = RmsDrift(c, 1000, kStraight, StraightAhead);
  EXPECT_GT(straight.position_percent, 1.0);
  EXPECT_LT(straight.position_percent, 6.0);
  EXPECT_GT(straight.heading_deg, 2.0);
  EXPECT_LT(straight.heading_deg, 10.0);

  // A 100 m loop: a 25 m square with rounded corners (radius 1 m), driven counter-clockwise.
  const double corner = core::kPi / 2.0 * 1.0;  // arc length of a corner (m)
  const double side = 25.0 - 2.0 * 1.0;
  const double lap = 4.0 * (side + corner);
  const auto loop = [&](double t) -> core::Twist {
    const double s = std::fmod(kSpeed * t, side + corner);
    return s < side ? core::Twist{kSpeed, 0.0} : core::Twist{kSpeed, kSpeed / 1.0};
  };
  const DriftRms looped = RmsDrift(c, 3000, lap, loop);
  EXPECT_GT(looped.position_percent, 0.5);
  EXPECT_LT(looped.position_percent, 6.0);
  EXPECT_GT(looped.heading_deg, 2.0);
  EXPECT_LT(looped.heading_deg, 10.0);
  std::printf(
      "[ info     ] defaults, RMS over %d seeds: straight 100 m: position %.2f %%, heading %.2f "
      "deg; %.0f m square loop: position %.2f %% of the loop, heading %.2f deg\n",
      kDriveSeeds, straight.position_percent, straight.heading_deg, lap, looped.position_percent,
      looped.heading_deg);
}

TEST(Odometry, IsDeterministicPerSeed) {
  const OdometryConfig c;
  const auto command = [](double t) { return core::Twist{0.7, 0.3 * std::sin(0.2 * t)}; };
  const RunResult a = Drive(c, 42, 50.0, 30.0, command);
  const RunResult b = Drive(c, 42, 50.0, 30.0, command);
  const RunResult other = Drive(c, 43, 50.0, 30.0, command);
  EXPECT_EQ(a.X_OR, b.X_OR);
  EXPECT_NE(a.X_OR, other.X_OR);
}

TEST(OdometryConfig, ValidateNamesTheKey) {
  EXPECT_EQ(ValidationErrorKey(OdometryConfig{}), kValid);
  OdometryConfig c;
  c.wheel_base = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "wheel_base");
  c = {};
  c.alpha3 = -1e-3;
  EXPECT_EQ(ValidationErrorKey(c), "alpha3");
  c = {};
  c.alpha1 = std::nan("");
  EXPECT_EQ(ValidationErrorKey(c), "alpha1");
  c = {};
  c.rate_hz = 0.0;
  EXPECT_EQ(ValidationErrorKey(c), "rate_hz");
  c = {};
  c.radius_mismatch = 0.5;
  EXPECT_EQ(ValidationErrorKey(c), "radius_mismatch");
  c = {};
  c.scale_error = -1.0;
  EXPECT_EQ(ValidationErrorKey(c), "scale_error");
  c = {};
  c.wheel_base = -1.0;
  EXPECT_THROW(Odometry(c, core::Rng(1)), core::ConfigError);
}

TEST(OdometryConfig, ReadsFromYamlStrictly) {
  const auto c =
      io::ReadConfig<OdometryConfig>(YAML::Load("alpha2: 2.0e-5\nwheel_base: 0.4"), "test.yaml");
  EXPECT_EQ(c.alpha2, 2.0e-5);
  EXPECT_EQ(c.wheel_base, 0.4);
  EXPECT_EQ(c.alpha1, OdometryConfig{}.alpha1);
  EXPECT_THROW(io::ReadConfig<OdometryConfig>(YAML::Load("alpha5: 1"), "test.yaml"),
               core::ConfigError);
  EXPECT_THROW(io::ReadConfig<OdometryConfig>(YAML::Load("wheel_base: -1"), "test.yaml"),
               core::ConfigError);
}

}  // namespace
}  // namespace retrace::sim
