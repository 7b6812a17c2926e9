#pragma once
// PNG files by libpng alone: the encoder of every image retrace writes (figures, map images) and
// the checked decoder of the images it reads back. (OpenCV's image codecs are not used: loading
// them, with GDAL and its dependencies, cost every process 0.15 s at start.)

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "io/decoded_image.hpp"

namespace retrace::io {

/// `pixels` (`height` rows of `width` × `channels` bytes, the top row first; channels 1: grey,
/// 3: RGB) as a PNG file's bytes. The same pixels always give the same bytes (zlib level 6,
/// libpng's default filters). Throws core::IoError for a size that does not match `pixels` or
/// when libpng fails.
std::string EncodePng(std::span<const std::uint8_t> pixels, int width, int height, int channels);

/// The PNG file at `path`, its chunks checked before libpng sees them, decoded to 8-bit channels
/// (io/decoded_image.hpp). Throws core::IoError naming `path` for a missing, non-PNG, truncated or
/// corrupt file.
DecodedImage ReadPngFile(const std::filesystem::path& path);

}  // namespace retrace::io
