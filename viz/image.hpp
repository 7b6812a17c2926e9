#pragma once
// A plain 8-bit RGB image (what a canvas reads back and what figures are made of), and PNG
// files. Kept free of OpenCV types so that callers and tests need no OpenCV.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "viz/style.hpp"

namespace retrace::viz {

/// Row-major RGB pixels, top row first, 3 bytes per pixel in R, G, B order.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  /// A width x height image filled with `fill` (its alpha is ignored).
  Image(int width_in, int height_in, Rgba fill = palette::kBackground);

  bool empty() const { return width <= 0 || height <= 0; }
  /// The colour of pixel (x = column, y = row from the top), alpha 255. Aborts outside.
  Rgba At(int x, int y) const;
  bool operator==(const Image&) const = default;
};

/// Encodes `image` as PNG (deterministic bytes for the same pixels) and writes it atomically.
/// Throws core::IoError if the image is empty, encoding fails or the file cannot be written.
void WritePng(const Image& image, const std::filesystem::path& png);

/// The PNG file's bytes, encoded in memory (io/png.hpp); the same bytes WritePng writes. Throws
/// core::IoError for an empty image or a failed encoding.
std::vector<std::uint8_t> EncodePng(const Image& image);

/// Reads a PNG file as RGB (grey spread over the three channels, alpha dropped). Throws
/// core::IoError if it is missing, not a PNG or not decodable.
Image ReadPng(const std::filesystem::path& png);

/// Places `tiles` in a grid of `columns`, left to right then top to bottom, with `gap` pixels
/// between them on `background`; each cell is as wide as the widest tile of its column and as
/// tall as the tallest of its row, tiles are top-left aligned. Empty tiles leave their cell
/// blank. Returns an empty image for no tiles.
Image ComposeGrid(const std::vector<Image>& tiles, int columns, int gap = 0,
                  Rgba background = palette::kBackground);

}  // namespace retrace::viz
