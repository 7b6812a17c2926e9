// likelihood.png (paper Fig. 5): the measurement likelihood over (x, y) around the true pose,
// without and with dynamic scan point rejection.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/errors.hpp"
#include "viz/figures.hpp"
#include "viz/internal/annotate.hpp"
#include "viz/internal/figure_layout.hpp"
#include "viz/internal/layers.hpp"

namespace retrace::viz {
namespace {

using internal::LegendSymbol;

constexpr int kColorBarTile = 130;  // px right of the panels for the colour bar

// A likelihood grid shaded for display, with where its maximum is.
struct Shaded {
  CellRaster raster;
  Vec2 peak = Vec2::Zero();  // cell centre of the maximum
  bool any = false;
};

// Values to display in [0, 1]: likelihood / max, or (log-likelihood - max) / range + 1.
Shaded Shade(const LikelihoodGrid& g, const LikelihoodFigureOptions& o) {
  Shaded s;
  s.raster.width = g.width;
  s.raster.height = g.height;
  s.raster.resolution = g.resolution;
  s.raster.origin = g.origin;
  const std::size_t n = static_cast<std::size_t>(std::max(0, g.width)) *
                        static_cast<std::size_t>(std::max(0, g.height));
  s.raster.cells.assign(n, palette::kMapUnknown);
  if (g.values.size() != n || n == 0) return s;
  // Work in log space whatever the input, so that tiny likelihoods keep their order.
  std::vector<double> l(n, -std::numeric_limits<double>::infinity());
  double l_max = -std::numeric_limits<double>::infinity();
  std::size_t i_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = g.values[i];
    if (!std::isfinite(v)) continue;
    if (g.log_values) {
      l[i] = v;
    } else if (v > 0.0) {
      l[i] = std::log(v);
    }
    if (l[i] > l_max) {
      l_max = l[i];
      i_max = i;
    }
  }
  if (!std::isfinite(l_max)) return s;
  s.any = true;
  s.peak =
      g.origin +
      Vec2((static_cast<double>(i_max % static_cast<std::size_t>(g.width)) + 0.5) * g.resolution,
           (static_cast<double>(i_max / static_cast<std::size_t>(g.width)) + 0.5) * g.resolution);
  const auto& lut = internal::Viridis();
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(g.values[i])) continue;
    double t = 0.0;
    if (std::isfinite(l[i])) {
      t = o.log_scale ? std::max(0.0, 1.0 + (l[i] - l_max) / o.log_range) : std::exp(l[i] - l_max);
    }
    s.raster.cells[i] =
        lut[static_cast<std::size_t>(std::clamp(static_cast<int>(std::lround(t * 255.0)), 0, 255))];
  }
  return s;
}

// Whether a grid has a size, a resolution and width x height values.
bool IsValidGrid(const LikelihoodGrid& g) {
  return g.width > 0 && g.height > 0 && g.resolution > 0.0 &&
         g.values.size() == static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
}

// The area a grid covers.
Box2 GridBox(const LikelihoodGrid& g) {
  return Box2::Of(g.origin, g.origin + Vec2(g.width * g.resolution, g.height * g.resolution));
}

// The subtitle: the heading the grid is taken at, the time and (simulated) the pedestrians
// that can block the robot's view here, not everyone in the world.
std::string LikelihoodSubtitle(const LikelihoodFigureData& data) {
  constexpr double kNearby = 5.0;  // m from the true position to a pedestrian's edge
  const auto nearby =
      std::count_if(data.pedestrians.begin(), data.pedestrians.end(), [&](const Circle& p) {
        return (p.center - data.true_pose.translation()).norm() - p.radius <= kNearby;
      });
  char when[48] = "";
  if (std::isfinite(data.time_s)) std::snprintf(when, sizeof(when), "t = %.1f s, ", data.time_s);
  char sub[200];
  if (data.simulated) {
    std::snprintf(sub, sizeof(sub),
                  "Over (x, y) at the true heading, %s%td pedestrians within %.0f m. Map frame.",
                  when, nearby, kNearby);
  } else {
    std::snprintf(sub, sizeof(sub),
                  "Over (x, y) at the reference heading, %sa recorded log. Map "
                  "frame.",
                  when);
  }
  return sub;
}

