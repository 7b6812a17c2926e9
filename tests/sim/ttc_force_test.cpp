// The time-to-collision power law (sim/ttc_force.hpp): the time to collision of two discs, the
// energy, the analytic gradient against a numerical one, what anticipation does (someone on a
// collision course is avoided sideways, someone walking alongside or away is not) and the
// driving term.

#include "sim/ttc_force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/support/config_key.hpp"

namespace retrace::sim {
namespace {

using retrace::testing::ValidationErrorKey;

const TtcForceConfig kTtc;
constexpr double kNever = std::numeric_limits<double>::infinity();

TEST(TtcForce, TimeToCollisionOfTwoDiscs) {
  // 4 m apart, closing at 2 m/s, radius sum 0.4 m: they touch after 3.6 m, 1.8 s.
  EXPECT_NEAR(DiscTimeToCollision({-4.0, 0.0}, {2.0, 0.0}, 0.4), 1.8, 1e-12);
  // Offset sideways by 0.3 m: |x + v t| = 0.4 when (2t - 4)² = 0.16 - 0.09.
  EXPECT_NEAR(DiscTimeToCollision({-4.0, 0.3}, {2.0, 0.0}, 0.4), (4.0 - std::sqrt(0.07)) / 2.0,
              1e-12);
  EXPECT_EQ(DiscTimeToCollision({-4.0, 0.5}, {2.0, 0.0}, 0.4), kNever);   // passes by
  EXPECT_EQ(DiscTimeToCollision({-4.0, 0.0}, {-2.0, 0.0}, 0.4), kNever);  // moving apart
  EXPECT_EQ(DiscTimeToCollision({-4.0, 0.0}, {0.0, 0.0}, 0.4), kNever);   // same velocity
  EXPECT_EQ(DiscTimeToCollision({-0.3, 0.0}, {2.0, 0.0}, 0.4), 0.0);      // overlapping
}

TEST(TtcForce, EnergyIsThePowerLawWithAnExponentialCutoff) {
  EXPECT_NEAR(TtcEnergy(1.0, kTtc), 1.5 * std::exp(-1.0 / 3.0), 1e-12);
  EXPECT_NEAR(TtcEnergy(2.0, kTtc), 1.5 / 4.0 * std::exp(-2.0 / 3.0), 1e-12);
  EXPECT_EQ(TtcEnergy(kNever, kTtc), 0.0);
  EXPECT_GT(TtcEnergy(0.5, kTtc), TtcEnergy(1.0, kTtc));
}

// -grad_x E(tau(x)) by central differences, x = x_self - x_other.
Vec2 NumericalForce(const SocialAgent& self, const SocialAgent& other) {
  const double h = 1e-6;
  Vec2 grad;
  for (int k = 0; k < 2; ++k) {
    SocialAgent plus = self;
    SocialAgent minus = self;
    plus.position[k] += h;
    minus.position[k] -= h;
    const double r = self.radius + other.radius;
    const double e_plus = TtcEnergy(
        DiscTimeToCollision(plus.position - other.position, self.velocity - other.velocity, r),
        kTtc);
    const double e_minus = TtcEnergy(
        DiscTimeToCollision(minus.position - other.position, self.velocity - other.velocity, r),
        kTtc);
    grad[k] = (e_plus - e_minus) / (2.0 * h);
  }
  return -grad;
}

TEST(TtcForce, AnalyticGradientMatchesNumericalOne) {
  TtcForceConfig uncapped;
  uncapped.max_pair_acceleration = 1e9;
  const SocialAgent self{{0.0, 0.0}, {1.3, 0.0}, 0.2};
  // Each neighbour on a collision course with self (lateral miss distance below 0.4 m).
  for (const Vec2& p : {Vec2(4.0, 0.2), Vec2(3.0, -0.3), Vec2(2.0, 0.1), Vec2(4.5, 0.2)}) {
    for (const Vec2& v : {Vec2(-1.2, 0.0), Vec2(0.0, 0.0), Vec2(-0.5, 0.05)}) {
      const SocialAgent other{p, v, 0.2};
      const Vec2 analytic = TtcRepulsion(self, other, uncapped);
      const Vec2 numerical = NumericalForce(self, other);
      ASSERT_GT(numerical.norm(), 0.0) << p.transpose() << " / " << v.transpose();
      EXPECT_NEAR((analytic - numerical).norm() / numerical.norm(), 0.0, 1e-5)
          << p.transpose() << " / " << v.transpose();
    }
  }
}

TEST(TtcForce, SomeoneOnACollisionCourseIsAvoidedSidewaysAndBrakedFor) {
  // Walking +x; someone comes the other way, slightly to the left (+y).
  const SocialAgent self{{0.0, 0.0}, {1.3, 0.0}, 0.2};
  const SocialAgent other{{4.0, 0.1}, {-1.3, 0.0}, 0.2};
  const Vec2 f = TtcRepulsion(self, other, kTtc);
  EXPECT_LT(f.y(), 0.0);  // steps to the right, away from the other's side
  EXPECT_LT(f.x(), 0.0);  // and slows down
  // The closer in time, the stronger.
  const SocialAgent nearer{{2.0, 0.1}, {-1.3, 0.0}, 0.2};
  EXPECT_GT(TtcRepulsion(self, nearer, kTtc).norm(), f.norm());
  // Equal and opposite for the other.
  EXPECT_TRUE(TtcRepulsion(other, self, kTtc).isApprox(-f, 1e-12));
}

TEST(TtcForce, NoForceWithoutACollisionCourse) {
  const SocialAgent self{{0.0, 0.0}, {1.3, 0.0}, 0.2};
  // Walking alongside, ahead at the same speed, walking away, or passing wide.
  EXPECT_EQ(TtcRepulsion(self, {{0.0, 0.6}, {1.3, 0.0}, 0.2}, kTtc), Vec2::Zero());
  EXPECT_EQ(TtcRepulsion(self, {{1.0, 0.0}, {1.3, 0.0}, 0.2}, kTtc), Vec2::Zero());
  EXPECT_EQ(TtcRepulsion(self, {{1.0, 0.0}, {1.5, 0.0}, 0.2}, kTtc), Vec2::Zero());
  EXPECT_EQ(TtcRepulsion(self, {{3.0, 1.0}, {-1.3, 0.0}, 0.2}, kTtc), Vec2::Zero());
  // Beyond the range.
  EXPECT_EQ(TtcRepulsion(self, {{5.5, 0.0}, {-1.3, 0.0}, 0.2}, kTtc), Vec2::Zero());
}

TEST(TtcForce, OverlappingDiscsGetAFiniteCappedPush) {
  const SocialAgent self{{0.0, 0.0}, {1.0, 0.0}, 0.2};
  const SocialAgent other{{0.35, 0.01}, {0.0, 0.0}, 0.2};
  const Vec2 f = TtcRepulsion(self, other, kTtc);
  EXPECT_TRUE(f.allFinite());
  EXPECT_LE(f.norm(), kTtc.max_pair_acceleration + 1e-12);
  EXPECT_LT(f.x(), 0.0);
}

TEST(TtcForce, DrivingTermRelaxesToThePreferredVelocity) {
  const Vec2 e(0.6, 0.8);
  EXPECT_TRUE(TtcDrivingForce(Vec2::Zero(), e, kTtc).isApprox(e / 0.54));
  EXPECT_NEAR(TtcDrivingForce(1.2 * e, 1.2 * e, kTtc).norm(), 0.0, 1e-12);
}

TEST(TtcForce, TotalIsCappedAndSumsNeighbours) {
  SocialForceConfig social;
  const SocialAgent others[] = {{{2.0, 0.05}, {-1.3, 0.0}, 0.2}, {{3.0, -0.1}, {-1.3, 0.0}, 0.2}};
  SocialForceInputs in;
  in.self = {{0.0, 0.0}, {1.3, 0.0}, 0.2};
  in.direction = {1.0, 0.0};
  in.others = others;
  const Vec2 expected = TtcDrivingForce(in.self.velocity, 1.3 * in.direction, kTtc) +
                        TtcRepulsion(in.self, others[0], kTtc) +
                        TtcRepulsion(in.self, others[1], kTtc);
  const Vec2 total = TtcForce(in, 1.3 * in.direction, kTtc, social);
  if (expected.norm() <= social.max_acceleration) {
    EXPECT_TRUE(total.isApprox(expected, 1e-12));
  } else {
    EXPECT_NEAR(total.norm(), social.max_acceleration, 1e-9);
    EXPECT_TRUE(total.normalized().isApprox(expected.normalized(), 1e-12));
  }
}

TEST(TtcForce, ValidateNamesTheKey) {
  EXPECT_EQ(ValidationErrorKey(kTtc), retrace::testing::kValid);
  EXPECT_EQ(ValidationErrorKey<TtcForceConfig>([](auto& c) { c.strength = -1.0; }), "strength");
  EXPECT_EQ(ValidationErrorKey<TtcForceConfig>([](auto& c) { c.time_horizon = 0.0; }),
            "time_horizon");
  EXPECT_EQ(ValidationErrorKey<TtcForceConfig>([](auto& c) { c.relaxation_time = 0.0; }),
            "relaxation_time");
  EXPECT_EQ(ValidationErrorKey<TtcForceConfig>([](auto& c) { c.range = 0.0; }), "range");
  EXPECT_EQ(ValidationErrorKey<TtcForceConfig>([](auto& c) { c.max_pair_acceleration = 0.0; }),
            "max_pair_acceleration");
}

}  // namespace
}  // namespace retrace::sim
