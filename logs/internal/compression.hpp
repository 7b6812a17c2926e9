#pragma once
// Compressing the chunks the binary log writers write (MCAP: lz4 frames and zstd; ROS 1 bags:
// bz2 and roslz4's LZ4 frames), as logs/internal/decompression.hpp reads them back. Each throws
// core::IoError with the library's reason should the library fail.

#include <cstdint>
#include <span>
#include <vector>

namespace retrace::logs::internal {

/// zstd at its default level, one frame.
std::vector<std::uint8_t> CompressZstd(std::span<const std::uint8_t> in);

/// How an LZ4 frame is laid out.
struct Lz4Frame {
  bool content_size = false;  ///< the frame header holds the input's size (MCAP)
  bool roslz4 = false;        ///< independent blocks of at most 1 MiB and a content checksum,
                              ///< as roslz4 writes them (ROS 1 bags)
};

/// One LZ4 frame.
std::vector<std::uint8_t> CompressLz4(std::span<const std::uint8_t> in, Lz4Frame frame);

/// bzip2 at block size 9 (900 kB), one stream.
std::vector<std::uint8_t> CompressBz2(std::span<const std::uint8_t> in);

}  // namespace retrace::logs::internal