// Title, subtitle and the legend: true (or reference) pose, peak and, simulated, pedestrians.
internal::Header LikelihoodHeader(const LikelihoodFigureData& data, const FigureOptions& fo) {
  internal::Header header;
  const char* truth = data.simulated ? "true" : "reference";
  header.title = fo.title.empty()
                     ? std::string("Measurement likelihood around the ") + truth + " pose"
                     : fo.title;
  header.subtitle = LikelihoodSubtitle(data);
  header.legend = {{std::string(truth) + " pose", palette::kTruth, LegendSymbol::kArrow,
                    Marker::kDisc, 3.0, true},
                   {"likelihood peak", palette::kText, LegendSymbol::kRing}};
  if (data.simulated)
    header.legend.push_back({"pedestrians", palette::kPedestrian, LegendSymbol::kRing});
  return header;
}

// A panel's title, with the distance of its peak from the truth (or reference) if it has one.
std::string PanelTitle(const char* title, const Shaded& s, const LikelihoodFigureData& data) {
  std::string out = title;
  if (s.any) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), ": peak %.2f m from %s",
                  (s.peak - data.true_pose.translation()).norm(),
                  data.simulated ? "truth" : "the reference");
    out += buf;
  }
  return out;
}

// The shaded likelihood, pedestrians as rings, the peak and the true pose.
void DrawLikelihoodLayers(GlCanvas& c, const Shaded& s, const LikelihoodFigureData& data) {
  c.DrawRaster(s.raster, core::Pose2::Identity());
  for (const Circle& p : data.pedestrians) {
    c.DrawCircle(p.center, p.radius, 6.0, palette::kBackground);
    c.DrawCircle(p.center, p.radius, 3.0, palette::kPedestrian);
  }
  // The peak as a ring (radius 12 px) so that it never hides the true pose inside it.
  if (s.any) {
    const double r = 12.0 / c.view().pixels_per_meter();
    c.DrawCircle(s.peak, r, 4.5, palette::kText);
    c.DrawCircle(s.peak, r, 2.5, palette::kBackground);
  }
  c.DrawPoseArrows({data.true_pose}, 30.0, palette::kTruth, {}, 1.5, palette::kBackground);
}

}  // namespace

FigureInfo RenderLikelihoodFigure(const LikelihoodFigureData& data,
                                  const std::filesystem::path& png,
                                  const LikelihoodFigureOptions& options) {
  options.figure.Validate();
  if (options.log_scale && !(options.log_range > 0.0)) {
    throw core::ConfigError("log_range", "must be a positive number of log-likelihood units");
  }
  internal::Require(IsValidGrid(data.without_rejection) && IsValidGrid(data.with_rejection), png,
                    "the likelihood figure needs two grids with width x height values");
  const FigureOptions& fo = options.figure;
  const int W = fo.width;
  const int tile_w = (W - kColorBarTile) / 2;
  const int plot_w = tile_w - internal::kPanelLeft - internal::kPanelRight;

  const LikelihoodGrid* grids[2] = {&data.without_rejection, &data.with_rejection};
  Shaded shaded[2] = {Shade(data.without_rejection, options), Shade(data.with_rejection, options)};
  Box2 boxes[2];
  double aspect = 0.5;
  for (int i = 0; i < 2; ++i) {
    boxes[i] = GridBox(*grids[i]);
    const Vec2 s = boxes[i].Size();
    aspect = std::max(aspect, s.y() / s.x());
  }
  const int plot_h = static_cast<int>(std::lround(plot_w * std::min(aspect, 1.2)));

  const internal::Header header = LikelihoodHeader(data, fo);
  const int top = internal::HeaderHeight(header, W);
  const int tile_h = internal::MapPanelAt(0, 0, tile_w, plot_h).tile.height;
  cv::Mat fig = internal::NewFigure(W, top + tile_h + 8);
  internal::DrawHeader(fig, header);

  const char* names[2] = {"without", "with"};
  const char* titles[2] = {"Without dynamic point rejection", "With dynamic point rejection"};
  std::vector<PanelInfo> panels;
  for (int i = 0; i < 2; ++i) {
    const Shaded& s = shaded[i];
    panels.push_back(
        internal::RenderMapPanel(fig, internal::MapPanelAt(i * tile_w, top, tile_w, plot_h),
                                 boxes[i], names[i], PanelTitle(titles[i], s, data), fo.supersample,
                                 [&](GlCanvas& c) { DrawLikelihoodLayers(c, s, data); }));
  }
  const cv::Rect bar(2 * tile_w + 14, top + internal::kPanelTop + 10, 22, plot_h - 20);
  internal::DrawColorBar(fig, bar, options.log_scale ? -options.log_range : 0.0,
                         options.log_scale ? 0.0 : 1.0,
                         options.log_scale ? "log-likelihood - max" : "likelihood / max");
  return internal::FinishFigure(fig, png, std::move(panels));
}

}  // namespace retrace::viz
