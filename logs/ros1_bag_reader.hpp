#pragma once
// Reading ROS 1 bags (format 2.0, what `rosbag record` has written since ROS C Turtle), without
// ROS: the bag header, then the index at its end (connection and chunk info records) says where
// the chunks are and what times they hold; chunks are uncompressed, bz2 or lz4 (roslz4 writes the
// LZ4 frame format). Messages are handed out in time order (the record time: when the recorder
// received the message) across chunks, also where chunks were stored out of order or overlap in
// time; equal times in storage order. A chunk is read and decompressed when its first message is
// due and dropped after its last, so that a bag is streamed, never held whole (chunks that overlap
// in time are held together, at most kRos1BagMaxChunkBytes of them).
//
// A bag that was never indexed (index_pos 0: a recording that was cut off, or a bag not closed)
// is read by scanning its chunks first, up to the first one that was never closed or is cut off,
// with a note (notes()). A bag whose header points at an index that is not there was cut short
// and is refused, naming the offsets. The index is checked against each chunk as it is read.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "logs/raw_message.hpp"

namespace retrace::logs {

/// The most bytes a chunk may hold uncompressed (a chunk declaring more is refused before anything
/// is allocated; rosbag's chunks are 768 KiB by default), and the most that the chunks overlapping
/// in time may hold together.
inline constexpr std::uint64_t kRos1BagMaxChunkBytes = std::uint64_t{1} << 30;  // 1 GiB

/// The messages of a ROS 1 bag. RawMessage::type is the connection's type
/// ("sensor_msgs/LaserScan"), md5sum its md5sum, encoding "ros1", topic the connection's topic and
/// log_time_ns the message record's time.
class Ros1BagReader final : public MessageSource {
 public:
  /// Opens `file`, reads its bag header and its index, or scans its chunks when it has none.
  /// Throws core::IoError "<file>: <what> at byte <offset>" if it cannot be opened, is not a ROS
  /// bag of format 2.0, or its header or index is cut off or malformed.
  explicit Ros1BagReader(const std::filesystem::path& file);
  ~Ros1BagReader() override;
  Ros1BagReader(const Ros1BagReader&) = delete;
  Ros1BagReader& operator=(const Ros1BagReader&) = delete;

  /// Throws core::IoError "<file>: <what> at byte <offset>" for a malformed chunk: cut off, not
  /// decompressing to its declared size, a record running past its end, a message on an unknown
  /// connection, or a chunk that disagrees with its chunk info; and for chunks overlapping in time
  /// that would hold more than kRos1BagMaxChunkBytes at once.
  bool Next(RawMessage& message) override;
  const std::string& name() const override;
  std::vector<std::string> notes() const override;

  /// False for a bag read by scanning its chunks (it has no index).
  bool indexed() const;
  /// The chunks holding messages.
  std::size_t chunk_count() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace retrace::logs
