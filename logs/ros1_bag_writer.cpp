#include "logs/ros1_bag_writer.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "logs/internal/compression.hpp"
#include "logs/internal/file_sink.hpp"
#include "logs/internal/ros1_bag_format.hpp"
#include "logs/ros1_messages.hpp"

namespace retrace::logs {
namespace {

using internal::AppendRos1Record;
using internal::AppendU32;
using internal::kRos1BagHeaderBytes;
using internal::kRos1BagMagic;
using internal::Ros1BagOp;
using internal::Ros1FieldWriter;

using Buffer = std::vector<std::uint8_t>;

constexpr std::int64_t kNsPerSecond = 1'000'000'000;
// The latest record time ROS 1 can hold (uint32 seconds).
constexpr std::int64_t kLatestNs =
    (static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max()) + 1) * kNsPerSecond - 1;

struct BagConnection {
  std::string topic;
  std::string type;
  bool written = false;  // its connection record is in a chunk
};

struct ChunkSummary {
  std::uint64_t pos = 0;
  std::int64_t start_ns = 0;
  std::int64_t end_ns = 0;
  std::map<std::uint32_t, std::uint32_t> counts;
};

// A chunk's compression field, by Ros1BagCompression.
std::string_view Ros1CompressionName(Ros1BagCompression c) {
  static constexpr std::array<std::string_view, 3> kNames{"none", "bz2", "lz4"};
  return kNames[static_cast<std::size_t>(c)];
}

// The bag header record: the index's position and counts, padded to kRos1BagHeaderBytes.
Buffer BagHeaderRecord(std::uint64_t index_pos, std::uint32_t connections, std::uint32_t chunks) {
  Ros1FieldWriter header;
  header.U8("op", static_cast<std::uint8_t>(Ros1BagOp::kBagHeader))
      .U64("index_pos", index_pos)
      .U32("conn_count", connections)
      .U32("chunk_count", chunks);
  const Buffer padding(kRos1BagHeaderBytes - header.bytes().size(), ' ');
  Buffer record;
  AppendRos1Record(record, header.bytes(), padding);
  return record;
}

// A connection record: its header and, as data, the connection header rosbag writes.
Buffer ConnectionRecord(std::uint32_t id, const BagConnection& c) {
  Ros1FieldWriter header;
  header.U8("op", static_cast<std::uint8_t>(Ros1BagOp::kConnection))
      .U32("conn", id)
      .Text("topic", c.topic);
  Ros1FieldWriter fields;
  fields.Text("topic", c.topic)
      .Text("type", c.type)
      .Text("md5sum", Ros1TypeMd5(c.type))
      .Text("message_definition", Ros1MessageDefinition(c.type));
  Buffer record;
  AppendRos1Record(record, header.bytes(), fields.bytes());
  return record;
}

Buffer ChunkInfoRecord(const ChunkSummary& chunk) {
  Ros1FieldWriter header;
  header.U8("op", static_cast<std::uint8_t>(Ros1BagOp::kChunkInfo))
      .U32("ver", 1)
      .U64("chunk_pos", chunk.pos)
      .TimeNs("start_time", chunk.start_ns)
      .TimeNs("end_time", chunk.end_ns)
      .U32("count", static_cast<std::uint32_t>(chunk.counts.size()));
  Buffer data;
  for (const auto& [conn, count] : chunk.counts) {
    AppendU32(data, conn);
    AppendU32(data, count);
  }
  Buffer record;
  AppendRos1Record(record, header.bytes(), data);
  return record;
}

}  // namespace

struct Ros1BagWriter::State {
  explicit State(const std::filesystem::path& path) : file(path) {}

  internal::FileSink file;
  Ros1BagCompression compression = Ros1BagCompression::kNone;
  std::size_t chunk_bytes = kRos1BagChunkBytes;
  bool closed = false;
  std::vector<BagConnection> connections;  // the id is the index

  // The chunk being filled: its records and, per connection, (time, offset) of its messages.
  Buffer chunk;
  std::map<std::uint32_t, std::vector<std::pair<std::int64_t, std::uint32_t>>> chunk_index;
  ChunkSummary current;
  std::vector<ChunkSummary> chunks;  // written

  // The chunk record, then one index data record per connection with messages in it.
  void FlushChunk() {
    if (chunk.empty()) return;
    current.pos = file.pos();
    Buffer compressed;
    std::span<const std::uint8_t> stored = chunk;
    if (compression == Ros1BagCompression::kBz2) {
      compressed = internal::CompressBz2(chunk);
      stored = compressed;
    } else if (compression == Ros1BagCompression::kLz4) {
      compressed = internal::CompressLz4(chunk, {.roslz4 = true});
      stored = compressed;
    }
    Ros1FieldWriter header;
    header.U8("op", static_cast<std::uint8_t>(Ros1BagOp::kChunk))
        .Text("compression", Ros1CompressionName(compression))
        .U32("size", static_cast<std::uint32_t>(chunk.size()));
    Buffer head;
    AppendU32(head, static_cast<std::uint32_t>(header.bytes().size()));
    head.insert(head.end(), header.bytes().begin(), header.bytes().end());
    AppendU32(head, static_cast<std::uint32_t>(stored.size()));
    file.Put(head);
    file.Put(stored);
    for (auto& [conn, entries] : chunk_index) file.Put(IndexDataRecord(conn, entries));
    chunks.push_back(std::move(current));
    current = {};
    chunk.clear();
    chunk_index.clear();
  }

