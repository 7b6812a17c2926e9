#pragma once
// Decompressing the chunks of the binary log containers (MCAP: lz4 frames and zstd; ROS 1 bags:
// bz2 and roslz4, which is the LZ4 frame format) into a buffer of the size the chunk declares.
// The buffer grows as output arrives, from 64 KiB up to the declared size, so that a chunk that
// lies about its size costs no more memory than its real contents; output beyond the declared
// size, input that ends early and corrupt input are refused with core::IoError and a short
// reason ("lz4 data truncated after 812 bytes") that the caller prefixes with the file and the
// chunk's offset.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace retrace::logs::internal {

/// Decompresses one or more LZ4 frames into `out` (exactly `size` bytes).
void DecompressLz4(std::span<const std::uint8_t> in, std::size_t size,
                   std::vector<std::uint8_t>& out);

/// Decompresses one or more zstd frames into `out` (exactly `size` bytes).
void DecompressZstd(std::span<const std::uint8_t> in, std::size_t size,
                    std::vector<std::uint8_t>& out);

/// Decompresses one bzip2 stream into `out` (exactly `size` bytes); bytes after the stream's end
/// are refused.
void DecompressBz2(std::span<const std::uint8_t> in, std::size_t size,
                   std::vector<std::uint8_t>& out);

}  // namespace retrace::logs::internal
