#pragma once
// A ROS 1 bag built record by record, for tests of what Ros1BagWriter never writes: bad,
// unusual and cut-off bags (logs/internal/ros1_bag_format.hpp has the records).
//
//   testing::Ros1BagBuilder b;
//   b.Chunk({b.Connection(0, "/scan", "sensor_msgs/LaserScan"), b.Message(0, 5, scan)});
//   b.Index({{b.chunk_pos(0), 5, 5, {{0, 1}}}});
//   const auto bag = tmp.Write("a.bag", b.Text());

#include <algorithm>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "logs/internal/ros1_bag_format.hpp"
#include "logs/ros1_messages.hpp"

namespace retrace::testing {

class Ros1BagBuilder {
 public:
  using Bytes = std::vector<std::uint8_t>;

  /// A chunk info record's contents.
  struct Info {
    std::uint64_t pos = 0;
    std::int64_t start_ns = 0;
    std::int64_t end_ns = 0;
    std::map<std::uint32_t, std::uint32_t> counts;
  };

  /// The version line and a bag header with index_pos 0 (filled in by Index), padded as rosbag
  /// pads it. `version` other than "2.0" makes another format's line.
  explicit Ros1BagBuilder(std::string_view version = "2.0") {
    const std::string line = "#ROSBAG V" + std::string(version) + "\n";
    bytes_.assign(line.begin(), line.end());
    header_at_ = bytes_.size();
    Append(BagHeader(0, 0, 0));
  }

  /// A connection record; the md5sum defaults to the type's.
  static Bytes Connection(std::uint32_t id, std::string_view topic, std::string_view type,
                          std::string_view md5sum = {}) {
    logs::internal::Ros1FieldWriter header, fields;
    header.U8("op", 0x07).U32("conn", id).Text("topic", topic);
    fields.Text("topic", topic).Text("type", type);
    fields.Text("md5sum", md5sum.empty() ? logs::Ros1TypeMd5(type) : md5sum);
    fields.Text("message_definition", logs::Ros1MessageDefinition(type));
    return Record(header, fields.bytes());
  }

  /// A message data record at `time_ns`.
  static Bytes Message(std::uint32_t conn, std::int64_t time_ns,
                       std::span<const std::uint8_t> data) {
    logs::internal::Ros1FieldWriter header;
    header.U8("op", 0x02).U32("conn", conn).TimeNs("time", time_ns);
    return Record(header, data);
  }

  /// Appends a chunk record holding `records` as they are, its header naming `compression` and
  /// declaring `declared_size` uncompressed bytes (by default their size); returns its position.
  std::uint64_t Chunk(const std::vector<Bytes>& records, std::string_view compression = "none",
                      std::int64_t declared_size = -1) {
    Bytes data;
    for (const Bytes& r : records) data.insert(data.end(), r.begin(), r.end());
    const std::uint64_t pos = bytes_.size();
    logs::internal::Ros1FieldWriter header;
    header.U8("op", 0x05).Text("compression", compression);
    header.U32("size", static_cast<std::uint32_t>(declared_size < 0 ? data.size() : declared_size));
    Append(Record(header, data));
    chunks_.push_back(pos);
    return pos;
  }

  /// Appends any bytes (a record cut off, an index data record).
  void Append(std::span<const std::uint8_t> bytes) {
    bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
  }

  /// Appends the index (`connections` records and a chunk info record per `infos`) and points the
  /// bag header at it, with these counts (by default the records').
  void Index(const std::vector<Bytes>& connections, const std::vector<Info>& infos,
             std::int64_t conn_count = -1, std::int64_t chunk_count = -1) {
    const std::uint64_t index_pos = bytes_.size();
    for (const Bytes& c : connections) Append(c);
    for (const Info& info : infos) {
      logs::internal::Ros1FieldWriter header;
      header.U8("op", 0x06).U32("ver", 1).U64("chunk_pos", info.pos);
      header.TimeNs("start_time", info.start_ns).TimeNs("end_time", info.end_ns);
      header.U32("count", static_cast<std::uint32_t>(info.counts.size()));
      Bytes data;
      for (const auto& [conn, count] : info.counts) {
        logs::internal::AppendU32(data, conn);
        logs::internal::AppendU32(data, count);
      }
      Append(Record(header, data));
    }
    const Bytes header = BagHeader(
        index_pos, static_cast<std::uint32_t>(conn_count < 0 ? connections.size() : conn_count),
        static_cast<std::uint32_t>(chunk_count < 0 ? infos.size() : chunk_count));
    std::copy(header.begin(), header.end(), bytes_.begin() + static_cast<long>(header_at_));
  }

  std::uint64_t chunk_pos(std::size_t i) const { return chunks_.at(i); }
  const Bytes& bytes() const { return bytes_; }
  std::string Text() const { return std::string(bytes_.begin(), bytes_.end()); }

 private:
  static Bytes Record(const logs::internal::Ros1FieldWriter& header,
                      std::span<const std::uint8_t> data) {
    Bytes r;
    logs::internal::AppendRos1Record(r, header.bytes(), data);
    return r;
  }

  static Bytes BagHeader(std::uint64_t index_pos, std::uint32_t connections, std::uint32_t chunks) {
    logs::internal::Ros1FieldWriter header;
    header.U8("op", 0x03).U64("index_pos", index_pos).U32("conn_count", connections);
    header.U32("chunk_count", chunks);
    const Bytes padding(4096 - header.bytes().size(), ' ');
    return Record(header, padding);
  }

  Bytes bytes_;
  std::size_t header_at_ = 0;
  std::vector<std::uint64_t> chunks_;
};

}  // namespace retrace::testing
