#include "core/path.hpp"

#include <gtest/gtest.h>

namespace retrace::core {
namespace {

TEST(Path, ArcLengthAndInterpolation) {
  const Path path({{0, 0, 0}, {3, 0, 0}, {3, 4, kPi / 2}});
  EXPECT_DOUBLE_EQ(path.Length(), 7.0);
  EXPECT_DOUBLE_EQ(path.ArcLength(1), 3.0);
  const Pose2 mid = path.AtArcLength(5.0);
  EXPECT_NEAR(mid.x, 3.0, 1e-12);
  EXPECT_NEAR(mid.y, 2.0, 1e-12);
  EXPECT_NEAR(mid.theta, kPi / 4, 1e-12);
  EXPECT_EQ(path.AtArcLength(-1.0), path.front());
  EXPECT_EQ(path.AtArcLength(100.0), path.back());
}

}  // namespace
}  // namespace retrace::core
