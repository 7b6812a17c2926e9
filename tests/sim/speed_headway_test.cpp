// The speed-headway rule (sim/speed_headway.hpp): which neighbour is the one ahead, and the
// speed the space to it allows.

#include "sim/speed_headway.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

constexpr double kNoHeadway = std::numeric_limits<double>::infinity();

TEST(SpeedHeadway, HeadwayIsTheNearestPersonInTheWalkersPath) {
  const SocialAgent self{{0.0, 0.0}, {1.0, 0.0}, 0.2};
  const Vec2 e(1.0, 0.0);
  const std::vector<SocialAgent> others = {
      {{2.0, 0.1}, {1.0, 0.0}, 0.2, e},          // ahead, in the path: 2.0025 m
      {{1.0, 0.5}, {1.0, 0.0}, 0.2, e},          // beside the path (0.5 > 0.4)
      {{-0.8, 0.0}, {1.0, 0.0}, 0.2, e},         // behind
      {{1.5, 0.0}, {-1.0, 0.0}, 0.2, Vec2(-e)},  // in the path but facing us: avoided
  };
  EXPECT_NEAR(Headway(self, e, others), std::hypot(2.0, 0.1), 1e-12);
  // Someone standing in the path (no heading) counts; so does a robot, whichever way it faces.
  const std::vector<SocialAgent> standing = {{{1.2, -0.3}, {0.0, 0.0}, 0.2}};
  EXPECT_NEAR(Headway(self, e, standing), std::hypot(1.2, 0.3), 1e-12);
  const SocialAgent robot{{1.0, 0.2}, {-0.5, 0.0}, 0.3, Vec2(-e)};
  EXPECT_NEAR(Headway(self, e, others, &robot), std::hypot(1.0, 0.2), 1e-12);
  EXPECT_EQ(Headway(self, e, std::vector<SocialAgent>{}), kNoHeadway);
  EXPECT_EQ(Headway(self, Vec2::Zero(), others), kNoHeadway);
}

TEST(SpeedHeadway, SpeedIsLinearInTheHeadwayUpToTheFreeSpeed) {
  SpeedHeadwayConfig c;
  c.length = 0.4;
  c.time_gap = 0.5;
  EXPECT_DOUBLE_EQ(HeadwaySpeed(0.3, 1.3, c), 0.0);  // closer than l: stands
  EXPECT_NEAR(HeadwaySpeed(0.6, 1.3, c), 0.4, 1e-12);
  EXPECT_NEAR(HeadwaySpeed(0.8, 1.3, c), 0.8, 1e-12);
  EXPECT_DOUBLE_EQ(HeadwaySpeed(3.0, 1.3, c), 1.3);  // free
  EXPECT_DOUBLE_EQ(HeadwaySpeed(kNoHeadway, 1.3, c), 1.3);
  c.enabled = false;
  EXPECT_DOUBLE_EQ(HeadwaySpeed(0.3, 1.3, c), 1.3);
}

TEST(SpeedHeadway, ValidateNamesTheKey) {
  EXPECT_EQ(ValidationErrorKey(SpeedHeadwayConfig{}), retrace::testing::kValid);
  EXPECT_EQ(ValidationErrorKey<SpeedHeadwayConfig>([](auto& c) { c.length = -0.1; }), "length");
  EXPECT_EQ(ValidationErrorKey<SpeedHeadwayConfig>([](auto& c) { c.time_gap = 0.0; }), "time_gap");
}

}  // namespace
}  // namespace retrace::sim
