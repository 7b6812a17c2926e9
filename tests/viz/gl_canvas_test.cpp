#include "viz/gl_canvas.hpp"

#include <gtest/gtest.h>

#include "core/occupancy_grid.hpp"
#include "tests/viz/viz_test_data.hpp"
#include "viz/render_error.hpp"

namespace retrace::viz {
namespace {

using testing::ColorNear;

constexpr Rgba kRed{255, 0, 0};
constexpr Rgba kBlue{0, 0, 255};
constexpr Rgba kWhite{255, 255, 255};

// A canvas of 200 x 100 px showing [0, 20] x [0, 10] m at 10 px/m.
GlCanvas MakeCanvas(int supersample = 2) {
  GlCanvas c(200, 100, supersample);
  c.SetView(View::Fit(Box2::Of(Vec2(0, 0), Vec2(20, 10)), 200, 100));
  return c;
}

Rgba At(const Image& img, const View& v, const Vec2& p) {
  const Vec2 q = v.ToPixel(p);
  return img.At(static_cast<int>(q.x()), static_cast<int>(q.y()));
}

TEST(GlCanvas, StartsWithTheBackgroundAndHasTheRequestedSize) {
  GlCanvas c(64, 48, 2, {10, 20, 30});
  const Image img = c.ReadBack();
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.height, 48);
  EXPECT_EQ(img.At(0, 0), (Rgba{10, 20, 30}));
  EXPECT_EQ(img.At(63, 47), (Rgba{10, 20, 30}));
}

TEST(GlCanvas, DiscLandsWhereTheViewPutsItsCentre) {
  GlCanvas c = MakeCanvas();
  c.FillDisc(Vec2(5, 5), 1.0, kRed);
  const Image img = c.ReadBack();
  EXPECT_EQ(At(img, c.view(), Vec2(5, 5)), kRed);
  EXPECT_EQ(At(img, c.view(), Vec2(5.7, 5)), kRed);
  EXPECT_EQ(At(img, c.view(), Vec2(6.5, 5)), kWhite);
  EXPECT_EQ(At(img, c.view(), Vec2(15, 5)), kWhite);
}

TEST(GlCanvas, FillsConcavePolygonsByTheEvenOddRule) {
  GlCanvas c = MakeCanvas();
  // An L: the notch (upper right) must stay empty.
  c.FillPolygon({{2, 2}, {12, 2}, {12, 4}, {4, 4}, {4, 8}, {2, 8}}, kBlue);
  const Image img = c.ReadBack();
  EXPECT_EQ(At(img, c.view(), Vec2(3, 7)), kBlue);
  EXPECT_EQ(At(img, c.view(), Vec2(10, 3)), kBlue);
  EXPECT_EQ(At(img, c.view(), Vec2(8, 6)), kWhite);
  EXPECT_EQ(At(img, c.view(), Vec2(15, 6)), kWhite);
}

TEST(GlCanvas, PolylineCoversItsPointsAtItsWidth) {
  GlCanvas c = MakeCanvas();
  c.DrawPolyline({{1, 1}, {10, 1}, {10, 9}}, 4.0, kRed);
  const Image img = c.ReadBack();
  EXPECT_EQ(At(img, c.view(), Vec2(5, 1)), kRed);
  EXPECT_EQ(At(img, c.view(), Vec2(10, 5)), kRed);
  EXPECT_EQ(At(img, c.view(), Vec2(10, 1)), kRed);    // the corner is joined
  EXPECT_EQ(At(img, c.view(), Vec2(5, 1.5)), kWhite);  // 5 px away: outside the 4 px line
}

TEST(GlCanvas, TranslucentPolylineBlendsEveryPixelOnce) {
  GlCanvas c = MakeCanvas();
  // Crosses itself at (5, 5).
  c.DrawPolyline({{1, 5}, {9, 5}, {9, 9}, {5, 9}, {5, 1}}, 6.0, kRed.WithAlpha(128));
  const Image img = c.ReadBack();
  const Rgba single = At(img, c.view(), Vec2(2, 5));
  EXPECT_TRUE(ColorNear(single, {255, 127, 127}, 3));
  EXPECT_EQ(At(img, c.view(), Vec2(5, 5)), single);
}

TEST(GlCanvas, GridCellsOfATenthMetreStayCrisp) {
  // 40 px/m: a 0.1 m cell is 4 px.
  GlCanvas c(160, 160, 2);
  c.SetView(View::Centered(Vec2(0, 0), 40.0, 160, 160));
  core::OccupancyGrid g(20, 20, 0.1, Vec2(-1, -1));
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) g.SetLogOdds({x, y}, -3.0f);
  }
  g.SetLogOdds({10, 10}, 3.0f);  // covers [0, 0.1) x [0, 0.1)
  c.DrawGrid(g, core::Pose2::Identity());
  const Image img = c.ReadBack();
  EXPECT_EQ(At(img, c.view(), Vec2(0.05, 0.05)), palette::kMapOccupied);
  EXPECT_EQ(At(img, c.view(), Vec2(0.01, 0.09)), palette::kMapOccupied);
  EXPECT_EQ(At(img, c.view(), Vec2(0.15, 0.05)), palette::kMapFree);
  EXPECT_EQ(At(img, c.view(), Vec2(-0.05, 0.05)), palette::kMapFree);
  EXPECT_EQ(At(img, c.view(), Vec2(1.5, 1.5)), palette::kBackground);  // outside the grid
}

