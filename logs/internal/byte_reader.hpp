#pragma once
// Bounds-checked reading of fixed-width integers and floats from a byte buffer, in little or big
// endian order: the one place where the binary log formats (MCAP records, CDR messages, SQLite
// blobs) touch raw bytes. Every read past the end throws core::IoError with a short message
// ("needs 8 bytes at byte 12, 3 left") that the caller prefixes with the file name and the
// record or message that was being read; no read ever leaves the buffer.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "core/errors.hpp"

namespace retrace::logs::internal {

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes, std::endian order = std::endian::little)
      : bytes_(bytes), order_(order) {}

  /// Bytes read so far (the offset of the next read from the start of the buffer).
  std::size_t offset() const { return offset_; }
  std::size_t size() const { return bytes_.size(); }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  bool AtEnd() const { return offset_ == bytes_.size(); }
  std::endian order() const { return order_; }

  /// Throws core::IoError unless `n` more bytes can be read.
  void Require(std::size_t n) const {
    if (n > remaining()) {
      throw core::IoError("truncated: needs " + std::to_string(n) + " bytes at byte " +
                          std::to_string(offset_) + ", " + std::to_string(remaining()) + " left");
    }
  }

  /// A fixed-width integer or floating-point value in the reader's byte order.
  template <typename T>
  T Read() {
    static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>,
                  "ByteReader::Read reads numbers only");
    Require(sizeof(T));
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + offset_, sizeof(T));
    if (order_ != std::endian::native) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    offset_ += sizeof(T);
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return value;
  }

  std::uint8_t U8() { return Read<std::uint8_t>(); }
  std::uint16_t U16() { return Read<std::uint16_t>(); }
  std::uint32_t U32() { return Read<std::uint32_t>(); }
  std::uint64_t U64() { return Read<std::uint64_t>(); }

  /// The next `n` bytes as a view into the buffer.
  std::span<const std::uint8_t> Bytes(std::uint64_t n) {
    Require(Checked(n));
    const std::span<const std::uint8_t> out = bytes_.subspan(offset_, static_cast<std::size_t>(n));
    offset_ += static_cast<std::size_t>(n);
    return out;
  }

  /// The next `n` bytes as characters (a view into the buffer).
  std::string_view Chars(std::uint64_t n) {
    const std::span<const std::uint8_t> b = Bytes(n);
    return {reinterpret_cast<const char*>(b.data()), b.size()};
  }

  void Skip(std::uint64_t n) { Bytes(n); }

  /// Moves to `offset` from the start of the buffer (at most its size).
  void Seek(std::size_t offset) {
    if (offset > bytes_.size()) {
      throw core::IoError("offset " + std::to_string(offset) + " beyond the end (" +
                          std::to_string(bytes_.size()) + " bytes)");
    }
    offset_ = offset;
  }

 private:
  // A 64-bit length as size_t, refused (as truncation) if it cannot be one.
  std::size_t Checked(std::uint64_t n) const {
    if (n > remaining()) {
      throw core::IoError("truncated: needs " + std::to_string(n) + " bytes at byte " +
                          std::to_string(offset_) + ", " + std::to_string(remaining()) + " left");
    }
    return static_cast<std::size_t>(n);
  }

  std::span<const std::uint8_t> bytes_;
  std::endian order_;
  std::size_t offset_ = 0;
};

}  // namespace retrace::logs::internal
