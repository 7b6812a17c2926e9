// The localizer on long drives in the furnished room: convergence, dynamic scan point rejection
// with walkers blocking the beams, recovery after a kidnapping (integration: seconds each).
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
#include "nav/localizer.hpp"
#include "tests/nav/localizer_room.hpp"
#include "tests/support/config_key.hpp"

namespace retrace::nav {
namespace {

using namespace testing_room;

TEST(Localizer, ConvergesInRoomFromHalfMetreTenDegreesWithinTenUpdates) {
  int converged = 0;
  double worst = 0.0, sum = 0.0, worst_heading = 0.0;
  const int kSeeds = 20;
  for (int seed = 0; seed < kSeeds; ++seed) {
    Drive drive(static_cast<std::uint64_t>(seed));
    Localizer loc(TestConfig(), TestRobot(),
                  core::Rng(static_cast<std::uint64_t>(seed)).Split("localizer"));
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

// The ten drives with walkers blocking about a third of the beams, localized with `config`.
struct RejectionScore {
  std::vector<double> errors;  // m, mean position error per drive
  int tp = 0, fp = 0, fn = 0, tested = 0;
  double mean_error() const {
    double sum = 0.0;
    for (const double e : errors) sum += e;
    return sum / static_cast<double>(errors.size());
  }
  double precision() const { return tp / static_cast<double>(tp + fp); }
  double recall() const { return tp / static_cast<double>(tp + fn); }
};

RejectionScore ScoreRejection(const LocalizerConfig& config) {
  const int kSeeds = 10;
  RejectionScore score;
  for (int seed = 0; seed < kSeeds; ++seed) {
    Drive drive(static_cast<std::uint64_t>(100 + seed));
    Localizer loc(config, TestRobot(),
                  core::Rng(static_cast<std::uint64_t>(seed)).Split("localizer"));
    loc.SetMap(drive.map);
    loc.Initialize(drive.X_WR, 0.05, 0.02);
    const RunResult r = DriveAndLocalize(loc, drive, 60, true, 5);
    score.errors.push_back(r.mean_position_error);
    score.tp += r.tp;
    score.fp += r.fp;
    score.fn += r.fn;
    score.tested += r.tested;
  }
  return score;
}

TEST(Localizer, RejectionKeepsErrorLowWithThirtyPercentOfBeamsBlocked) {
  LocalizerConfig off = TestConfig();
  off.rejection.enabled = false;
  const RejectionScore on_score = ScoreRejection(TestConfig());
  const RejectionScore off_score = ScoreRejection(off);
  int worse = 0;
  for (std::size_t k = 0; k < on_score.errors.size(); ++k) {
    worse += off_score.errors[k] > on_score.errors[k] ? 1 : 0;
  }
  const double mean_on = on_score.mean_error(), mean_off = off_score.mean_error();
  std::printf(
      "[ report ] 30 %% beams blocked: mean position error rejection ON %.3f m, OFF %.3f m "
      "(OFF worse on %d/%zu seeds); %.1f %% of tested beams blocked; mask precision %.3f recall "
      "%.3f (tp %d fp %d fn %d)\n",
      mean_on, mean_off, worse, on_score.errors.size(),
      100.0 * (on_score.tp + on_score.fn) / on_score.tested, on_score.precision(),
      on_score.recall(), on_score.tp, on_score.fp, on_score.fn);
  EXPECT_LT(mean_on, 0.1);
  EXPECT_GT(mean_off, 1.5 * mean_on);
  EXPECT_GE(worse, 8);
  EXPECT_GT(on_score.precision(), 0.9);
  EXPECT_GT(on_score.recall(), 0.5);
}

TEST(Localizer, RejectionOnAStratifiedSampleMatchesAllParticlesInTheRoom) {
  ASSERT_EQ(TestConfig().rejection.particles, 0);  // the default: all particles
  const auto with_sample = [](int sample) {
    LocalizerConfig config = TestConfig();
    config.rejection.particles = sample;
    return ScoreRejection(config);
  };
  const RejectionScore full = ScoreRejection(TestConfig());
  const RejectionScore sampled = with_sample(100);
  const RejectionScore few = with_sample(10);
  std::printf(
      "[ report ] eq. (9) over all %d particles: error %.4f m, precision %.3f, recall %.3f; over "
      "100: %.4f m, %.3f, %.3f; over 10: %.4f m, %.3f, %.3f\n",
      TestConfig().particles, full.mean_error(), full.precision(), full.recall(),
      sampled.mean_error(), sampled.precision(), sampled.recall(), few.mean_error(),
      few.precision(), few.recall());
  EXPECT_NEAR(sampled.recall(), full.recall(), 0.02);
  EXPECT_NEAR(sampled.precision(), full.precision(), 0.02);
  EXPECT_NEAR(sampled.mean_error(), full.mean_error(), 0.01);
}

TEST(Localizer, RecoveryTrialFindsAKidnappedRobotAgain) {
  const int kSeeds = 10;
  int recovered = 0, reacquired_any = 0, ok_without = 0;
  double sum_err = 0.0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    for (const bool augmented : {true, false}) {
      LocalizerConfig config = TestConfig();
      config.augmented.enabled = augmented;
      Drive drive(static_cast<std::uint64_t>(200 + seed));
      Localizer loc(config, TestRobot(),
                    core::Rng(static_cast<std::uint64_t>(seed)).Split("localizer"));
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
        reacquired_any += r.reacquisitions > 0 ? 1 : 0;
        sum_err += r.final_position_error;
      } else {
        ok_without += ok ? 1 : 0;
      }
    }
  }
  std::printf(
      "[ report ] kidnapping by 1.5 m and 20 deg: augmented MCL recovered on %d/%d seeds (mean "
      "final "
      "error %.3f m), a trial won on %d/%d; without recovery recovered on %d/%d\n",
      recovered, kSeeds, sum_err / kSeeds, reacquired_any, kSeeds, ok_without, kSeeds);
  EXPECT_GE(reacquired_any, 8);
  EXPECT_GE(recovered, 8);
  EXPECT_GT(recovered, ok_without);
}

// The poses of the test drive's circle (radius 2.5 m round (6, 4.5), counter-clockwise) every
// 0.1 m: the taught path a recovery trial draws its hypotheses around.
std::vector<Pose2> CirclePath() {
  std::vector<Pose2> out;
  for (double s = 0.0; s < 2.0 * core::kPi * 2.5; s += 0.1) {
    const double a = s / 2.5 - 0.5 * core::kPi;
    out.emplace_back(6.0 + 2.5 * std::cos(a), 4.5 + 2.5 * std::sin(a), a + 0.5 * core::kPi);
  }
  return out;
}

TEST(Localizer, RecoverySearchesOnlyAsFarAsTheDistanceDrivenWhileLostCanExplain) {
  // The robot is carried 3 m along the taught circle unseen (2.8 m from the estimate), then
  // drives 12 m (60 updates). With a reach of 1 m that does not grow, no trial looks that far
  // and none wins: the localizer abstains. When the reach grows by 0.5 m per metre driven while
  // lost, the robot is found.
  const auto run = [](double reach_per_metre, std::uint64_t seed) {
    LocalizerConfig config = TestConfig();
    config.augmented.path_reach = 1.0;
    config.augmented.reach_per_metre = reach_per_metre;
    config.augmented.near_sigma_xy = 0.2;
    config.augmented.path_sigma_xy = 0.2;
    Drive drive(300 + seed);
    Localizer loc(config, TestRobot(), core::Rng(seed).Split("localizer"));
    loc.SetMap(drive.map);
    loc.SetRecoveryPoses(CirclePath());
    loc.Initialize(drive.X_WR, 0.05, 0.02);
    DriveAndLocalize(loc, drive, 15, false);
    drive.X_WR = core::IntegrateOdometry(drive.X_WR, {3.0, 3.0 / 2.5});
    return DriveAndLocalize(loc, drive, 60, false);
  };
  int found_fixed = 0, found_growing = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const RunResult fixed = run(0.0, seed);
    const RunResult growing = run(0.5, seed);
    EXPECT_EQ(fixed.reacquisitions, 0) << "seed " << seed;
    EXPECT_GT(fixed.final_position_error, 1.0) << "seed " << seed;
    found_fixed += fixed.final_position_error < 0.2 ? 1 : 0;
    found_growing += growing.final_position_error < 0.2 ? 1 : 0;
  }
  std::printf(
      "[ report ] carried 3 m along the path: found on %d/3 seeds with a fixed 1 m reach, "
      "%d/3 with 0.5 m more per metre driven while lost\n",
      found_fixed, found_growing);
  EXPECT_GE(found_growing, 2);
}

}  // namespace
}  // namespace retrace::nav
