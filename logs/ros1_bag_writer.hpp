#pragma once
// Writing ROS 1 bags (format 2.0) as `rosbag record` writes them, readable by rosbag, rqt_bag and
// the ROS 1 libraries: the version line, the bag header (padded to 4 KiB), chunks of about
// 768 KiB (uncompressed, bz2 or lz4 in roslz4's framing) each followed by its index data records,
// a connection record inside the chunk where its topic is first written, and at the end the index:
// every connection record and a chunk info record per chunk, which the bag header then points at.
// Messages are streamed out a chunk at a time.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

namespace retrace::logs {

/// Compression of the chunks of a ROS 1 bag.
enum class Ros1BagCompression { kNone, kBz2, kLz4 };

/// Uncompressed size (bytes) at which a chunk is closed: rosbag's default chunk threshold.
inline constexpr std::size_t kRos1BagChunkBytes = 768 * 1024;

class Ros1BagWriter {
 public:
  /// Creates (or truncates) `file` and writes the version line and the bag header. Atomicity is
  /// the caller's business (write to a temporary name and rename). `chunk_bytes` is the
  /// uncompressed size at which a chunk is closed. Throws core::IoError if the file cannot be
  /// created.
  Ros1BagWriter(const std::filesystem::path& file, Ros1BagCompression compression,
                std::size_t chunk_bytes = kRos1BagChunkBytes);
  /// Without Close() the bag is left as a recording that was cut off: the chunks written so far,
  /// no index (the bag header's index_pos stays 0), the messages of the open chunk lost.
  ~Ros1BagWriter();
  Ros1BagWriter(const Ros1BagWriter&) = delete;
  Ros1BagWriter& operator=(const Ros1BagWriter&) = delete;

  /// Adds a connection on `topic` for messages of the ROS 1 type `type`, one of those of
  /// logs/ros1_messages.hpp ("sensor_msgs/LaserScan"), and returns its id. Its connection header
  /// holds the type's md5sum and definition (Ros1TypeMd5, Ros1MessageDefinition). Throws
  /// std::invalid_argument for another type.
  std::uint32_t AddConnection(std::string topic, std::string type);

  /// Writes one message (ROS 1 serialization) with the record time `log_time_ns` (ns since the
  /// epoch). Throws std::invalid_argument for an unknown connection, core::IoError for a time
  /// outside ROS 1 time (uint32 seconds) or if writing fails.
  void Write(std::uint32_t connection, std::int64_t log_time_ns,
             std::span<const std::uint8_t> data);

  /// Writes the last chunk and the index, points the bag header at it and closes the file. Does
  /// nothing the second time. Throws core::IoError if writing fails.
  void Close();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace retrace::logs
