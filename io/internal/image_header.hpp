#pragma once
// What a map image declares before any decoder sees it: the format by its signature, and the
// size, checked against the limit (core::kMaxMapCells) and against the bytes the file holds. A
// PNG's chunk structure is checked whole (lengths, CRCs, IHDR first, IEND last), so that a
// truncated or corrupt file is refused here, in one line, and libpng never prints its own.

#include <cstdint>
#include <filesystem>
#include <string_view>

namespace retrace::io::internal {

enum class ImageFormat { kNetpbm, kPng };

struct ImageHeader {
  ImageFormat format = ImageFormat::kPng;
  std::int64_t width = 0;
  std::int64_t height = 0;
};

/// The header of a PNG; for Netpbm (P1..P6) only its format (the Netpbm reader parses it
/// strictly, the size limit included, before it allocates). Throws core::IoError naming `path`
/// for any other format, an empty or oversized PNG, or a PNG whose chunks do not check out.
ImageHeader CheckImageHeader(std::string_view bytes, const std::filesystem::path& path);

}  // namespace retrace::io::internal
