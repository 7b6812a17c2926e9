#pragma once
// The records of a ROS 1 bag file (logs/internal/ros1_bag_format.hpp) read by position: the bag
// header, the index (connections and chunk infos) or, for a bag that was never indexed, the same
// rebuilt by scanning its chunks, and one chunk's messages. logs/ros1_bag_reader.hpp puts them in
// time order. Every size read from the file is checked against what is left of it before
// anything is allocated; every error is a core::IoError "<file>: <what> at byte <offset>".

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "logs/ros1_bag_reader.hpp"

namespace retrace::logs::internal {

/// A connection record: a topic's messages of one type.
struct Ros1Connection {
  std::string topic;
  std::string type;    ///< "sensor_msgs/LaserScan"
  std::string md5sum;  ///< of the type's definition
};

/// Where a chunk is and what it holds.
struct Ros1ChunkInfo {
  std::uint64_t pos = 0;      ///< of the chunk record
  std::int64_t start_ns = 0;  ///< the earliest message time in it (ns since the epoch)
  std::int64_t end_ns = 0;    ///< the latest
  std::map<std::uint32_t, std::uint32_t> counts;  ///< messages per connection id
};

/// A message data record of a loaded chunk.
struct Ros1MessageEntry {
  std::int64_t time_ns = 0;  ///< the record's time (when the recorder received it)
  std::uint32_t conn = 0;
  std::uint32_t offset = 0;  ///< of the message's serialized bytes in the uncompressed chunk
  std::uint32_t size = 0;
};

/// What the bag holds: from its index, or rebuilt by scanning its chunks.
struct Ros1BagLayout {
  std::map<std::uint32_t, Ros1Connection> connections;
  std::vector<Ros1ChunkInfo> chunks;  ///< in storage order
  bool indexed = true;
  std::vector<std::string> notes;  ///< a bag read without its index says so
};

/// The chunk info of a loaded chunk at `pos`: its messages' times and counts.
Ros1ChunkInfo SummarizeChunk(std::uint64_t pos, const std::vector<Ros1MessageEntry>& messages);

class Ros1BagFile {
 public:
  /// Opens `file` and reads its version line and bag header record. Throws core::IoError for a
  /// missing file, another format or version, or a bag header that is cut off or malformed.
  explicit Ros1BagFile(const std::filesystem::path& file);

  const std::string& name() const { return name_; }

  /// The connections and chunks of the bag: its index, checked against the file (a truncated
  /// bag, whose header points at an index past its end, is refused naming the offsets), or,
  /// for a bag without one (index_pos 0: a recording cut off), rebuilt by reading every chunk,
  /// up to the first one that was cut off, never closed or cannot be read, with notes saying so.
  Ros1BagLayout ReadLayout();

  /// Reads and decompresses the chunk record at `pos` into `data` and lists its message records
  /// in `messages` (in storage order). Connection records in it that `connections` lacks are
  /// added; a message on a connection no record declared is refused.
  void LoadChunk(std::uint64_t pos, std::map<std::uint32_t, Ros1Connection>& connections,
                 std::vector<std::uint8_t>& data, std::vector<Ros1MessageEntry>& messages);

  /// Refuses a loaded chunk that disagrees with its chunk info from the index: a message time
  /// outside [start_ns, end_ns], another count of messages on a connection.
  void CheckChunk(const Ros1ChunkInfo& info, const std::vector<Ros1MessageEntry>& messages) const;

 private:
  struct Record;
  Record ReadRecord(std::uint64_t offset, bool with_data);
  void ReadAt(std::uint64_t offset, std::uint8_t* out, std::uint64_t n);
  Ros1BagLayout ReadIndex();
  Ros1BagLayout ScanChunks();
  void ReadChunkData(const Record& chunk, std::string_view compression, std::uint64_t size,
                     std::vector<std::uint8_t>& data);
  void ListChunkRecords(std::uint64_t pos, std::span<const std::uint8_t> records,
                        std::map<std::uint32_t, Ros1Connection>& connections,
                        std::vector<Ros1MessageEntry>& messages) const;
  [[noreturn]] void Fail(const std::string& what, std::uint64_t offset) const;

  std::string name_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint64_t stream_pos_ = 0;
  std::uint64_t first_record_ = 0;  ///< after the bag header
  std::uint64_t index_pos_ = 0;
  std::uint32_t conn_count_ = 0;
  std::uint32_t chunk_count_ = 0;
  std::vector<std::uint8_t> compressed_;  ///< a compressed chunk's data, reused
};

}  // namespace retrace::logs::internal
