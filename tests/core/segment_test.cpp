#include "core/segment.hpp"

#include <gtest/gtest.h>

namespace retrace::core {
namespace {

TEST(Segment, ClosestPointIsTheFootOfThePerpendicularOrAnEnd) {
  const Vec2 a(1.0, 1.0), b(5.0, 1.0);
  EXPECT_EQ(ClosestPointOnSegment(Vec2(3.0, 4.0), a, b), Vec2(3.0, 1.0));  // inside
  EXPECT_EQ(ClosestPointOnSegment(Vec2(-2.0, 0.0), a, b), a);             // before a
  EXPECT_EQ(ClosestPointOnSegment(Vec2(9.0, -3.0), a, b), b);             // past b
  EXPECT_DOUBLE_EQ(SegmentDistance(Vec2(3.0, 4.0), a, b), 3.0);
  EXPECT_DOUBLE_EQ(SegmentDistance(Vec2(9.0, -2.0), a, b), 5.0);  // 4, 3 from b
  EXPECT_DOUBLE_EQ(SegmentDistanceSquared(Vec2(9.0, -2.0), a, b), 25.0);
  // A slanted segment: the foot of the perpendicular from (0, 2) onto y = x is (1, 1).
  EXPECT_NEAR(SegmentDistance(Vec2(0.0, 2.0), Vec2(0.0, 0.0), Vec2(4.0, 4.0)), std::sqrt(2.0),
              1e-15);
}

TEST(Segment, AZeroLengthSegmentIsItsPoint) {
  const Vec2 a(2.0, -1.0);
  EXPECT_EQ(ClosestPointOnSegment(Vec2(5.0, 3.0), a, a), a);
  EXPECT_DOUBLE_EQ(SegmentDistance(Vec2(5.0, 3.0), a, a), 5.0);
}

}  // namespace
}  // namespace retrace::core
