#include "viz/image.hpp"

#include <algorithm>
#include <string_view>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/png.hpp"

namespace retrace::viz {

Image::Image(int width_in, int height_in, Rgba fill)
    : width(std::max(0, width_in)), height(std::max(0, height_in)) {
  rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = fill.r;
    rgb[i + 1] = fill.g;
    rgb[i + 2] = fill.b;
  }
}

Rgba Image::At(int x, int y) const {
  RETRACE_CHECK(x >= 0 && y >= 0 && x < width && y < height);
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(x)) *
                        3;
  return {rgb[i], rgb[i + 1], rgb[i + 2], 255};
}

std::vector<std::uint8_t> EncodePng(const Image& image) {
  if (image.empty()) throw core::IoError("cannot encode an empty image as PNG");
  const std::string bytes = io::EncodePng(image.rgb, image.width, image.height, 3);
  return {bytes.begin(), bytes.end()};
}

void WritePng(const Image& image, const std::filesystem::path& png) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = EncodePng(image);
  } catch (const core::IoError& e) {
    throw core::IoError(png.string() + ": " + e.what());
  }
  io::WriteFileAtomic(png,
                      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

Image ReadPng(const std::filesystem::path& png) {
  const io::DecodedImage decoded = io::ReadPngFile(png);
  Image image(decoded.width, decoded.height);
  const auto channels = static_cast<std::size_t>(decoded.channels);
  const bool colour = decoded.channels >= 3;  // grey (+ alpha) is spread over R, G and B
  for (std::size_t p = 0; p * 3 < image.rgb.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      image.rgb[p * 3 + c] = decoded.data[p * channels + (colour ? c : 0)];
    }
  }
  return image;
}

Image ComposeGrid(const std::vector<Image>& tiles, int columns, int gap, Rgba background) {
  if (tiles.empty()) return {};
  const int cols = std::clamp(columns, 1, static_cast<int>(tiles.size()));
  const int rows = (static_cast<int>(tiles.size()) + cols - 1) / cols;
  std::vector<int> col_w(static_cast<std::size_t>(cols), 0);
  std::vector<int> row_h(static_cast<std::size_t>(rows), 0);
  for (int i = 0; i < static_cast<int>(tiles.size()); ++i) {
    const auto c = static_cast<std::size_t>(i % cols);
    const auto r = static_cast<std::size_t>(i / cols);
    col_w[c] = std::max(col_w[c], tiles[static_cast<std::size_t>(i)].width);
    row_h[r] = std::max(row_h[r], tiles[static_cast<std::size_t>(i)].height);
  }
  int w = gap * (cols - 1);
  for (int cw : col_w) w += cw;
  int h = gap * (rows - 1);
  for (int rh : row_h) h += rh;
  Image out(w, h, background);
  int y = 0;
  for (int r = 0; r < rows; ++r) {
    int x = 0;
    for (int c = 0; c < cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r * cols + c);
      if (i < tiles.size() && !tiles[i].empty()) {
        const Image& t = tiles[i];
        for (int ty = 0; ty < t.height; ++ty) {
          std::copy_n(t.rgb.begin() + static_cast<std::ptrdiff_t>(ty) * t.width * 3, t.width * 3,
                      out.rgb.begin() + (static_cast<std::ptrdiff_t>(y + ty) * w + x) * 3);
        }
      }
      x += col_w[static_cast<std::size_t>(c)] + gap;
    }
    y += row_h[static_cast<std::size_t>(r)] + gap;
  }
  return out;
}

}  // namespace retrace::viz
