#pragma once
// Reading MCAP files (https://mcap.dev/spec, major version 0), the container of rosbag2's
// default storage: the file is streamed record by record from the front, never read whole,
// and its messages are handed out in storage order (the messages of a chunk in the chunk's
// order), up to the Data End record. The summary section and the indexes are not needed for
// that and are not read. Chunks may be uncompressed, "lz4" (LZ4 frame format) or "zstd", and
// their CRC is checked when the writer stored one.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "logs/raw_message.hpp"

namespace retrace::logs {

/// The most bytes one record (a chunk's compressed or uncompressed records, a message) may
/// occupy in memory; a file declaring more is refused before anything is allocated.
inline constexpr std::uint64_t kMcapMaxRecordBytes = std::uint64_t{1} << 30;  // 1 GiB

/// The messages of an MCAP file. RawMessage::type is the channel's schema name
/// ("sensor_msgs/msg/LaserScan", empty for a channel without a schema), encoding the channel's
/// message encoding ("cdr"), topic its topic and log_time_ns the message's log time.
class McapReader final : public MessageSource {
 public:
  /// Opens `file` and checks its leading magic, its Header record and that it ends with a
  /// Footer record and the trailing magic (so that a truncated file is refused at once).
  /// Throws core::IoError "<file>: <what> at byte <offset>" if it cannot be opened or is not
  /// a complete MCAP file.
  explicit McapReader(const std::filesystem::path& file);
  ~McapReader() override;
  McapReader(const McapReader&) = delete;
  McapReader& operator=(const McapReader&) = delete;

  /// Throws core::IoError "<file>: <what> at byte <offset>" for a malformed record: truncated,
  /// longer than the file or than kMcapMaxRecordBytes, a Message on an unknown channel, a
  /// Channel of an unknown schema, a chunk that does not decompress to its declared size or
  /// fails its CRC, an unknown compression.
  bool Next(RawMessage& message) override;
  const std::string& name() const override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace retrace::logs
