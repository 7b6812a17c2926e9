#pragma once
// OMG CDR as ROS 2 serializes its messages (plain CDR, XCDR version 1, as eProsima Fast-CDR
// writes it): a 4-byte encapsulation header (0x00 0x01 little endian, 0x00 0x00 big endian, then
// two option bytes), then the fields in declaration order, each primitive aligned to its own size
// (at most 8) counted from the first byte after the header. A string is a uint32 length that
// counts a terminating NUL, the bytes and the NUL; a sequence is a uint32 element count and the
// elements; a fixed-size array is its elements alone; an empty sequence adds no padding.
// The reader never reads past its buffer and checks every length and count against the bytes
// left before it allocates anything.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "logs/internal/byte_reader.hpp"

namespace retrace::logs {

/// Reads the fields of one CDR-serialized message in order.
/// Every method throws core::IoError with a short reason ("truncated: needs 8 bytes at byte 12,
/// 3 left", counted from the byte after the encapsulation header) on malformed input; the caller
/// says which message it was.
class CdrReader {
 public:
  /// `message` is the serialized message including its encapsulation header. Throws
  /// core::IoError if it is shorter than the header or its encapsulation is anything but plain
  /// CDR (little or big endian): parameter-list and XCDR2 encodings are refused.
  explicit CdrReader(std::span<const std::uint8_t> message);

  bool ReadBool();  ///< a byte that must be 0 or 1
  /// One number, aligned to its size: T is one of the ROS 2 primitives int8_t ... uint64_t,
  /// float (float32) and double (float64); ROS `byte` and `char` are uint8_t.
  template <typename T>
  T Read();
  /// A string; the terminating NUL is dropped (a length of 0 reads as "").
  std::string ReadString();

  /// The element count of a sequence, refused unless `count * min_element_bytes` bytes are
  /// left (min_element_bytes: the smallest serialized size of one element, at least 1).
  std::uint32_t ReadSequenceLength(std::size_t min_element_bytes);
  std::vector<float> ReadFloat32Sequence();
  void SkipFloat32Sequence();
  std::vector<double> ReadFloat64Sequence();
  /// A fixed-size float64 array (no count), e.g. a covariance: out.size() values.
  void ReadFloat64Array(std::span<double> out);
  /// Skips a fixed-size float64 array of `n` values.
  void SkipFloat64Array(std::size_t n);

  std::endian byte_order() const { return reader_.order(); }
  /// Bytes read after the encapsulation header.
  std::size_t offset() const { return reader_.offset(); }
  /// Bytes left (trailing padding included).
  std::size_t remaining() const { return reader_.remaining(); }

 private:
  void Align(std::size_t n);

  internal::ByteReader reader_;
};

/// Writes a CDR message in little endian with the header 00 01 00 00, aligned as the reader
/// expects. Never throws except std::bad_alloc.
class CdrWriter {
 public:
  CdrWriter();

  void WriteBool(bool v);
  /// One number, aligned to its size (the types of Read).
  template <typename T>
  void Write(T v);
  void WriteString(std::string_view s);
  void WriteSequenceLength(std::uint32_t count);
  void WriteFloat32Sequence(std::span<const float> values);
  void WriteFloat64Sequence(std::span<const double> values);
  /// A fixed-size float64 array (no count).
  void WriteFloat64Array(std::span<const double> values);

  /// The message so far, header included.
  const std::vector<std::uint8_t>& data() const { return data_; }
  /// Hands over the message.
  std::vector<std::uint8_t> Take() { return std::move(data_); }

 private:
  void Align(std::size_t n);

  std::vector<std::uint8_t> data_;
};

}  // namespace retrace::logs
