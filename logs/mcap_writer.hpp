#pragma once
// Writing MCAP files (https://mcap.dev/spec) as rosbag2 writes them, readable by the official
// MCAP tools and by `ros2 bag`: the profile "ros2", one ros2msg Schema per message type, CDR
// messages in chunks of about 1 MiB (uncompressed, lz4 frames or zstd) each followed by its
// Message Index records, then Data End, a summary section (Schema, Channel, Statistics and
// Chunk Index records, grouped by opcode, with their Summary Offset records), the Footer with
// the summary's CRC, and the trailing magic. Messages are streamed out a chunk at a time.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

namespace retrace::logs {

/// Compression of the chunks of an MCAP file.
enum class McapCompression { kNone, kLz4, kZstd };

/// Uncompressed size (bytes) at which a chunk is closed.
inline constexpr std::size_t kMcapChunkBytes = std::size_t{1} << 20;

class McapWriter {
 public:
  /// Creates (or truncates) `file` and writes the magic and the Header record. Atomicity is the
  /// caller's business (write to a temporary name and rename). `chunk_bytes` is the
  /// uncompressed size at which a chunk is closed. Throws core::IoError if the file cannot be
  /// created.
  McapWriter(const std::filesystem::path& file, McapCompression compression,
             std::string profile = "ros2", std::size_t chunk_bytes = kMcapChunkBytes);
  /// Without Close() the file is left without its footer, so that readers refuse it as
  /// truncated.
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Adds a channel on `topic` for messages of the ROS type `type` ("sensor_msgs/msg/LaserScan")
  /// and returns its id. The first channel of a type adds a ros2msg Schema with
  /// RosMessageDefinition(type). Throws std::invalid_argument for a type without a known
  /// definition or past 65535 channels, core::IoError if writing fails.
  std::uint16_t AddChannel(std::string topic, std::string type,
                           std::string message_encoding = "cdr");

  /// Writes one message: log and publish time `log_time_ns` (ns since the epoch, >= 0), the
  /// sequence numbers counting per channel from 0. Throws std::invalid_argument for an unknown
  /// channel, core::IoError for a negative time or if writing fails.
  void Write(std::uint16_t channel, std::int64_t log_time_ns, std::span<const std::uint8_t> data);

  /// Writes the last chunk, Data End, the summary, the Footer and the trailing magic, and closes
  /// the file. Does nothing the second time. Throws core::IoError if writing fails.
  void Close();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace retrace::logs
