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

// Netpbm: P1 (ASCII bitmap), P3 (ASCII RGB), P4 (binary bitmap), P6 (binary RGB).
ImageHeader CheckPnm(std::string_view b, const std::filesystem::path& path) {
  const char kind = b[1];
  std::size_t at = 2;
  const auto number = [&](const char* what) {
    while (at < b.size()) {
      if (b[at] == '#') {
        while (at < b.size() && b[at] != '\n' && b[at] != '\r') ++at;
      } else if (std::strchr(" \t\n\r\v\f", b[at]) != nullptr) {
        ++at;
      } else {
        break;
      }
    }
    std::int64_t v = 0;
    const std::size_t start = at;
    while (at < b.size() && b[at] >= '0' && b[at] <= '9') {
      if (v > core::kMaxMapCells) Fail(path, std::string("Netpbm ") + what + " is too large");
      v = v * 10 + (b[at] - '0');
      ++at;
    }
    if (at == start) Fail(path, std::string("malformed Netpbm header: no ") + what);
    return v;
  };
  ImageHeader header;
  header.format = ImageFormat::kPnm;
  header.width = number("width");
  header.height = number("height");
  const bool bitmap = kind == '1' || kind == '4';
  const std::int64_t maxval = bitmap ? 1 : number("maxval");
  CheckSize(path, "Netpbm", header.width, header.height);
  if (!bitmap && (maxval < 1 || maxval > 65535)) {
    Fail(path, "Netpbm maxval " + std::to_string(maxval) + " is out of range 1..65535");
  }
  if (kind == '4' || kind == '5' || kind == '6') {
    const std::int64_t channels = kind == '6' ? 3 : 1;
    const std::int64_t bytes_per_sample = maxval > 255 ? 2 : 1;
    const std::int64_t row =
        kind == '4' ? (header.width + 7) / 8 : header.width * channels * bytes_per_sample;
    const std::int64_t needed = row * header.height;
    const auto available = static_cast<std::int64_t>(b.size() - std::min(b.size(), at + 1));
    if (available < needed) {
      Fail(path, "truncated Netpbm image: the header declares " + std::to_string(header.width) +
                     " x " + std::to_string(header.height) + " pixels (" + std::to_string(needed) +
                     " bytes), the file holds " + std::to_string(available));
    }
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
  if (bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '2' || bytes[1] == '5')) {
    return {ImageFormat::kPgm, 0, 0};  // parsed strictly, size limit included, by the PGM reader
  }
  if (bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6') {
    return CheckPnm(bytes, path);
  }
  Fail(path, "not a map image retrace reads (PGM, PNG, or PBM/PPM)");
}

}  // namespace retrace::io::internal