TEST(GlCanvas, GridIsPlacedByItsPoseInTheWorld) {
  GlCanvas c = MakeCanvas();
  core::OccupancyGrid g(10, 10, 0.1, Vec2(0, 0));  // 1 x 1 m, all occupied
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) g.SetLogOdds({x, y}, 3.0f);
  }
  // M sits at (15, 5) in W, turned a quarter: the grid covers x in [14, 15], y in [5, 6].
  c.DrawGrid(g, core::Pose2(15, 5, core::kPi / 2));
  const Image img = c.ReadBack();
  EXPECT_EQ(At(img, c.view(), Vec2(14.5, 5.5)), palette::kMapOccupied);
  EXPECT_EQ(At(img, c.view(), Vec2(15.5, 5.5)), palette::kBackground);
}

TEST(GlCanvas, ZoomedOutGridKeepsOneCellWalls) {
  // 100 m of grid at 0.1 m shown at 2 px/m: 20 cells per output pixel.
  GlCanvas c(220, 220, 2);
  c.SetView(View::Centered(Vec2(50, 50), 2.0, 220, 220));
  core::OccupancyGrid g(1000, 1000, 0.1, Vec2(0, 0));
  for (float& l : g.log_odds()) l = -3.0f;
  for (int x = 0; x < 1000; ++x) g.SetLogOdds({x, 503}, 3.0f);  // one cell thick at y = 50.3 m
  c.DrawGrid(g, core::Pose2::Identity());
  const Image img = c.ReadBack();
  for (double x : {10.0, 33.3, 50.0, 71.7, 90.0}) {
    const Vec2 q = c.view().ToPixel(Vec2(x, 50.35));
    int darkest = 255;
    for (int dy = -1; dy <= 1; ++dy) {
      darkest = std::min<int>(darkest, img.At(static_cast<int>(q.x()), static_cast<int>(q.y()) + dy).r);
    }
    EXPECT_LT(darkest, 150) << "wall lost at x = " << x;
  }
  EXPECT_EQ(At(img, c.view(), Vec2(50, 30)), palette::kMapFree);
}

TEST(GlCanvas, InterleavedCanvasesKeepTheirOwnPixels) {
  // OSMesa shares one framebuffer between buffers of the same size: switching must not leak.
  GlCanvas a = MakeCanvas();
  GlCanvas b = MakeCanvas();
  a.FillDisc(Vec2(5, 5), 1.0, kRed);
  b.FillDisc(Vec2(15, 5), 1.0, kBlue);
  a.FillDisc(Vec2(10, 5), 1.0, kRed);
  const Image ia = a.ReadBack();
  const Image ib = b.ReadBack();
  EXPECT_EQ(At(ia, a.view(), Vec2(5, 5)), kRed);
  EXPECT_EQ(At(ia, a.view(), Vec2(10, 5)), kRed);
  EXPECT_EQ(At(ia, a.view(), Vec2(15, 5)), kWhite);
  EXPECT_EQ(At(ib, b.view(), Vec2(15, 5)), kBlue);
  EXPECT_EQ(At(ib, b.view(), Vec2(5, 5)), kWhite);
}

TEST(GlCanvas, MarkersAndArrowsAreCentredOnTheirPoints) {
  GlCanvas c = MakeCanvas();
  c.DrawMarkers({{3, 3}, {7, 3}}, Marker::kSquare, 12.0, kBlue);
  c.DrawMarkers({{11, 3}}, Marker::kDiamond, 12.0, kBlue, 2.0, kRed);
  c.DrawPoseArrows({core::Pose2(15, 3, 0.0)}, 20.0, kRed);
  const Image img = c.ReadBack();
  EXPECT_EQ(At(img, c.view(), Vec2(3, 3)), kBlue);
  EXPECT_EQ(At(img, c.view(), Vec2(7, 3)), kBlue);
  EXPECT_EQ(At(img, c.view(), Vec2(11, 3)), kBlue);
  EXPECT_EQ(At(img, c.view(), Vec2(15.5, 3)), kRed);   // in front of the centre
  EXPECT_EQ(At(img, c.view(), Vec2(15, 4)), kWhite);   // beside it
}

TEST(GlCanvas, SameCallsGiveTheSamePixels) {
  auto draw = [] {
    GlCanvas c = MakeCanvas();
    c.FillPolygon({{1, 1}, {9, 2}, {4, 8}}, kBlue.WithAlpha(100));
    c.DrawPolyline({{0, 0}, {20, 10}, {3, 9}}, 2.5, kRed.WithAlpha(200));
    c.DrawCircle(Vec2(12, 5), 3.0, 1.5, {0, 128, 0});
    return c.ReadBack();
  };
  EXPECT_EQ(draw(), draw());
}

TEST(GlCanvas, RejectsImpossibleSizesWithRenderError) {
  EXPECT_THROW(GlCanvas(0, 10), RenderError);
  EXPECT_THROW(GlCanvas(10, -1), RenderError);
  EXPECT_THROW(GlCanvas(kMaxCanvasSide, 10, 2), RenderError);
  EXPECT_THROW(GlCanvas(10, 10, 9), RenderError);
  try {
    GlCanvas(20000, 10, 1);
    FAIL() << "no exception";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("16384"), std::string::npos) << e.what();
  }
}

TEST(GridCellColor, BlendsThroughUnknownBetweenTheThresholds) {
  EXPECT_EQ(GridCellColor(0.0f), palette::kMapUnknown);
  EXPECT_EQ(GridCellColor(-3.0f), palette::kMapFree);
  EXPECT_EQ(GridCellColor(3.0f), palette::kMapOccupied);
  const Rgba mid = GridCellColor(0.3f);  // p = 0.57
  EXPECT_LT(mid.r, palette::kMapUnknown.r);
  EXPECT_GT(mid.r, palette::kMapOccupied.r);
  GridStyle transparent;
  transparent.unknown_transparent = true;
  EXPECT_EQ(GridCellColor(0.0f, transparent).a, 0);
}

}  // namespace
}  // namespace retrace::viz
