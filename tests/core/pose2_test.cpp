#include "core/pose2.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angle.hpp"
#include "core/rng.hpp"

namespace retrace::core {
namespace {

void ExpectPoseNear(const Pose2& a, const Pose2& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(AngleDiff(a.theta, b.theta), 0.0, tol);
}

TEST(WrapAngle, MapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapAngle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(WrapAngle(kPi), -kPi);
  EXPECT_DOUBLE_EQ(WrapAngle(-kPi), -kPi);
  EXPECT_NEAR(WrapAngle(3.0 * kPi / 2.0), -kPi / 2.0, 1e-15);
  EXPECT_NEAR(WrapAngle(-7.0 * kPi / 2.0), kPi / 2.0, 1e-14);
  EXPECT_NEAR(WrapAngle(1001.0 * 2.0 * kPi + 0.25), 0.25, 1e-9);
  EXPECT_NEAR(AngleDiff(-3.1, 3.1), 2.0 * kPi - 6.2, 1e-12);
}

TEST(Pose2, ComposeMatchesHandComputedExample) {
  const Pose2 X_AB(1.0, 2.0, kPi / 2.0);
  const Pose2 X_BC(3.0, 0.0, kPi / 2.0);
  ExpectPoseNear(X_AB * X_BC, Pose2(1.0, 5.0, kPi));
  const Vec2 p = X_AB * Vec2(1.0, 1.0);
  EXPECT_NEAR(p.x(), 0.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
}

TEST(Pose2, InverseComposesToIdentityAndIsAssociative) {
  Rng rng(7);
  for (int i = 0; i < 1000; ++i) {
    const Pose2 a(rng.Uniform(-50, 50), rng.Uniform(-50, 50), rng.Uniform(-4, 4));
    const Pose2 b(rng.Uniform(-50, 50), rng.Uniform(-50, 50), rng.Uniform(-4, 4));
    const Pose2 c(rng.Uniform(-50, 50), rng.Uniform(-50, 50), rng.Uniform(-4, 4));
    ExpectPoseNear(a * a.Inverse(), Pose2::Identity(), 1e-12);
    ExpectPoseNear(a.Inverse() * a, Pose2::Identity(), 1e-12);
    ExpectPoseNear((a * b) * c, a * (b * c), 1e-10);
    ExpectPoseNear((a * b).Inverse(), b.Inverse() * a.Inverse(), 1e-10);
    ExpectPoseNear(a * Between(a, b), b, 1e-10);
    EXPECT_GE(a.theta, -kPi);
    EXPECT_LT(a.theta, kPi);
  }
}

TEST(Pose2, InterpolateTakesShortestArc) {
  const Pose2 a(0.0, 0.0, kPi - 0.1);
  const Pose2 b(2.0, 4.0, -kPi + 0.1);
  ExpectPoseNear(Interpolate(a, b, 0.0), a);
  ExpectPoseNear(Interpolate(a, b, 1.0), b);
  ExpectPoseNear(Interpolate(a, b, 0.5), Pose2(1.0, 2.0, -kPi));
}

}  // namespace
}  // namespace retrace::core
