#include "logs/internal/compression.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <string>

#include "core/errors.hpp"

namespace retrace::logs::internal {

std::vector<std::uint8_t> CompressZstd(std::span<const std::uint8_t> in) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(in.size()));
  const std::size_t n =
      ZSTD_compress(out.data(), out.size(), in.data(), in.size(), ZSTD_CLEVEL_DEFAULT);
  if (ZSTD_isError(n)) {
    throw core::IoError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
  }
  out.resize(n);
  return out;
}

std::vector<std::uint8_t> CompressLz4(std::span<const std::uint8_t> in, Lz4Frame frame) {
  LZ4F_preferences_t prefs{};
  if (frame.content_size) prefs.frameInfo.contentSize = in.size();
  if (frame.roslz4) {
    // roslz4 refuses frames that differ in any of these.
    prefs.frameInfo.blockSizeID = LZ4F_max1MB;
    prefs.frameInfo.blockMode = LZ4F_blockIndependent;
    prefs.frameInfo.contentChecksumFlag = LZ4F_contentChecksumEnabled;
  }
  std::vector<std::uint8_t> out(LZ4F_compressFrameBound(in.size(), &prefs));
  const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &prefs);
  if (LZ4F_isError(n)) {
    throw core::IoError(std::string("lz4 compression failed: ") + LZ4F_getErrorName(n));
  }
  out.resize(n);
  return out;
}

std::vector<std::uint8_t> CompressBz2(std::span<const std::uint8_t> in) {
  // bzip2's bound on its output: 1 % more than the input and 600 bytes.
  unsigned length = static_cast<unsigned>(in.size() + in.size() / 100 + 600);
  std::vector<std::uint8_t> out(length);
  const int ret =
      BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(out.data()), &length,
                               const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                               static_cast<unsigned>(in.size()), 9, 0, 0);
  if (ret != BZ_OK) throw core::IoError("bz2 compression failed (" + std::to_string(ret) + ")");
  out.resize(length);
  return out;
}

}  // namespace retrace::logs::internal
