#pragma once
// Bridges between viz::Image and OpenCV (private to viz). Inside viz, cv::Mat images are
// CV_8UC3 in R, G, B channel order, like viz::Image; only encoding swaps to OpenCV's BGR.

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

}  // namespace retrace::viz::internal
