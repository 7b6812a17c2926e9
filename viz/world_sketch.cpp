#include "viz/world_sketch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace retrace::viz {
namespace {

struct Bounds {
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  void Add(const Vec2& p, double r = 0.0) {
    lo = lo.cwiseMin(p - Vec2(r, r));
    hi = hi.cwiseMax(p + Vec2(r, r));
  }
  bool valid() const { return lo.x() <= hi.x() && lo.y() <= hi.y(); }
};

}  // namespace

void RenderSketchPng(const SketchScene& scene, const std::filesystem::path& png,
                     const SketchOptions& options) {
  Bounds b;
  for (const auto& ring : scene.solids) for (const auto& p : ring) b.Add(p);
  for (const auto& [p, q] : scene.edges) {
    b.Add(p);
    b.Add(q);
  }
  for (const auto& [c, r] : scene.discs) b.Add(c, r);
  for (const auto& [c, r] : scene.pedestrians) b.Add(c, r);
  for (const auto& p : scene.route) b.Add(p);
  if (scene.robot) b.Add(scene.robot->translation(), scene.robot_radius);
  if (!b.valid()) throw core::IoError(png.string() + ": nothing to draw");
  b.lo -= Vec2(options.margin, options.margin);
  b.hi += Vec2(options.margin, options.margin);

  const Vec2 extent = b.hi - b.lo;
  const double ppm = std::min(options.pixels_per_meter, options.max_pixels / extent.maxCoeff());
  const int w = std::max(1, static_cast<int>(std::ceil(extent.x() * ppm)));
  const int h = std::max(1, static_cast<int>(std::ceil(extent.y() * ppm)));
  // Sub-pixel drawing: OpenCV's `shift` gives 1/16 px precision.
  constexpr int kShift = 4;
  constexpr double kScale = 1 << kShift;
  auto px = [&](const Vec2& p) {
    return cv::Point(static_cast<int>(std::lround((p.x() - b.lo.x()) * ppm * kScale)),
                     static_cast<int>(std::lround((b.hi.y() - p.y()) * ppm * kScale)));
  };
  auto radius = [&](double r) { return std::max(1, static_cast<int>(std::lround(r * ppm * kScale))); };

  cv::Mat img(h, w, CV_8UC3, cv::Scalar(250, 250, 250));
  // 1 m grid.
  for (double x = std::ceil(b.lo.x()); x <= b.hi.x(); x += 1.0) {
    cv::line(img, px({x, b.lo.y()}), px({x, b.hi.y()}), cv::Scalar(235, 235, 235), 1, cv::LINE_AA, kShift);
  }
  for (double y = std::ceil(b.lo.y()); y <= b.hi.y(); y += 1.0) {
    cv::line(img, px({b.lo.x(), y}), px({b.hi.x(), y}), cv::Scalar(235, 235, 235), 1, cv::LINE_AA, kShift);
  }
  const cv::Scalar solid(60, 60, 60);
  for (const auto& ring : scene.solids) {
    std::vector<cv::Point> pts;
    pts.reserve(ring.size());
    for (const auto& p : ring) pts.push_back(px(p));
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{pts}, solid, cv::LINE_AA, kShift);
  }
  for (const auto& [p, q] : scene.edges) cv::line(img, px(p), px(q), solid, 1, cv::LINE_AA, kShift);
  for (const auto& [c, r] : scene.discs) cv::circle(img, px(c), radius(r), solid, cv::FILLED, cv::LINE_AA, kShift);
  if (scene.route.size() >= 2) {
    std::vector<cv::Point> pts;
    for (const auto& p : scene.route) pts.push_back(px(p));
    cv::polylines(img, pts, false, cv::Scalar(200, 120, 30), 2, cv::LINE_AA, kShift);
    cv::circle(img, pts.front(), radius(0.2), cv::Scalar(60, 170, 60), cv::FILLED, cv::LINE_AA, kShift);
  }
  for (const auto& [c, r] : scene.pedestrians) {
    cv::circle(img, px(c), radius(r), cv::Scalar(40, 40, 220), cv::FILLED, cv::LINE_AA, kShift);
  }
  if (scene.robot) {
    const core::Pose2& X = *scene.robot;
    cv::circle(img, px(X.translation()), radius(scene.robot_radius), cv::Scalar(200, 90, 20), 2, cv::LINE_AA, kShift);
    cv::line(img, px(X.translation()), px(X * Vec2(scene.robot_radius, 0.0)), cv::Scalar(200, 90, 20), 2, cv::LINE_AA, kShift);
  }
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", img, bytes)) throw core::IoError(png.string() + ": PNG encoding failed");
  io::WriteFileAtomic(png, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace retrace::viz
