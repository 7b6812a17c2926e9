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

}  // namespace
}  // namespace retrace::bench
