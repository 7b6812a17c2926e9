#pragma once
// Bridges between viz::Image and OpenCV (private to viz). Inside viz, cv::Mat images are
// CV_8UC3 in R, G, B channel order, like viz::Image; only the video plugin swaps to OpenCV's BGR.

#include <cmath>
#include <opencv2/core.hpp>

#include "viz/image.hpp"
#include "viz/style.hpp"

namespace retrace::viz::internal {

/// A deep copy of `image` as an RGB cv::Mat.
cv::Mat ToMat(const Image& image);
/// A deep copy of an RGB CV_8UC3 cv::Mat.
Image FromMat(const cv::Mat& rgb);
/// The colour as a cv::Scalar in the RGB channel order used inside viz.
inline cv::Scalar ToScalar(Rgba c) { return cv::Scalar(c.r, c.g, c.b); }

/// OpenCV's sub-pixel drawing: points in fixed point with this many fractional bits (1/16 px),
/// passed as the `shift` of cv::line, cv::polylines, cv::circle.
inline constexpr int kSubPixelBits = 4;
/// A point in pixels as a fixed-point cv::Point for a `shift` of kSubPixelBits.
inline cv::Point SubPixel(double x, double y) {
  constexpr double kOne = 1 << kSubPixelBits;
  return {static_cast<int>(std::lround(x * kOne)), static_cast<int>(std::lround(y * kOne))};
}
inline cv::Point SubPixel(const cv::Point2d& p) { return SubPixel(p.x, p.y); }

}  // namespace retrace::viz::internal
