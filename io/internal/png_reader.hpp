#pragma once
// PNG map images, decoded by libpng with its messages caught: a corrupt image is refused with
// one core::IoError, and libpng's warnings (an sRGB profile it dislikes, an ancillary chunk's CRC)
// are dropped rather than printed beside retrace's output.

#include <filesystem>
#include <string_view>

#include "io/decoded_image.hpp"

namespace retrace::io::internal {

/// Decodes `bytes` (a whole PNG file whose chunks CheckImageHeader has checked) to 8-bit grey,
/// grey + alpha, RGB or RGBA: palettes and transparency chunks are expanded, grey below 8 bits is
/// stretched to 0..255. Throws core::IoError naming `path` for 16-bit channels or anything libpng
/// refuses.
DecodedImage ReadPng(std::string_view bytes, const std::filesystem::path& path);

}  // namespace retrace::io::internal
