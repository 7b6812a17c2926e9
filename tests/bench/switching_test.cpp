// The switching metric: maps that hold a place twice and the fewest maps a drive needs, judged
// on the drive's ground truth.

#include "bench/metrics/switching.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/angle.hpp"

namespace retrace::bench {
namespace {

// Two laps of a 20 m × 10 m rectangle (60 m each), ticks every 0.05 m, cut into maps after the
// given distances driven.
TeachTrace TwoLaps(const std::vector<double>& cuts) {
  const std::vector<core::Vec2> corners{{0, 0}, {20, 0}, {20, 10}, {0, 10}, {0, 0}};
  TeachTrace trace;
  trace.maps.resize(1);
  std::size_t next_cut = 0;
  double d = 0.0;
  for (int lap = 0; lap < 2; ++lap) {
    for (std::size_t c = 0; c + 1 < corners.size(); ++c) {
      const core::Vec2 a = corners[c], b = corners[c + 1];
      const double len = (b - a).norm();
      for (double u = 0.0; u < len; u += 0.05, d += 0.05) {
        if (next_cut < cuts.size() && d >= cuts[next_cut]) {
          trace.maps.emplace_back();
          ++next_cut;
        }
        const core::Vec2 p = a + (b - a) * (u / len);
        trace.maps.back().X_WR.emplace_back(p.x(), p.y(), 0.0);
      }
    }
  }
  return trace;
}

TEST(Switching, OneMapOverTwoLapsHoldsItsPlacesTwice) {
  const SwitchingQuality q = EvaluateSwitching(TwoLaps({}), 3.0);
  EXPECT_EQ(q.maps, 1);
  EXPECT_EQ(q.revisiting, 1);
  ASSERT_EQ(q.warnings.size(), 1u);
  EXPECT_EQ(q.minimum, 3);  // each map a little under one lap
  EXPECT_TRUE(q.switch_travel_m.empty());
}

TEST(Switching, CutsBeforeEachLapClosesHoldEveryPlaceOnce) {
  const SwitchingQuality q = EvaluateSwitching(TwoLaps({55.0, 110.0}), 3.0);
  EXPECT_EQ(q.maps, 3);
  EXPECT_EQ(q.minimum, 3);
  EXPECT_EQ(q.revisiting, 0);
  ASSERT_EQ(q.switch_travel_m.size(), 2u);
  EXPECT_NEAR(q.switch_travel_m[0], 55.0, 0.3);
  EXPECT_NEAR(q.switch_travel_m[1], 110.0, 0.3);
}

TEST(Switching, ACutTooLateLeavesOneMapHoldingAPlaceTwice) {
  // Map 0 runs 1 m past where the lap closes (the start lies within 3 m of 60 m).
  const SwitchingQuality q = EvaluateSwitching(TwoLaps({61.0, 115.0}), 3.0);
  EXPECT_EQ(q.maps, 3);
  EXPECT_EQ(q.revisiting, 1);
  EXPECT_NE(q.warnings.at(0).find("partial map 0"), std::string::npos);
}

TEST(Switching, EachSwitchSaysWhy) {
  const SwitchingQuality q =
      EvaluateSwitching(TwoLaps({40.0, 55.0, 110.0}), 3.0, {"drift_budget", "revisit", "revisit"});
  ASSERT_EQ(q.reasons.size(), q.switch_travel_m.size());
  EXPECT_EQ(q.reasons, (std::vector<std::string>{"drift_budget", "revisit", "revisit"}));
  EXPECT_EQ(q.reason_counts.drift_budget, 1);
  EXPECT_EQ(q.reason_counts.revisit, 2);
  EXPECT_EQ(q.reason_counts.operator_points + q.reason_counts.auto_points, 0);
  // Without reasons (a teach folder read back), none are made up.
  EXPECT_TRUE(EvaluateSwitching(TwoLaps({55.0, 110.0}), 3.0).reasons.empty());
}

TEST(Switching, ReasonsComeFromTheRecorderOnlineAndFromTheRouteOtherwise) {
  ModeTeach teach;
  teach.mode = MapMode::kPartial;
  teach.bundle.maps.resize(3);
  teach.online_switches = {{100.0, 20.0, nav::SwitchReason::kDriftBudget},
                           {150.0, 30.0, nav::SwitchReason::kRevisit}};
  RouteConfig route;
  route.switch_points.word = SwitchPlanning::kOnline;
  EXPECT_EQ(SwitchReasons(teach, route), (std::vector<std::string>{"drift_budget", "revisit"}));
  route.switch_points.word = SwitchPlanning::kAuto;
  EXPECT_EQ(SwitchReasons(teach, route), (std::vector<std::string>{"auto", "auto"}));
  route.switch_points.word.reset();
  route.switch_points.value = {100.0, 150.0};
  EXPECT_EQ(SwitchReasons(teach, route), (std::vector<std::string>{"operator", "operator"}));
  teach.mode = MapMode::kSingle;
  EXPECT_TRUE(SwitchReasons(teach, route).empty());
}

}  // namespace
}  // namespace retrace::bench
