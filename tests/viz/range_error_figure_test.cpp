// range_error.png on synthetic data: two panels where the data says, the bars' colour inside a
// tall bin and white above it, byte-identical when rendered twice, and missing data refused.

#include "viz/range_error_figure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/viz/viz_test_data.hpp"
#include "viz/image.hpp"
#include "viz/render_error.hpp"

namespace retrace::viz {
namespace {

using RangeErrorFigureTest = retrace::testing::TempDirTest;

// A Gaussian histogram of errors and its density, on a linear and a log panel.
RangeErrorFigureData GaussianData() {
  RangeErrorFigureData data;
  for (const bool log_scale : {false, true}) {
    RangeErrorPanel p;
    p.name = log_scale ? "all" : "near";
    p.title = p.name;
    p.log_scale = log_scale;
    for (int b = 0; b <= 40; ++b) p.bin_edges.push_back(-0.2 + 0.01 * b);
    for (int b = 0; b < 40; ++b) {
      const double x = p.bin_edges[b] + 0.005;
      p.bin_density.push_back(std::exp(-0.5 * x * x / 0.0025) / (0.05 * std::sqrt(2 * M_PI)));
    }
    for (int k = 0; k <= 200; ++k) {
      const double x = -0.2 + 0.002 * k;
      p.curve_error.push_back(x);
      p.curve_density.push_back(std::exp(-0.5 * x * x / 0.0025) / (0.05 * std::sqrt(2 * M_PI)));
    }
    data.panels.push_back(p);
  }
  return data;
}

TEST_F(RangeErrorFigureTest, DrawsTheHistogramInEachPanelAndIsDeterministic) {
  FigureOptions options;
  options.width = 800;
  const FigureInfo info = RenderRangeErrorFigure(GaussianData(), tmp_.path() / "a.png", options);
  ASSERT_EQ(info.panels.size(), 2u);
  const Image img = ReadPng(info.path);
  const PanelInfo& near = info.Panel("near");
  // Inside the tallest bin (density 7.9 at 0) the bar's colour; well above the curve, white.
  EXPECT_TRUE(testing::ColorNear(testing::PixelAt(img, near, Vec2(-0.004, 2.0)),
                                 Rgba{150, 190, 225}, 10));
  EXPECT_TRUE(testing::ColorNear(testing::PixelAt(img, near, Vec2(-0.15, 7.0)),
                                 Rgba{255, 255, 255}, 10));
  EXPECT_LT(info.Panel("all").box.max.y(), 2.0);  // log10 of the densities
  RenderRangeErrorFigure(GaussianData(), tmp_.path() / "b.png", options);
  EXPECT_EQ(tmp_.Read("a.png"), tmp_.Read("b.png"));
}

TEST_F(RangeErrorFigureTest, RefusesMissingData) {
  EXPECT_THROW(RenderRangeErrorFigure({}, tmp_.path() / "c.png"), core::IoError);
  RangeErrorFigureData data = GaussianData();
  data.panels[0].bin_edges.pop_back();
  EXPECT_THROW(RenderRangeErrorFigure(data, tmp_.path() / "c.png"), core::IoError);
  EXPECT_FALSE(std::filesystem::exists(tmp_.path() / "c.png"));
}

}  // namespace
}  // namespace retrace::viz