  // Sorted by time, as rosbag indexes them; offsets keep ties in storage order.
  static Buffer IndexDataRecord(std::uint32_t conn,
                                std::vector<std::pair<std::int64_t, std::uint32_t>>& entries) {
    std::stable_sort(entries.begin(), entries.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    Ros1FieldWriter header;
    header.U8("op", static_cast<std::uint8_t>(Ros1BagOp::kIndexData))
        .U32("ver", 1)
        .U32("conn", conn)
        .U32("count", static_cast<std::uint32_t>(entries.size()));
    Buffer data;
    for (const auto& [ns, offset] : entries) {
      AppendU32(data, static_cast<std::uint32_t>(ns / kNsPerSecond));
      AppendU32(data, static_cast<std::uint32_t>(ns % kNsPerSecond));
      AppendU32(data, offset);
    }
    Buffer record;
    AppendRos1Record(record, header.bytes(), data);
    return record;
  }
};

Ros1BagWriter::Ros1BagWriter(const std::filesystem::path& file, Ros1BagCompression compression,
                             std::size_t chunk_bytes)
    : state_(std::make_unique<State>(file)) {
  State& s = *state_;
  s.compression = compression;
  s.chunk_bytes = std::max<std::size_t>(chunk_bytes, 1);
  s.file.Put({reinterpret_cast<const std::uint8_t*>(kRos1BagMagic.data()), kRos1BagMagic.size()});
  s.file.Put(BagHeaderRecord(0, 0, 0));
}

Ros1BagWriter::~Ros1BagWriter() = default;

std::uint32_t Ros1BagWriter::AddConnection(std::string topic, std::string type) {
  State& s = *state_;
  if (s.closed) throw std::logic_error("Ros1BagWriter::AddConnection after Close");
  if (Ros1MessageDefinition(type).empty()) {
    throw std::invalid_argument("Ros1BagWriter: no message definition for type '" + type + "'");
  }
  s.connections.push_back({std::move(topic), std::move(type), false});
  return static_cast<std::uint32_t>(s.connections.size() - 1);
}

void Ros1BagWriter::Write(std::uint32_t connection, std::int64_t log_time_ns,
                          std::span<const std::uint8_t> data) {
  State& s = *state_;
  if (s.closed) throw std::logic_error("Ros1BagWriter::Write after Close");
  if (connection >= s.connections.size()) {
    throw std::invalid_argument("Ros1BagWriter: unknown connection " + std::to_string(connection));
  }
  if (log_time_ns < 0 || log_time_ns > kLatestNs) {
    throw core::IoError(s.file.name() + ": record time " + std::to_string(log_time_ns) +
                        " ns is outside ROS 1 time (uint32 seconds since the epoch)");
  }
  BagConnection& c = s.connections[connection];
  if (!c.written) {
    const Buffer record = ConnectionRecord(connection, c);
    s.chunk.insert(s.chunk.end(), record.begin(), record.end());
    c.written = true;
  }
  s.chunk_index[connection].emplace_back(log_time_ns, static_cast<std::uint32_t>(s.chunk.size()));
  Ros1FieldWriter header;
  header.U8("op", static_cast<std::uint8_t>(Ros1BagOp::kMessageData))
      .U32("conn", connection)
      .TimeNs("time", log_time_ns);
  AppendRos1Record(s.chunk, header.bytes(), data);
  ChunkSummary& chunk = s.current;
  const bool first = chunk.counts.empty();
  chunk.start_ns = first ? log_time_ns : std::min(chunk.start_ns, log_time_ns);
  chunk.end_ns = first ? log_time_ns : std::max(chunk.end_ns, log_time_ns);
  ++chunk.counts[connection];
  if (s.chunk.size() >= s.chunk_bytes) s.FlushChunk();
}

void Ros1BagWriter::Close() {
  State& s = *state_;
  if (s.closed) return;
  s.FlushChunk();
  const std::uint64_t index_pos = s.file.pos();
  std::uint32_t written = 0;
  for (std::uint32_t id = 0; id < s.connections.size(); ++id) {
    if (!s.connections[id].written) continue;  // rosbag lists only connections with messages
    s.file.Put(ConnectionRecord(id, s.connections[id]));
    ++written;
  }
  for (const ChunkSummary& chunk : s.chunks) s.file.Put(ChunkInfoRecord(chunk));
  s.file.Patch(kRos1BagMagic.size(),
               BagHeaderRecord(index_pos, written, static_cast<std::uint32_t>(s.chunks.size())));
  s.file.Finish();
  s.closed = true;
}

}  // namespace retrace::logs
