#include "io/internal/image_header.hpp"

#include <zlib.h>

#include <array>
#include <cstring>
#include <string>

#include "core/errors.hpp"
#include "core/limits.hpp"

namespace retrace::io::internal {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& what) {
  throw core::IoError(path.string() + ": " + what);
}

void CheckSize(const std::filesystem::path& path, std::string_view format, std::int64_t width,
               std::int64_t height) {
  if (width <= 0 || height <= 0) {
    Fail(path, std::string(format) + " header gives an empty image (" + std::to_string(width) +
                   " x " + std::to_string(height) + ")");
  }
  if (width > core::kMaxMapCells || height > core::kMaxMapCells ||
      width * height > core::kMaxMapCells) {
    Fail(path, std::string(format) + " header declares " + std::to_string(width) + " x " +
                   std::to_string(height) + " pixels; retrace's limit for a map is " +
                   std::to_string(core::kMaxMapCells / 1'000'000) + " million cells");
  }
}

std::uint32_t BigEndian32(std::string_view b, std::size_t at) {
  return (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 24) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 8) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3]));
}

ImageHeader CheckPng(std::string_view b, const std::filesystem::path& path) {
  ImageHeader header;
  header.format = ImageFormat::kPng;
  std::size_t at = 8;  // after the signature
  bool first = true, ended = false;
  while (!ended) {
    if (b.size() - at < 12) Fail(path, "truncated PNG: the file ends inside a chunk header");
    const std::uint32_t length = BigEndian32(b, at);
    const std::string_view type = b.substr(at + 4, 4);
    if (length > 0x7fffffffu || length > b.size() - at - 12) {
      Fail(path, "truncated PNG: chunk '" + std::string(type) + "' at byte " + std::to_string(at) +
                     " declares " + std::to_string(length) + " bytes, the file holds " +
                     std::to_string(b.size() - at - 12));
    }
    const std::uint32_t stored = BigEndian32(b, at + 8 + length);
    const auto crc = static_cast<std::uint32_t>(
        crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(b.data() + at + 4),
              static_cast<uInt>(length + 4)));
    if (crc != stored) {
      Fail(path, "corrupt PNG: chunk '" + std::string(type) + "' at byte " + std::to_string(at) +
                     " fails its CRC");
    }
    if (first) {
      if (type != "IHDR" || length != 13) Fail(path, "corrupt PNG: it does not start with IHDR");
      header.width = BigEndian32(b, at + 8);
      header.height = BigEndian32(b, at + 12);
      CheckSize(path, "PNG", header.width, header.height);
      first = false;
    }
    ended = type == "IEND";
    at += 12 + length;
  }
  return header;
}

}  // namespace

ImageHeader CheckImageHeader(std::string_view bytes, const std::filesystem::path& path) {
  static constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P',  'N',  'G',
                                                                 '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPngSignature.data(), 8) == 0) {
    return CheckPng(bytes, path);
  }
  if (bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6') {
    return {ImageFormat::kNetpbm, 0, 0};  // parsed strictly, size limit included, by its reader
  }
  Fail(path, "not a map image retrace reads (PGM, PNG, or PBM/PPM)");
}

}  // namespace retrace::io::internal
