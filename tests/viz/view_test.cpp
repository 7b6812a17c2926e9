#include "viz/view.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace retrace::viz {
namespace {

TEST(View, FitShowsTheWholeBoxCentredWithUniformScale) {
  const Box2 box = Box2::Of(Vec2(10, 20), Vec2(30, 30));  // 20 x 10 m
  const View v = View::Fit(box, 400, 400, 10.0);
  EXPECT_DOUBLE_EQ(v.pixels_per_meter(), 19.0);  // (400 - 20) / 20
  const Vec2 lo = v.ToPixel(box.min);
  const Vec2 hi = v.ToPixel(box.max);
  EXPECT_NEAR(lo.x(), 10.0, 1e-9);
  EXPECT_NEAR(hi.x(), 390.0, 1e-9);
  // y up in the world is up in the image: the box's top has the smaller row.
  EXPECT_LT(hi.y(), lo.y());
  EXPECT_NEAR(0.5 * (lo.y() + hi.y()), 200.0, 1e-9);
}

TEST(View, ToWorldInvertsToPixel) {
  const View v = View::Centered(Vec2(3.0, -2.0), 25.0, 640, 480);
  const Vec2 p(4.5, -7.25);
  const Vec2 back = v.ToWorld(v.ToPixel(p));
  EXPECT_NEAR(back.x(), p.x(), 1e-12);
  EXPECT_NEAR(back.y(), p.y(), 1e-12);
  EXPECT_NEAR(v.ToPixel(Vec2(3.0, -2.0)).x(), 320.0, 1e-12);
}

TEST(View, VisibleBoxCoversTheImage) {
  const View v = View::Centered(Vec2(0, 0), 10.0, 200, 100);
  const Box2 b = v.VisibleBox();
  EXPECT_NEAR(b.min.x(), -10.0, 1e-12);
  EXPECT_NEAR(b.max.y(), 5.0, 1e-12);
}

TEST(View, DegenerateBoxGetsAFiniteScale) {
  Box2 b;
  b.Extend(Vec2(1, 1));
  const View v = View::Fit(b, 100, 100);
  EXPECT_TRUE(std::isfinite(v.pixels_per_meter()));
  EXPECT_NEAR(v.ToPixel(Vec2(1, 1)).x(), 50.0, 1e-9);
}

TEST(Box2, ExtendIgnoresNonFinitePoints) {
  Box2 b;
  b.Extend(Vec2(std::nan(""), 0.0));
  EXPECT_TRUE(b.IsEmpty());
  b.Extend(Vec2(1, 2), 0.5);
  EXPECT_FALSE(b.IsEmpty());
  EXPECT_DOUBLE_EQ(b.min.x(), 0.5);
}

}  // namespace
}  // namespace retrace::viz
