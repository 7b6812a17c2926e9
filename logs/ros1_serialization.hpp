#pragma once
// ROS 1 serialization, as roscpp and genpy write messages: the fields in declaration order, little
// endian, without alignment or padding. A string is a uint32 byte count and the bytes (no
// terminating NUL); a variable-length array is a uint32 element count and the elements; a
// fixed-size array is its elements alone; time and duration are uint32 sec (int32 for duration)
// and uint32 nsec. std_msgs/Header is uint32 seq, time stamp, string frame_id.
// The reader never reads past its buffer and checks every length and count against the bytes
// left before it allocates anything.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "logs/internal/byte_reader.hpp"

namespace retrace::logs {

/// ROS 1 `time`: seconds and nanoseconds since the epoch.
struct Ros1Time {
  std::uint32_t sec = 0;
  std::uint32_t nsec = 0;
};

/// sec + nsec·1e-9 (s).
double Ros1StampSeconds(Ros1Time t);

/// The nearest Ros1Time to `stamp` (s; nsec in [0, 1e9)). Throws core::IoError for a non-finite
/// stamp or one outside the uint32 seconds of ROS 1 time (before 1970 or after 2106).
Ros1Time ToRos1Time(double stamp);

/// Reads the fields of one ROS 1 message in order. Every method throws core::IoError with a short
/// reason ("truncated: needs 8 bytes at byte 12, 3 left"); the caller says which message it was.
class Ros1Reader {
 public:
  explicit Ros1Reader(std::span<const std::uint8_t> message) : reader_(message) {}

  /// One number: T is one of the ROS primitives int8_t ... uint64_t, float (float32) and double
  /// (float64); ROS `byte`, `char` and `bool` are uint8_t.
  template <typename T>
  T Read() {
    return reader_.Read<T>();
  }
  Ros1Time ReadTime();
  std::string ReadString();
  // A variable-length array T[] is a "sequence", as ROS 2's CdrReader calls it: the two readers
  // share their names (logs/internal/ros_fields.hpp reads the messages of both through them).

  /// The element count of a sequence, refused unless `count * min_element_bytes` bytes are left
  /// (min_element_bytes: the smallest serialized size of one element, at least 1).
  std::uint32_t ReadSequenceLength(std::size_t min_element_bytes);
  std::vector<float> ReadFloat32Sequence();
  void SkipFloat32Sequence();
  /// Skips a fixed-size float64 array of `n` values.
  void SkipFloat64Array(std::size_t n) { reader_.Skip(n * sizeof(double)); }
  /// Skips `n` bytes.
  void Skip(std::size_t n) { reader_.Skip(n); }

  /// Bytes read so far.
  std::size_t offset() const { return reader_.offset(); }
  /// Bytes left.
  std::size_t remaining() const { return reader_.remaining(); }

 private:
  internal::ByteReader reader_;
};

/// Writes a ROS 1 message as the reader expects it. Never throws except std::bad_alloc.
class Ros1Writer {
 public:
  /// One number (the types of Ros1Reader::Read), little endian.
  template <typename T>
  void Write(T v);
  void WriteTime(Ros1Time t);
  void WriteString(std::string_view s);
  void WriteSequenceLength(std::uint32_t count);
  void WriteFloat32Sequence(std::span<const float> values);
  /// A fixed-size float64 array (no count).
  void WriteFloat64Array(std::span<const double> values);

  /// Hands over the message.
  std::vector<std::uint8_t> Take() { return std::move(data_); }

 private:
  std::vector<std::uint8_t> data_;
};

}  // namespace retrace::logs
