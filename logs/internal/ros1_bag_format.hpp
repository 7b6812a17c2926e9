#pragma once
// The ROS bag format 2.0 (http://wiki.ros.org/Bags/Format/2.0) that its reader and writer share.
// A bag is the line "#ROSBAG V2.0\n", then records: <header_len uint32><header><data_len
// uint32><data>, all integers little endian. A header is fields, each <field_len uint32>
// "name=value" (the value binary: op a uint8, conn and counts uint32, positions uint64, times
// uint32 sec and uint32 nsec). The records, by their "op" field:
//
//   0x03 bag header   index_pos (uint64: where the index starts; 0 until the bag is closed),
//                     conn_count, chunk_count; padded with spaces to 4096 bytes of header and data
//   0x05 chunk        compression ("none", "bz2", "lz4"), size (uncompressed); data: connection
//                     and message data records, compressed
//   0x04 index data   ver (1), conn, count; data: count × (time, uint32 offset of the message
//                     record in the uncompressed chunk). Follows its chunk, one per connection.
//   0x07 connection   conn, topic; data: a connection header (fields topic, type, md5sum,
//                     message_definition, optionally callerid, latching). Inside the chunk where
//                     the connection is first used, and again in the index.
//   0x02 message data conn, time; data: the serialized message. Inside chunks.
//   0x06 chunk info   ver (1), chunk_pos (uint64), start_time, end_time, count; data: count ×
//                     (conn, message count). In the index, after the connections.
//
// A bag closed by its recorder ends with the index: its connection records and a chunk info
// record per chunk, at index_pos. A recording that was cut off has index_pos 0, and the chunk it
// was writing keeps the sizes 0 its header was started with.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace retrace::logs::internal {

/// The first line of every ROS bag of format 2.0.
inline constexpr std::string_view kRos1BagMagic = "#ROSBAG V2.0\n";
/// The bag header record's header and data together fill this many bytes (its two length fields
/// come on top).
inline constexpr std::uint64_t kRos1BagHeaderBytes = 4096;
/// The two uint32 lengths of every record.
inline constexpr std::uint64_t kRos1RecordLengthBytes = 4;

enum class Ros1BagOp : std::uint8_t {
  kMessageDefinition = 0x01,  // format 1.2 only
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

/// "message data", "chunk", ... or "op 0x2a".
std::string_view Ros1BagOpName(std::uint8_t op);

/// The fields of one record header, or of a connection header: views into its bytes. Methods
/// throw core::IoError with a short reason ("no 'conn' field", "field 'time' of 3 bytes, not 8").
class Ros1FieldList {
 public:
  /// Checks that `bytes` is a sequence of whole fields, each with a '='.
  explicit Ros1FieldList(std::span<const std::uint8_t> bytes);

  /// The value of the first field named `name`, or nothing.
  std::optional<std::span<const std::uint8_t>> Find(std::string_view name) const;
  std::span<const std::uint8_t> Get(std::string_view name) const;  ///< required
  std::uint8_t Op() const;                                         ///< the required "op"
  std::uint32_t U32(std::string_view name) const;
  std::uint64_t U64(std::string_view name) const;
  /// A time field as ns since the epoch.
  std::int64_t TimeNs(std::string_view name) const;
  std::string_view Text(std::string_view name) const;

 private:
  std::span<const std::uint8_t> bytes_;
};

/// Appends fields to a record or connection header.
class Ros1FieldWriter {
 public:
  Ros1FieldWriter& Bytes(std::string_view name, std::span<const std::uint8_t> value);
  Ros1FieldWriter& Text(std::string_view name, std::string_view value);
  Ros1FieldWriter& U8(std::string_view name, std::uint8_t value);
  Ros1FieldWriter& U32(std::string_view name, std::uint32_t value);
  Ros1FieldWriter& U64(std::string_view name, std::uint64_t value);
  /// A time field from ns since the epoch (>= 0).
  Ros1FieldWriter& TimeNs(std::string_view name, std::int64_t ns);
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

/// Appends a uint32 in little endian.
void AppendU32(std::vector<std::uint8_t>& out, std::uint32_t value);

/// Appends a record: header length, header, data length, data.
void AppendRos1Record(std::vector<std::uint8_t>& out, std::span<const std::uint8_t> header,
                      std::span<const std::uint8_t> data);

}  // namespace retrace::logs::internal
