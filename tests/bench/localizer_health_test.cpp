#include "bench/metrics/localizer_health.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace retrace::bench {
namespace {

// A robot driving 0.05 m per tick along x whose estimate follows the odometry exactly, except
// for one tick at which it jumps 3 m sideways and the next, at which it comes back.
std::vector<EstimateSample> Track() {
  std::vector<EstimateSample> track;
  for (int k = 0; k < 20; ++k) {
    EstimateSample s;
    s.time = 0.05 * k;
    s.X_OR = core::Pose2(0.05 * k, 0.0, 0.0);
    s.X_MR = core::Pose2(1.0 + 0.05 * k, 2.0, 0.0);  // a constant offset: no jump
    if (k == 7) s.X_MR.y += 3.0;
    s.lost = k >= 10 && k < 14;
    track.push_back(s);
  }
  return track;
}

TEST(LocalizerHealth, FindsAOneTickJumpThatTheOdometryDoesNotExplain) {
  const LocalizerHealth h = ComputeLocalizerHealth(Track(), {});
  EXPECT_NEAR(h.max_jump_m, 3.0, 1e-9);
  EXPECT_NEAR(h.max_jump_time_s, 0.35, 1e-12);  // the tick it jumped away (back is also 3 m)
  EXPECT_NEAR(h.lost_time_s, 0.2, 1e-9);        // four samples lost, each until the next
  EXPECT_EQ(h.lost_spells, 1);
  EXPECT_EQ(h.reacquisitions, 0);
}

TEST(LocalizerHealth, IgnoresTheFrameChangeOfAMapSwitchAndCountsReacquisitions) {
  std::vector<EstimateSample> track = Track();
  track[7].X_MR.y -= 3.0;
  for (std::size_t k = 12; k < track.size(); ++k) {
    track[k].map = 1;
    track[k].X_MR = core::Pose2(-40.0 + 0.05 * static_cast<double>(k), 7.0, 0.0);
  }
  std::vector<LocalizerSample> updates(3);
  updates[1].reacquired = true;
  const LocalizerHealth h = ComputeLocalizerHealth(track, updates);
  EXPECT_LT(h.max_jump_m, 1e-9);
  EXPECT_EQ(h.reacquisitions, 1);
  const LocalizerHealth two[] = {h, ComputeLocalizerHealth(Track(), {})};
  const LocalizerHealth all = CombineLocalizerHealth(two);
  EXPECT_NEAR(all.max_jump_m, 3.0, 1e-9);
  EXPECT_EQ(all.lost_spells, 2);
  EXPECT_EQ(all.reacquisitions, 1);
  EXPECT_NEAR(all.lost_time_s, 0.4, 1e-9);
}

TEST(LocalizerHealth, ErrorIncreaseIsMeasuredInOneAlignment) {
  // The truth moves 0.5 m along x; the estimate, 1 m off, follows it: no increase, however far
  // the later sample's local truth (its alignment) has moved from the earlier one's.
  const core::Pose2 W0(0, 0, 0), W1(0.5, 0, 0);
  const core::Pose2 truth1(20.0, 5.0, 0.3);  // the later sample's local truth, anywhere
  const core::Pose2 truth0 = truth1 * core::Between(W1, W0);
  const core::Pose2 off(0.0, 1.0, 0.0);
  EXPECT_NEAR(ErrorIncrease(truth0 * off, truth1 * off, W0, W1, truth1), 0.0, 1e-12);
  // The estimate jumps 3 m further away: a 3 m increase.
  EXPECT_NEAR(ErrorIncrease(truth0 * off, truth1 * core::Pose2(0.0, 4.0, 0.0), W0, W1, truth1),
              3.0, 1e-12);
}

TEST(LocalizerHealth, ClassifiesReacquisitionsByTheErrorIncreaseThatShowsThem) {
  std::vector<EstimateSample> track = Track();
  track[5].error_increase = -2.0;  // the update at 0.25 s brought it closer
  track[9].error_increase = 4.0;   // the one at 0.43 s, shown at 0.45 s, took it 4 m away
  std::vector<LocalizerSample> updates(3);
  updates[0].time = 0.25;
  updates[0].reacquired = true;
  updates[1].time = 0.43;
  updates[1].reacquired = true;
  updates[2].time = 0.6;  // not a re-acquisition
  track[12].error_increase = 7.0;
  const LocalizerHealth h = ComputeLocalizerHealth(track, updates);
  EXPECT_EQ(h.reacquisitions, 2);
  EXPECT_EQ(h.reacquisitions_closer, 1);
  EXPECT_EQ(h.reacquisitions_wrong, 1);
  EXPECT_NEAR(h.max_error_increase_m, 7.0, 1e-12);
  EXPECT_NEAR(h.max_error_increase_time_s, 0.6, 1e-12);
}

}  // namespace
}  // namespace retrace::bench
