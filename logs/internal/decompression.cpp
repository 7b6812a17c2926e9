#include "logs/internal/decompression.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <climits>
#include <memory>
#include <string>

#include "core/errors.hpp"

namespace retrace::logs::internal {
namespace {

// Size of the first output buffer of a decompression; it doubles up to the declared size.
constexpr std::size_t kFirstOutputBytes = std::size_t{1} << 16;

// The output buffer of a decompression: grows on demand up to `limit`, then any further output
// goes to a scratch byte and means the data holds more than declared.
class GrowingOutput {
 public:
  GrowingOutput(std::vector<std::uint8_t>& out, std::size_t limit, std::size_t input_bytes)
      : out_(out), limit_(limit) {
    out_.clear();
    out_.resize(std::min(limit_, std::max(kFirstOutputBytes, 4 * input_bytes)));
  }
  // Where the next output goes and how much room there is.
  std::uint8_t* data() { return Full() ? &scratch_ : out_.data() + produced_; }
  std::size_t room() {
    if (produced_ == out_.size() && out_.size() < limit_) {
      out_.resize(std::min(limit_, 2 * out_.size()));
    }
    return Full() ? 1 : out_.size() - produced_;
  }
  // Records `n` bytes written at data(); false if they went past the declared size.
  bool Advance(std::size_t n, bool was_full) {
    if (was_full) return n == 0;
    produced_ += n;
    return true;
  }
  bool Full() const { return produced_ == limit_; }
  std::size_t produced() const { return produced_; }
  // Throws unless exactly the declared size came out, then trims the buffer to it.
  void Finish(const char* format) {
    if (produced_ != limit_) {
      throw core::IoError(std::string(format) + " data holds " + std::to_string(produced_) +
                          " bytes, the chunk declares " + std::to_string(limit_));
    }
    out_.resize(produced_);
  }

 private:
  std::vector<std::uint8_t>& out_;
  std::size_t limit_;
  std::size_t produced_ = 0;
  std::uint8_t scratch_ = 0;
};

[[noreturn]] void ThrowTooMuch(const char* format, std::size_t size) {
  throw core::IoError(std::string(format) + " data holds more than the declared " +
                      std::to_string(size) + " bytes");
}

[[noreturn]] void ThrowTruncated(const char* format, std::size_t produced) {
  throw core::IoError(std::string(format) + " data truncated after " + std::to_string(produced) +
                      " bytes");
}

std::string Bz2ErrorName(int code) {
  switch (code) {
    case BZ_DATA_ERROR:
      return "data error";
    case BZ_DATA_ERROR_MAGIC:
      return "not bzip2 data";
    case BZ_MEM_ERROR:
      return "out of memory";
    case BZ_PARAM_ERROR:
      return "bad parameter";
    default:
      return "error " + std::to_string(code);
  }
}

}  // namespace

void DecompressZstd(std::span<const std::uint8_t> in, std::size_t size,
                    std::vector<std::uint8_t>& out) {
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), ZSTD_freeDCtx);
  if (!ctx) throw core::IoError("cannot create a zstd decompression context");
  GrowingOutput output(out, size, in.size());
  ZSTD_inBuffer input{in.data(), in.size(), 0};
  for (;;) {
    const std::size_t room = output.room();
    const bool was_full = output.Full();
    ZSTD_outBuffer o{output.data(), room, 0};
    const std::size_t in_before = input.pos;
    const std::size_t ret = ZSTD_decompressStream(ctx.get(), &o, &input);
    if (ZSTD_isError(ret)) {
      throw core::IoError(std::string("zstd data corrupt: ") + ZSTD_getErrorName(ret));
    }
    if (!output.Advance(o.pos, was_full)) ThrowTooMuch("zstd", size);
    if (ret == 0 && input.pos == input.size) break;
    if (input.pos == in_before && o.pos == 0) ThrowTruncated("zstd", output.produced());
  }
  output.Finish("zstd");
}

void DecompressLz4(std::span<const std::uint8_t> in, std::size_t size,
                   std::vector<std::uint8_t>& out) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    throw core::IoError("cannot create an lz4 decompression context");
  }
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw, LZ4F_freeDecompressionContext);
  GrowingOutput output(out, size, in.size());
  std::size_t in_pos = 0;
  for (;;) {
    std::size_t room = output.room();
    const bool was_full = output.Full();
    std::size_t consumed = in.size() - in_pos;
    const std::size_t ret =
        LZ4F_decompress(ctx.get(), output.data(), &room, in.data() + in_pos, &consumed, nullptr);
    if (LZ4F_isError(ret)) {
      throw core::IoError(std::string("lz4 data corrupt: ") + LZ4F_getErrorName(ret));
    }
    in_pos += consumed;
    if (!output.Advance(room, was_full)) ThrowTooMuch("lz4", size);
    if (ret == 0 && in_pos == in.size()) break;
    if (consumed == 0 && room == 0) ThrowTruncated("lz4", output.produced());
  }
  output.Finish("lz4");
}

void DecompressBz2(std::span<const std::uint8_t> in, std::size_t size,
                   std::vector<std::uint8_t>& out) {
  bz_stream stream{};
  if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK) {
    throw core::IoError("cannot create a bz2 decompression stream");
  }
  std::unique_ptr<bz_stream, decltype(&BZ2_bzDecompressEnd)> guard(&stream, BZ2_bzDecompressEnd);
  GrowingOutput output(out, size, in.size());
  std::size_t in_pos = 0;
  for (;;) {
    // bzlib counts in unsigned int: at most UINT_MAX bytes in and out per call.
    const std::size_t room = std::min<std::size_t>(output.room(), UINT_MAX);
    const bool was_full = output.Full();
    const std::size_t offered = std::min<std::size_t>(in.size() - in_pos, UINT_MAX);
    stream.next_in = const_cast<char*>(reinterpret_cast<const char*>(in.data() + in_pos));
    stream.avail_in = static_cast<unsigned>(offered);
    stream.next_out = reinterpret_cast<char*>(output.data());
    stream.avail_out = static_cast<unsigned>(room);
    const int ret = BZ2_bzDecompress(&stream);
    if (ret != BZ_OK && ret != BZ_STREAM_END) {
      throw core::IoError("bz2 data corrupt: " + Bz2ErrorName(ret));
    }
    const std::size_t consumed = offered - stream.avail_in;
    const std::size_t produced = room - stream.avail_out;
    in_pos += consumed;
    if (!output.Advance(produced, was_full)) ThrowTooMuch("bz2", size);
    if (ret == BZ_STREAM_END) break;
    if (consumed == 0 && produced == 0) ThrowTruncated("bz2", output.produced());
  }
  if (in_pos != in.size()) {
    throw core::IoError("bz2 data: " + std::to_string(in.size() - in_pos) +
                        " bytes after the end of the stream");
  }
  output.Finish("bz2");
}

}  // namespace retrace::logs::internal
