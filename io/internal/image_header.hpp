#pragma once
// What a map image declares before any decoder sees it: the format by its signature, and the
// size, checked against the limit (core::kMaxMapCells) and against the bytes the file holds. A
// PNG's chunk structure is checked whole (lengths, CRCs, IHDR first, IEND last), so that a
// truncated or corrupt file is refused here, in one line, and libpng never prints its own.

#include <cstdint>
#include <filesystem>
#include <string_view>

namespace retrace::io::internal {

enum class ImageFormat { kPgm, kPnm, kPng };

struct ImageHeader {
  ImageFormat format = ImageFormat::kPng;
  std::int64_t width = 0;
  std::int64_t height = 0;
};

/// The header of a Netpbm image (P1, P3, P4, P6) or a PNG; for a PGM (P2, P5) only its format
/// (the PGM reader parses it strictly, the size limit included). Throws core::IoError naming
/// `path` for any other format, an empty or oversized image, pixel data shorter than the header
/// declares (binary Netpbm), or a PNG whose chunks do not check out.
ImageHeader CheckImageHeader(std::string_view bytes, const std::filesystem::path& path);

}  // namespace retrace::io::internal
