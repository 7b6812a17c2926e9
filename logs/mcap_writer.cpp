#include "logs/mcap_writer.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "logs/internal/compression.hpp"
#include "logs/internal/file_sink.hpp"
#include "logs/internal/mcap_format.hpp"
#include "logs/ros_messages.hpp"

namespace retrace::logs {
namespace {

using internal::kMcapMagic;
using internal::McapOp;

// GCC 12 at -O3 sees impossible sizes in the inlined vector growth below (a known false
// positive of -Wstringop-overflow); clang and the sanitizer builds check the same code.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif

// Little-endian serialization of MCAP record fields into a byte buffer.
class Bytes {
 public:
  template <typename T>
  Bytes& Int(T v) {
    static_assert(std::is_integral_v<T>);
    std::array<std::uint8_t, sizeof(T)> bytes{};
    for (std::size_t i = 0; i < sizeof(T); ++i)
      bytes[i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(v) >> (8 * i));
    Append(bytes.data(), bytes.size());
    return *this;
  }
  Bytes& U8(std::uint8_t v) { return Int(v); }
  Bytes& U16(std::uint16_t v) { return Int(v); }
  Bytes& U32(std::uint32_t v) { return Int(v); }
  Bytes& U64(std::uint64_t v) { return Int(v); }
  Bytes& Raw(std::span<const std::uint8_t> b) {
    Append(b.data(), b.size());
    return *this;
  }
  /// uint32 length and the bytes.
  Bytes& Str(std::string_view s) {
    U32(static_cast<std::uint32_t>(s.size()));
    Append(s.data(), s.size());
    return *this;
  }
  /// A record: opcode, uint64 length, `body`.
  Bytes& Record(McapOp op, const Bytes& body) {
    U8(static_cast<std::uint8_t>(op));
    U64(body.size());
    return Raw(body.data_);
  }
  std::size_t size() const { return data_.size(); }
  void Append(const void* bytes, std::size_t n) {
    const auto* first = static_cast<const std::uint8_t*>(bytes);
    data_.insert(data_.end(), first, first + n);
  }
  const std::vector<std::uint8_t>& data() const { return data_; }
  void clear() { data_.clear(); }

 private:
  std::vector<std::uint8_t> data_;
};

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

struct Schema {
  std::uint16_t id = 0;
  std::string name;
  std::string data;
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string encoding;
  std::map<std::string, std::string> metadata;
  std::uint32_t sequence = 0;
  std::uint64_t message_count = 0;
};

struct ChunkIndex {
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  std::uint64_t chunk_offset = 0;
  std::uint64_t chunk_length = 0;
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
};

Bytes SchemaRecord(const Schema& s) {
  Bytes b;
  b.U16(s.id).Str(s.name).Str("ros2msg").Str(s.data);
  return b;
}

Bytes ChannelRecord(const Channel& c) {
  Bytes metadata;
  for (const auto& [key, value] : c.metadata) metadata.Str(key).Str(value);
  Bytes b;
  b.U16(c.id).U16(c.schema_id).Str(c.topic).Str(c.encoding);
  b.U32(static_cast<std::uint32_t>(metadata.size())).Raw(metadata.data());
  return b;
}

// One group of the summary section: its opcode, and where it lies in the file (bytes).
struct SummaryGroup {
  McapOp op;
  std::uint64_t start;
  std::uint64_t length;
};

// A chunk's compression field, by McapCompression.
std::string_view CompressionName(McapCompression c) {
  static constexpr std::array<std::string_view, 3> kNames{"", "lz4", "zstd"};
  return kNames[static_cast<std::size_t>(c)];
}

// The body of the Chunk Index record of chunk `c`, compressed with `compression`.
Bytes ChunkIndexRecord(const ChunkIndex& c, McapCompression compression) {
  Bytes offsets;
  for (const auto& [channel, offset] : c.message_index_offsets) offsets.U16(channel).U64(offset);
  Bytes b;
  b.U64(c.start_time).U64(c.end_time).U64(c.chunk_offset).U64(c.chunk_length);
  b.U32(static_cast<std::uint32_t>(offsets.size())).Raw(offsets.data());
  b.U64(c.message_index_length).Str(CompressionName(compression));
  b.U64(c.compressed_size).U64(c.uncompressed_size);
  return b;
}

}  // namespace

struct McapWriter::State {
  explicit State(const std::filesystem::path& path) : file(path) {}

  internal::FileSink file;
  McapCompression compression = McapCompression::kNone;
  std::string profile;
  std::size_t chunk_bytes = kMcapChunkBytes;
  bool closed = false;

  std::vector<Schema> schemas;
  std::map<std::string, std::uint16_t, std::less<>> schema_of_type;
  std::vector<Channel> channels;  // channel id = index + 1

