// sweep.png on small synthetic sweeps: points and bars land at the pixels of their values on
// log, linear and categorical axes, series get their colours, many series are pooled, random
// samples become a scatter, NaN values are left out, and bad data write nothing.

#include "viz/sweep_figure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/viz/viz_test_data.hpp"
#include "viz/image.hpp"
#include "viz/style.hpp"

namespace retrace::viz {
namespace {

using testing::ColorNear;
using testing::DistinctColors;
using testing::PixelAt;

class SweepFigureTest : public retrace::testing::TempDirTest {
 protected:
  std::string Bytes(const FigureInfo& info) { return tmp_.Read(info.path); }
};

const std::string kParticles = "nav.localizer.particles";
const std::string kRejection = "nav.dynamic_rejection.enabled";
const std::string kTracking = "tracking_error_m.pooled.rms";
const std::string kSuccess = "success_rate";

// Tracking error of the grid sweep: falls with the particle count, lower with rejection;
// repeats at mean - 0.05, mean, mean + 0.05.
double TrackingMean(int particles, bool rejection) {
  return (rejection ? 0.1 : 0.3) + 30.0 / particles;
}

// particles {100, 300, 1000} x rejection {false, true} x 3 repeats.
SweepFigureData GridSweep() {
  SweepFigureData d;
  d.parameters = {kParticles, kRejection};
  d.metrics = {kTracking, kSuccess};
  for (int particles : {100, 300, 1000}) {
    for (bool rejection : {false, true}) {
      SweepCombination c;
      c.values = {std::to_string(particles), rejection ? "true" : "false"};
      const double mean = TrackingMean(particles, rejection);
      c.metrics = {{mean - 0.05, mean, mean + 0.05}, {1.0, 1.0, rejection ? 1.0 : 0.0}};
      d.combinations.push_back(c);
    }
  }
  return d;
}

// Whether a pixel of `color` lies within `reach` px left or right of the panel point p (series
// at one x sit a few pixels apart).
::testing::AssertionResult ColorAround(const Image& img, const PanelInfo& panel, const Vec2& p,
                                       Rgba color, int reach = 12, int tol = 40) {
  const Vec2 q = panel.ToFigurePixel(p);
  const int y = static_cast<int>(std::floor(q.y()));
  for (int dx = -reach; dx <= reach; ++dx) {
    const int x = static_cast<int>(std::floor(q.x())) + dx;
    if (x >= 0 && x < img.width && testing::Near(img.At(x, y), color, tol))
      return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << "no pixel near (" << q.x() << ", " << q.y() << ") has the colour";
}

// Whether dark text pixels lie just above the bottom of the panel around frame x.
bool TextNear(const Image& img, const PanelInfo& panel, double x) {
  const Vec2 q = panel.ToFigurePixel(Vec2(x, panel.box.min.y()));
  for (int dy = 4; dy <= 26; ++dy) {
    for (int dx = -30; dx <= 30; ++dx) {
      if (testing::Near(img.At(static_cast<int>(q.x()) + dx, static_cast<int>(q.y()) - dy),
                        palette::kText, 60)) {
        return true;
      }
    }
  }
  return false;
}

Image CheckFile(const FigureInfo& info, int width) {
  EXPECT_TRUE(std::filesystem::exists(info.path));
  const Image img = ReadPng(info.path);
  EXPECT_EQ(img.width, width);
  EXPECT_EQ(img.width, info.width);
  EXPECT_EQ(img.height, info.height);
  EXPECT_GT(img.height, 400);
  EXPECT_GT(DistinctColors(img), 20u);
  return img;
}

TEST_F(SweepFigureTest, GridSweepHasOnePanelPerMetricAndParameter) {
  const FigureInfo info = RenderSweepFigure(GridSweep(), tmp_.path() / "sweep.png");
  const Image img = CheckFile(info, 1600);
  ASSERT_EQ(info.panels.size(), 4u);
  // Rows are metrics, columns parameters.
  const PanelInfo& a = info.Panel(kTracking + " vs " + kParticles);
  const PanelInfo& b = info.Panel(kTracking + " vs " + kRejection);
  const PanelInfo& c = info.Panel(kSuccess + " vs " + kParticles);
  EXPECT_EQ(a.y, b.y);
  EXPECT_LT(a.x, b.x);
  EXPECT_EQ(a.x, c.x);
  EXPECT_LT(a.y, c.y);
  EXPECT_EQ(Bytes(info), Bytes(RenderSweepFigure(GridSweep(), tmp_.path() / "again.png")));
}

TEST_F(SweepFigureTest, SpanningParameterGetsALogAxisWithOneLinePerOtherValue) {
  const FigureInfo info = RenderSweepFigure(GridSweep(), tmp_.path() / "sweep.png");
  const Image img = ReadPng(info.path);
  const PanelInfo& panel = info.Panel(kTracking + " vs " + kParticles);
  // The frame's x is log10(particles): 100 .. 1000 with a margin.
  EXPECT_LT(panel.box.min.x(), 2.0);
  EXPECT_GT(panel.box.min.x(), 1.8);
  EXPECT_GT(panel.box.max.x(), 3.0);
  EXPECT_LT(panel.box.max.x(), 3.2);
  for (int particles : {100, 300, 1000}) {
    const double x = std::log10(particles);
    // rejection off: first series; on: second.
    EXPECT_TRUE(ColorAround(img, panel, Vec2(x, TrackingMean(particles, false)), RunColor(0)))
        << particles;
    EXPECT_TRUE(ColorAround(img, panel, Vec2(x, TrackingMean(particles, true)), RunColor(1)))
        << particles;
    // The bar reaches from min to max over the repeats: inside it, beyond the marker.
    EXPECT_TRUE(
        ColorAround(img, panel, Vec2(x, TrackingMean(particles, false) + 0.035), RunColor(0)));
    EXPECT_TRUE(
        ColorAround(img, panel, Vec2(x, TrackingMean(particles, true) - 0.035), RunColor(1)));
    // ... and not further.
    EXPECT_FALSE(ColorAround(img, panel, Vec2(x, TrackingMean(particles, false) + 0.075),
                             RunColor(0), 12, 60));
  }
  // A line joins the means: halfway between 300 and 1000 on the log axis.
  const double mid = 0.5 * (std::log10(300) + std::log10(1000));
  const double y_mid = 0.5 * (TrackingMean(300, true) + TrackingMean(1000, true));
  EXPECT_TRUE(ColorAround(img, panel, Vec2(mid, y_mid), RunColor(1), 6));
  // On a linear axis that point would sit elsewhere: far from any data here.
  EXPECT_TRUE(ColorNear(PixelAt(img, panel, Vec2(mid, 0.6)), palette::kBackground, 40));
}

TEST_F(SweepFigureTest, BooleanParameterGetsACategoricalAxisFalseFirst) {
  SweepFigureData d = GridSweep();
  // Listed true first: the axis still puts false on the left.
  std::swap(d.combinations[0], d.combinations[1]);
  const FigureInfo info = RenderSweepFigure(d, tmp_.path() / "sweep.png");
  const Image img = ReadPng(info.path);
  const PanelInfo& panel = info.Panel(kTracking + " vs " + kRejection);
  EXPECT_DOUBLE_EQ(panel.box.min.x(), -0.5);
  EXPECT_DOUBLE_EQ(panel.box.max.x(), 1.5);
  // One series per particle count, in ascending order.
  const int counts[3] = {100, 300, 1000};
  for (int s = 0; s < 3; ++s) {
    EXPECT_TRUE(ColorAround(img, panel, Vec2(0.0, TrackingMean(counts[s], false)), RunColor(s)))
        << s;
    EXPECT_TRUE(ColorAround(img, panel, Vec2(1.0, TrackingMean(counts[s], true)), RunColor(s)))
        << s;
  }
  // The middle series sits exactly on its value.
  EXPECT_TRUE(ColorNear(PixelAt(img, panel, Vec2(1.0, TrackingMean(300, true))), RunColor(1), 30));
}

TEST_F(SweepFigureTest, NarrowNumericRangeGetsALinearAxis) {
  SweepFigureData d;
  d.parameters = {"nav.localizer.sigma_hit"};
  d.metrics = {kTracking};
  for (double s : {0.1, 0.2, 0.3}) {
    SweepCombination c;
    c.values = {s == 0.3 ? "0.30000000000000004" : std::to_string(s)};
    c.metrics = {{10 * s, 10 * s + 1.0}};
    d.combinations.push_back(c);
  }
  const FigureInfo info = RenderSweepFigure(d, tmp_.path() / "sweep.png", {1000, 1, "sigma"});
  const Image img = CheckFile(info, 1000);
  const PanelInfo& panel = info.Panel(kTracking + " vs nav.localizer.sigma_hit");
  EXPECT_NEAR(panel.box.min.x(), 0.1 - 0.012, 1e-9);
  EXPECT_NEAR(panel.box.max.x(), 0.3 + 0.012, 1e-9);
  // One series: no sideways shift; mean, bar ends and the line between means.
  for (double s : {0.1, 0.2, 0.3}) {
    EXPECT_TRUE(ColorNear(PixelAt(img, panel, Vec2(s, 10 * s + 0.5)), RunColor(0), 30)) << s;
    EXPECT_TRUE(ColorAround(img, panel, Vec2(s, 10 * s + 0.1), RunColor(0), 1)) << s;
    EXPECT_TRUE(ColorAround(img, panel, Vec2(s, 10 * s + 0.9), RunColor(0), 1)) << s;
  }
  EXPECT_TRUE(ColorNear(PixelAt(img, panel, Vec2(0.15, 2.0)), RunColor(0), 40));
  EXPECT_TRUE(ColorNear(PixelAt(img, panel, Vec2(0.15, 3.5)), palette::kBackground, 40));
}

TEST_F(SweepFigureTest, WordsAreCategoriesInFirstAppearanceOrderAndModesKeepTheirColours) {
  SweepFigureData d;
  d.parameters = {"map_mode", kParticles};
  d.metrics = {kTracking};
  const std::vector<std::string> modes = {"partial", "single", "consistent"};
  for (std::size_t i = 0; i < modes.size(); ++i) {
    for (int particles : {200, 400}) {
      SweepCombination c;
      c.values = {modes[i], std::to_string(particles)};
      c.metrics = {{0.2 * static_cast<double>(i + 1) + particles / 4000.0}};
      d.combinations.push_back(c);
    }
  }
  const FigureInfo info = RenderSweepFigure(d, tmp_.path() / "sweep.png");
  const Image img = ReadPng(info.path);
  const PanelInfo& by_mode = info.Panel(kTracking + " vs map_mode");
  EXPECT_DOUBLE_EQ(by_mode.box.max.x(), 2.5);
  EXPECT_TRUE(ColorAround(img, by_mode, Vec2(1.0, 0.4 + 0.05), RunColor(0)));  // single, 200
  EXPECT_TRUE(ColorAround(img, by_mode, Vec2(2.0, 0.6 + 0.1), RunColor(1)));   // consistent, 400
  // 200 .. 400 spans less than 10x: linear; one line per mode in the mode's colour.
  const PanelInfo& by_particles = info.Panel(kTracking + " vs " + kParticles);
  EXPECT_LT(by_particles.box.min.x(), 200.0);
  EXPECT_GT(by_particles.box.min.x(), 150.0);
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const Rgba color = ModeColor(modes[i], static_cast<int>(i));
    EXPECT_TRUE(ColorAround(img, by_particles, Vec2(200.0, 0.2 * static_cast<double>(i + 1) + 0.05),
                            color, 12, 30))
        << modes[i];
  }
}

TEST_F(SweepFigureTest, NanValuesAreLeftOutAndAnAllNanMetricStillRenders) {
  SweepFigureData d = GridSweep();
  d.metrics.push_back("localization_error_m.pooled.rms");
  const double nan = std::nan("");
  for (auto& c : d.combinations) {
    c.metrics.push_back({nan, nan, nan});
    // The largest repeat of 300 particles without rejection failed.
    if (c.values[0] == "300" && c.values[1] == "false") c.metrics[0][2] = nan;
  }
  // Every repeat of 1000 particles failed.
  d.combinations[4].metrics[0] = {nan, nan, nan};
  d.combinations[5].metrics[0] = {nan, nan, nan};
  const FigureInfo info = RenderSweepFigure(d, tmp_.path() / "sweep.png");
  const Image img = CheckFile(info, 1600);
  ASSERT_EQ(info.panels.size(), 6u);
  const PanelInfo& panel = info.Panel(kTracking + " vs " + kParticles);
  const double x300 = std::log10(300.0);
  // Mean of the two finite repeats; the bar ends at the largest of them.
  const double m = TrackingMean(300, false);
  EXPECT_TRUE(ColorAround(img, panel, Vec2(x300, m - 0.025), RunColor(0)));
  EXPECT_FALSE(ColorAround(img, panel, Vec2(x300, m + 0.03), RunColor(0), 12, 60));
  // No point where every value is NaN, and the line stops before it.
  EXPECT_FALSE(ColorAround(img, panel, Vec2(3.0, TrackingMean(1000, true)), RunColor(1), 12, 60));
  EXPECT_TRUE(ColorAround(img, panel, Vec2(x300, TrackingMean(300, true)), RunColor(1)));
  const double mid = 0.5 * (x300 + 3.0);
  EXPECT_FALSE(ColorAround(img, panel, Vec2(mid, TrackingMean(300, true)), RunColor(1), 12, 60));
  // "all nan" is written above the axis there, and only there.
  EXPECT_TRUE(TextNear(img, panel, 3.0));
  EXPECT_FALSE(TextNear(img, panel, x300));
}

TEST_F(SweepFigureTest, ManySeriesArePooledIntoOne) {
  SweepFigureData d;
  d.parameters = {"a", "b"};
  d.metrics = {"m"};
  for (int a = 1; a <= 2; ++a) {
    for (int b = 1; b <= kMaxSweepSeries + 2; ++b) {
      SweepCombination c;
      c.values = {std::to_string(a), std::to_string(b)};
      c.metrics = {{a + 0.01 * b}};
      d.combinations.push_back(c);
    }
  }
  const FigureInfo info = RenderSweepFigure(d, tmp_.path() / "sweep.png");
  const Image img = ReadPng(info.path);
  // Column a: 10 values of b would be 10 lines; pooled into one series in the first colour,
  // the mean over b at each a, the bar from b = 1 to b = 10.
  const PanelInfo& pooled = info.Panel("m vs a");
  for (int a = 1; a <= 2; ++a) {
    EXPECT_TRUE(ColorNear(PixelAt(img, pooled, Vec2(a, a + 0.055)), RunColor(0), 30)) << a;
    EXPECT_TRUE(ColorAround(img, pooled, Vec2(a, a + 0.095), RunColor(0), 1)) << a;
  }
  EXPECT_TRUE(ColorNear(PixelAt(img, pooled, Vec2(1.5, 1.555)), RunColor(0), 40));
  // Column b: two series (a = 1, a = 2), side by side.
  const PanelInfo& lines = info.Panel("m vs b");
  // b = 1 .. 10 spans a factor 10: a log axis.
  EXPECT_TRUE(ColorAround(img, lines, Vec2(std::log10(4.0), 1.04), RunColor(0)));
  EXPECT_TRUE(ColorAround(img, lines, Vec2(std::log10(4.0), 2.04), RunColor(1)));
}

TEST_F(SweepFigureTest, RandomSamplesBecomeAScatterOfEveryCase) {
  SweepFigureData d;
  d.parameters = {"a", "b"};
  d.metrics = {"m"};
  // Every combination distinct: a and b drawn "at random", two repeats each.
  const double a[5] = {1.3, 4.1, 2.2, 3.7, 2.9};
  const double b[5] = {0.52, 0.11, 0.93, 0.37, 0.75};
  for (int i = 0; i < 5; ++i) {
    SweepCombination c;
    c.values = {std::to_string(a[i]), std::to_string(b[i])};
    c.metrics = {{a[i], a[i] + 1.0}};
    d.combinations.push_back(c);
  }
  const FigureInfo info = RenderSweepFigure(d, tmp_.path() / "sweep.png");
  const Image img = ReadPng(info.path);
  const PanelInfo& panel = info.Panel("m vs a");
  for (int i = 0; i < 5; ++i) {
    // Every case is a dot: both repeats, not their mean.
    EXPECT_TRUE(ColorNear(PixelAt(img, panel, Vec2(a[i], a[i])), RunColor(0), 30)) << i;
    EXPECT_TRUE(ColorNear(PixelAt(img, panel, Vec2(a[i], a[i] + 1.0)), RunColor(0), 30)) << i;
    EXPECT_FALSE(ColorNear(PixelAt(img, panel, Vec2(a[i], a[i] + 0.5)), RunColor(0), 60)) << i;
  }
  // No lines between them.
  EXPECT_FALSE(ColorNear(PixelAt(img, panel, Vec2(1.75, 1.75)), RunColor(0), 60));
  const PanelInfo& by_b = info.Panel("m vs b");
  EXPECT_TRUE(ColorNear(PixelAt(img, by_b, Vec2(b[3], a[3] + 1.0)), RunColor(0), 30));
}

TEST_F(SweepFigureTest, ManyParametersWidenTheFigure) {
  SweepFigureData d;
  d.metrics = {"m"};
  // Not "p" + std::to_string(p): GCC 12 at -O3 warns about it (-Wrestrict, GCC bug 105651).
  for (int p = 0; p < 6; ++p) d.parameters.push_back(std::string("p").append(std::to_string(p)));
  for (int i = 0; i < 3; ++i) {
    SweepCombination c;
    for (int p = 0; p < 6; ++p) c.values.push_back(std::to_string(i + p));
    c.metrics = {{static_cast<double>(i)}};
    d.combinations.push_back(c);
  }
  const FigureInfo info = RenderSweepFigure(d, tmp_.path() / "sweep.png", {1200, 1, ""});
  EXPECT_EQ(info.width, 6 * 320);
  EXPECT_EQ(info.panels.size(), 6u);
  EXPECT_EQ(ReadPng(info.path).width, 6 * 320);
}

TEST_F(SweepFigureTest, MissingOrMismatchedDataIsAnIoErrorAndWritesNothing) {
  const std::filesystem::path png = tmp_.path() / "sweep.png";
  EXPECT_THROW(RenderSweepFigure({}, png), core::IoError);
  SweepFigureData d = GridSweep();
  d.combinations[2].values.pop_back();
  EXPECT_THROW(RenderSweepFigure(d, png), core::IoError);
  d = GridSweep();
  d.combinations[4].metrics.pop_back();
  EXPECT_THROW(RenderSweepFigure(d, png), core::IoError);
  d = GridSweep();
  d.metrics.clear();
  for (auto& c : d.combinations) c.metrics.clear();
  EXPECT_THROW(RenderSweepFigure(d, png), core::IoError);
  EXPECT_FALSE(std::filesystem::exists(png));
  tmp_.Write("file", "x");
  EXPECT_THROW(RenderSweepFigure(GridSweep(), tmp_.path() / "file" / "sweep.png"), core::IoError);
  EXPECT_THROW(RenderSweepFigure(GridSweep(), png, {100, 1, ""}), core::ConfigError);
  EXPECT_FALSE(std::filesystem::exists(png));
}

}  // namespace
}  // namespace retrace::viz
