#include "viz/internal/cv_image.hpp"

#include <cstring>

#include "core/check.hpp"

namespace retrace::viz::internal {

cv::Mat ToMat(const Image& image) {
  if (image.empty()) return {};
  cv::Mat m(image.height, image.width, CV_8UC3);
  RETRACE_CHECK(m.isContinuous());
  std::memcpy(m.data, image.rgb.data(), image.rgb.size());
  return m;
}

Image FromMat(const cv::Mat& rgb) {
  RETRACE_CHECK(rgb.empty() || rgb.type() == CV_8UC3);
  Image out;
  if (rgb.empty()) return out;
  out.width = rgb.cols;
  out.height = rgb.rows;
  out.rgb.resize(static_cast<std::size_t>(rgb.cols) * static_cast<std::size_t>(rgb.rows) * 3);
  for (int r = 0; r < rgb.rows; ++r) {
    std::memcpy(out.rgb.data() + static_cast<std::size_t>(r) * rgb.cols * 3, rgb.ptr(r),
                static_cast<std::size_t>(rgb.cols) * 3);
  }
  return out;
}

}  // namespace retrace::viz::internal