  // The chunk being filled: its records and, per channel, (log time, offset) of its messages.
  Bytes chunk;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index;
  std::uint64_t chunk_start_time = 0;
  std::uint64_t chunk_end_time = 0;
  bool chunk_has_messages = false;

  std::vector<ChunkIndex> chunk_indexes;
  std::uint64_t message_count = 0;
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;

  void FlushChunk() {
    if (chunk.size() == 0) return;
    const std::span<const std::uint8_t> records = chunk.data();
    const auto crc = static_cast<std::uint32_t>(crc32_z(0, records.data(), records.size()));
    std::vector<std::uint8_t> compressed;
    std::span<const std::uint8_t> stored = records;
    if (compression == McapCompression::kZstd) {
      compressed = internal::CompressZstd(records);
      stored = compressed;
    } else if (compression == McapCompression::kLz4) {
      compressed = internal::CompressLz4(records, {.content_size = true});
      stored = compressed;
    }
    ChunkIndex index;
    index.start_time = chunk_has_messages ? chunk_start_time : 0;
    index.end_time = chunk_has_messages ? chunk_end_time : 0;
    index.chunk_offset = file.pos();
    index.compressed_size = stored.size();
    index.uncompressed_size = records.size();

    // The Chunk record, its records streamed out without another copy.
    Bytes head;
    head.U64(index.start_time).U64(index.end_time).U64(records.size()).U32(crc);
    head.Str(CompressionName(compression)).U64(stored.size());
    Bytes prefix;
    prefix.U8(static_cast<std::uint8_t>(McapOp::kChunk)).U64(head.size() + stored.size());
    file.Put(prefix.data());
    file.Put(head.data());
    file.Put(stored);
    index.chunk_length = file.pos() - index.chunk_offset;

    // One Message Index record per channel with messages in the chunk.
    const std::uint64_t indexes_start = file.pos();
    for (auto& [channel, entries] : chunk_index) {
      // Sorted by log time, as the MCAP libraries index them; offsets keep ties in file order.
      std::stable_sort(entries.begin(), entries.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      Bytes body;
      body.U16(channel).U32(static_cast<std::uint32_t>(entries.size() * 16));
      for (const auto& [time, offset] : entries) body.U64(time).U64(offset);
      Bytes record;
      record.Record(McapOp::kMessageIndex, body);
      index.message_index_offsets[channel] = file.pos();
      file.Put(record.data());
    }
    index.message_index_length = file.pos() - indexes_start;
    chunk_indexes.push_back(std::move(index));

    chunk.clear();
    chunk_index.clear();
    chunk_has_messages = false;
  }

  // The body of the Statistics record: the counts of messages, schemas, channels and chunks,
  // the time span, and the messages per channel.
  Bytes StatisticsBody() const {
    Bytes counts;
    for (const Channel& c : channels) counts.U16(c.id).U64(c.message_count);
    Bytes stats;
    stats.U64(message_count)
        .U16(static_cast<std::uint16_t>(schemas.size()))
        .U32(static_cast<std::uint32_t>(channels.size()))
        .U32(0)  // attachments
        .U32(0)  // metadata
        .U32(static_cast<std::uint32_t>(chunk_indexes.size()))
        .U64(message_count > 0 ? start_time : 0)
        .U64(message_count > 0 ? end_time : 0)
        .U32(static_cast<std::uint32_t>(counts.size()))
        .Raw(counts.data());
    return stats;
  }

  // The summary section (to be written at pos()), grouped by opcode, then the offsets of its
  // groups, the Footer (its CRC covering everything before it from the summary on) and the
  // trailing magic.
  Bytes SummaryAndFooter() const {
    const std::uint64_t summary_start = file.pos();
    Bytes summary;
    std::vector<SummaryGroup> groups;
    const auto group = [&](McapOp op, const auto& write_records) {
      const std::size_t before = summary.size();
      write_records();
      if (summary.size() > before)
        groups.push_back({op, summary_start + before, summary.size() - before});
    };
    group(McapOp::kSchema, [&] {
      for (const Schema& schema : schemas) summary.Record(McapOp::kSchema, SchemaRecord(schema));
    });
    group(McapOp::kChannel, [&] {
      for (const Channel& c : channels) summary.Record(McapOp::kChannel, ChannelRecord(c));
    });
    group(McapOp::kStatistics, [&] { summary.Record(McapOp::kStatistics, StatisticsBody()); });
    group(McapOp::kChunkIndex, [&] {
      for (const ChunkIndex& c : chunk_indexes) {
        summary.Record(McapOp::kChunkIndex, ChunkIndexRecord(c, compression));
      }
    });
    const std::uint64_t summary_offset_start = summary_start + summary.size();
    for (const SummaryGroup& g : groups) {
      Bytes b;
      b.U8(static_cast<std::uint8_t>(g.op)).U64(g.start).U64(g.length);
      summary.Record(McapOp::kSummaryOffset, b);
    }
    // The Footer; its CRC covers the summary up to and including summary_offset_start.
    summary.U8(static_cast<std::uint8_t>(McapOp::kFooter)).U64(internal::kMcapFooterBodyBytes);
    summary.U64(summary_start).U64(summary_offset_start);
    const auto crc =
        static_cast<std::uint32_t>(crc32_z(0, summary.data().data(), summary.data().size()));
    summary.U32(crc);
    summary.Raw(kMcapMagic);
    return summary;
  }
};

McapWriter::McapWriter(const std::filesystem::path& file, McapCompression compression,
                       std::string profile, std::size_t chunk_bytes)
    : state_(std::make_unique<State>(file)) {
  State& s = *state_;
  s.compression = compression;
  s.profile = std::move(profile);
  s.chunk_bytes = std::max<std::size_t>(chunk_bytes, 1);
  s.file.Put(kMcapMagic);
  Bytes header;
  header.Str(s.profile).Str("retrace");
  Bytes record;
  record.Record(McapOp::kHeader, header);
  s.file.Put(record.data());
}

McapWriter::~McapWriter() = default;

std::uint16_t McapWriter::AddChannel(std::string topic, std::string type,
                                     std::string message_encoding) {
  State& s = *state_;
  if (s.closed) throw std::logic_error("McapWriter::AddChannel after Close");
  if (s.channels.size() >= std::numeric_limits<std::uint16_t>::max()) {
    throw std::invalid_argument("McapWriter: more than 65535 channels");
  }
  std::uint16_t schema_id = 0;
  if (const auto it = s.schema_of_type.find(type); it != s.schema_of_type.end()) {
    schema_id = it->second;
  } else {
    const std::string_view definition = RosMessageDefinition(type);
    if (definition.empty()) {
      throw std::invalid_argument("McapWriter: no message definition for type '" + type + "'");
    }
    schema_id = static_cast<std::uint16_t>(s.schemas.size() + 1);
    s.schemas.push_back({schema_id, type, std::string(definition)});
    s.schema_of_type.emplace(type, schema_id);
    s.chunk.Record(McapOp::kSchema, SchemaRecord(s.schemas.back()));
  }
  Channel c;
  c.id = static_cast<std::uint16_t>(s.channels.size() + 1);
  c.schema_id = schema_id;
  c.topic = std::move(topic);
  c.encoding = std::move(message_encoding);
  // rosbag2 reads the publishers' QoS from here; empty means none were recorded.
  if (s.profile == "ros2") c.metadata["offered_qos_profiles"] = "";
  s.channels.push_back(std::move(c));
  s.chunk.Record(McapOp::kChannel, ChannelRecord(s.channels.back()));
  return s.channels.back().id;
}

void McapWriter::Write(std::uint16_t channel, std::int64_t log_time_ns,
                       std::span<const std::uint8_t> data) {
  State& s = *state_;
  if (s.closed) throw std::logic_error("McapWriter::Write after Close");
  if (channel == 0 || channel > s.channels.size()) {
    throw std::invalid_argument("McapWriter: unknown channel " + std::to_string(channel));
  }
  if (log_time_ns < 0) {
    throw core::IoError(s.file.name() + ": log time " + std::to_string(log_time_ns) +
                        " ns is negative (MCAP times are unsigned)");
  }
  Channel& c = s.channels[channel - 1];
  const auto t = static_cast<std::uint64_t>(log_time_ns);

  Bytes body;
  body.U16(channel).U32(c.sequence++).U64(t).U64(t).Raw(data);
  s.chunk_index[channel].emplace_back(t, s.chunk.size());
  s.chunk.Record(McapOp::kMessage, body);

  s.chunk_start_time = s.chunk_has_messages ? std::min(s.chunk_start_time, t) : t;
  s.chunk_end_time = s.chunk_has_messages ? std::max(s.chunk_end_time, t) : t;
  s.chunk_has_messages = true;
  s.start_time = s.message_count > 0 ? std::min(s.start_time, t) : t;
  s.end_time = s.message_count > 0 ? std::max(s.end_time, t) : t;
  ++s.message_count;
  ++c.message_count;
  if (s.chunk.size() >= s.chunk_bytes) s.FlushChunk();
}

void McapWriter::Close() {
  State& s = *state_;
  if (s.closed) return;
  s.FlushChunk();
  Bytes data_end;
  data_end.U32(0);  // no CRC of the data section, as the MCAP C++ library writes it
  Bytes record;
  record.Record(McapOp::kDataEnd, data_end);
  s.file.Put(record.data());
  s.file.Put(s.SummaryAndFooter().data());
  s.file.Finish();
  s.closed = true;
}

}  // namespace retrace::logs
