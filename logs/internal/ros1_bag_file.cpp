#include "logs/internal/ros1_bag_file.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <span>
#include <string_view>

#include "core/errors.hpp"
#include "logs/internal/byte_reader.hpp"
#include "logs/internal/decompression.hpp"
#include "logs/internal/ros1_bag_format.hpp"

namespace retrace::logs::internal {
namespace {

// An error that already names the file and the offset.
class LocatedBagError : public core::IoError {
 public:
  using core::IoError::IoError;
};

// A record that runs past the end of the file: where a bag without an index stops being read.
class CutOffRecord : public LocatedBagError {
 public:
  using LocatedBagError::LocatedBagError;
};

// The most bytes a record header may hold: a connection's holds its type's definition (a few KiB;
// the largest ROS 1 definitions, of nested types, are tens of KiB).
constexpr std::uint32_t kMaxHeaderBytes = std::uint32_t{1} << 24;  // 16 MiB

std::string OpText(std::uint8_t op) {
  const std::string_view name = Ros1BagOpName(op);
  if (name != "unknown") return std::string(name);
  return "op " + std::to_string(op);
}

// Runs `parse`, locating an IoError it throws at the record at `offset` of `file`.
template <class F>
auto LocatedAt(const std::string& file, std::uint64_t offset, const std::string& what, F&& parse) {
  try {
    return parse();
  } catch (const LocatedBagError&) {
    throw;
  } catch (const core::IoError& e) {
    throw LocatedBagError(file + ": " + what + " (" + e.what() + ") at byte " +
                          std::to_string(offset));
  }
}

// A connection record's id and connection (the topic from its header, the type and md5sum from
// the connection header in its data).
std::pair<std::uint32_t, Ros1Connection> ParseConnection(const Ros1FieldList& header,
                                                         std::span<const std::uint8_t> data) {
  const std::uint32_t id = header.U32("conn");
  Ros1Connection c;
  c.topic = header.Text("topic");
  const Ros1FieldList fields(data);
  c.type = fields.Text("type");
  c.md5sum = fields.Text("md5sum");
  return {id, std::move(c)};
}

Ros1ChunkInfo ParseChunkInfo(const Ros1FieldList& header, std::span<const std::uint8_t> data) {
  const std::uint32_t version = header.U32("ver");
  if (version != 1)
    throw core::IoError("chunk info version " + std::to_string(version) + ", not 1");
  Ros1ChunkInfo info;
  info.pos = header.U64("chunk_pos");
  info.start_ns = header.TimeNs("start_time");
  info.end_ns = header.TimeNs("end_time");
  if (info.end_ns < info.start_ns) throw core::IoError("its end_time is before its start_time");
  const std::uint32_t count = header.U32("count");
  if (std::uint64_t{count} * 8 > data.size()) {
    throw core::IoError(std::to_string(count) + " connections need " +
                        std::to_string(std::uint64_t{count} * 8) + " bytes of data, it has " +
                        std::to_string(data.size()));
  }
  ByteReader r(data);
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t conn = r.U32();
    info.counts[conn] += r.U32();
  }
  std::erase_if(info.counts, [](const auto& entry) { return entry.second == 0; });
  return info;
}

}  // namespace

struct Ros1BagFile::Record {
  std::uint64_t offset = 0;
  std::vector<std::uint8_t> header;
  std::uint64_t data_offset = 0;
  std::uint32_t data_size = 0;
  std::vector<std::uint8_t> data;  // read only when asked for
  std::uint64_t end() const { return data_offset + data_size; }
};

void Ros1BagFile::Fail(const std::string& what, std::uint64_t offset) const {
  throw LocatedBagError(name_ + ": " + what + " at byte " + std::to_string(offset));
}

void Ros1BagFile::ReadAt(std::uint64_t offset, std::uint8_t* out, std::uint64_t n) {
  if (offset != stream_pos_) {
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    stream_pos_ = offset;
  }
  in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
  if (static_cast<std::uint64_t>(in_.gcount()) != n) {
    stream_pos_ = std::numeric_limits<std::uint64_t>::max();
    Fail("cannot read " + std::to_string(n) + " bytes (the file shrank or is unreadable)", offset);
  }
  stream_pos_ += n;
}

Ros1BagFile::Record Ros1BagFile::ReadRecord(std::uint64_t offset, bool with_data) {
  const auto cut_off = [&](const std::string& what) {
    throw CutOffRecord(name_ + ": truncated: the file (" + std::to_string(size_) +
                       " bytes) ends within the " + what + " of the record at byte " +
                       std::to_string(offset));
  };
  Record r;
  r.offset = offset;
  std::array<std::uint8_t, 4> length{};
  if (size_ - offset < length.size()) cut_off("header length");
  ReadAt(offset, length.data(), length.size());
  const std::uint32_t header_size = ByteReader(length).U32();
  if (header_size > size_ - offset - 4) {
    cut_off("header of " + std::to_string(header_size) + " bytes");
  }
  if (header_size > kMaxHeaderBytes) {
    Fail("record header of " + std::to_string(header_size) + " bytes, more than the limit of " +
             std::to_string(kMaxHeaderBytes),
         offset);
  }
  r.header.resize(header_size);
  ReadAt(offset + 4, r.header.data(), header_size);
  const std::uint64_t data_length_at = offset + 4 + header_size;
  if (size_ - data_length_at < length.size()) cut_off("data length");
  ReadAt(data_length_at, length.data(), length.size());
  r.data_size = ByteReader(length).U32();
  r.data_offset = data_length_at + 4;
  if (r.data_size > size_ - r.data_offset) {
    cut_off("data of " + std::to_string(r.data_size) + " bytes");
  }
  if (with_data) {
    if (r.data_size > kRos1BagMaxChunkBytes) {
      Fail("record data of " + std::to_string(r.data_size) + " bytes, more than the limit of " +
               std::to_string(kRos1BagMaxChunkBytes),
           offset);
    }
    r.data.resize(r.data_size);
    ReadAt(r.data_offset, r.data.data(), r.data_size);
  }
  return r;
}

Ros1BagFile::Ros1BagFile(const std::filesystem::path& file) : name_(file.string()) {
  in_.open(file, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!in_ || ec) throw core::IoError(name_ + ": cannot open the file");
  size_ = size;
  std::array<std::uint8_t, kRos1BagMagic.size()> magic{};
  if (size_ < magic.size()) Fail("not a ROS bag: too short for the version line", 0);
  ReadAt(0, magic.data(), magic.size());
  const std::string_view line(reinterpret_cast<const char*>(magic.data()), magic.size());
  if (line != kRos1BagMagic) {
    if (!line.starts_with("#ROSBAG V")) Fail("not a ROS bag: no '#ROSBAG V2.0' line", 0);
    throw core::IoError(name_ + ": a ROS bag of format " + std::string(line.substr(9, 3)) +
                        "; retrace reads format 2.0 (`rosbag filter old.bag new.bag True` "
                        "rewrites it so)");
  }
  const Record header = ReadRecord(magic.size(), true);
  std::string encryptor;
  LocatedAt(name_, magic.size(), "malformed bag header record", [&] {
    const Ros1FieldList fields(header.header);
    const std::uint8_t op = fields.Op();
    if (op != static_cast<std::uint8_t>(Ros1BagOp::kBagHeader)) {
      throw core::IoError("a " + OpText(op) + " record where the bag header belongs");
    }
    index_pos_ = fields.U64("index_pos");
    conn_count_ = fields.U32("conn_count");
    chunk_count_ = fields.U32("chunk_count");
    if (fields.Find("encryptor")) encryptor = fields.Text("encryptor");
  });
  if (!encryptor.empty()) {
    throw core::IoError(name_ + ": an encrypted bag (" + encryptor +
                        "); retrace reads unencrypted bags (`rosbag decrypt` decrypts it)");
  }
  first_record_ = header.end();
  if (index_pos_ != 0 && index_pos_ < first_record_) {
    Fail("the bag header puts the index at byte " + std::to_string(index_pos_) +
             ", before the end of the bag header",
         magic.size());
  }
}

Ros1BagLayout Ros1BagFile::ReadLayout() { return index_pos_ == 0 ? ScanChunks() : ReadIndex(); }

Ros1BagLayout Ros1BagFile::ReadIndex() {
  if (index_pos_ > size_) {
    throw LocatedBagError(name_ + ": truncated: the bag header puts the index at byte " +
                          std::to_string(index_pos_) + ", past the end of the file at byte " +
                          std::to_string(size_) + " (the file was cut short)");
  }
  Ros1BagLayout layout;
  std::uint32_t connections = 0, chunks = 0;
  for (std::uint64_t pos = index_pos_; connections < conn_count_ || chunks < chunk_count_;) {
    if (pos == size_) {
      Fail("truncated: the file ends after " + std::to_string(connections) + " of the index's " +
               std::to_string(conn_count_) + " connection records and " + std::to_string(chunks) +
               " of its " + std::to_string(chunk_count_) + " chunk info records",
           pos);
    }
    const Record r = ReadRecord(pos, true);
    LocatedAt(name_, pos, "malformed index record", [&] {
      const Ros1FieldList fields(r.header);
      const std::uint8_t op = fields.Op();
      if (op == static_cast<std::uint8_t>(Ros1BagOp::kConnection)) {
        ++connections;
        layout.connections.insert(ParseConnection(fields, r.data));
      } else if (op == static_cast<std::uint8_t>(Ros1BagOp::kChunkInfo)) {
        ++chunks;
        layout.chunks.push_back(ParseChunkInfo(fields, r.data));
      }
    });
    pos = r.end();
  }
  std::sort(layout.chunks.begin(), layout.chunks.end(),
            [](const Ros1ChunkInfo& a, const Ros1ChunkInfo& b) { return a.pos < b.pos; });
  for (std::size_t i = 0; i < layout.chunks.size(); ++i) {
    const std::uint64_t pos = layout.chunks[i].pos;
    if (pos < first_record_ || pos >= index_pos_) {
      Fail("the index puts a chunk at byte " + std::to_string(pos) +
               ", outside the chunks (bytes " + std::to_string(first_record_) + " to " +
               std::to_string(index_pos_) + ")",
           index_pos_);
    }
    if (i > 0 && pos == layout.chunks[i - 1].pos) {
      Fail("the index lists the chunk at byte " + std::to_string(pos) + " twice", index_pos_);
    }
  }
  return layout;
}

Ros1BagLayout Ros1BagFile::ScanChunks() {
  Ros1BagLayout layout;
  layout.indexed = false;
  std::vector<std::uint8_t> data;
  std::vector<Ros1MessageEntry> messages;
  std::string stopped;  // why the scan stopped before the end of the file
  for (std::uint64_t pos = first_record_; pos < size_;) {
    Record r;
    try {
      r = ReadRecord(pos, false);
    } catch (const CutOffRecord&) {
      stopped = "it ends in a record cut off at byte " + std::to_string(pos) + " (" +
                std::to_string(size_ - pos) + " bytes not read)";
      break;
    }
    const std::uint8_t op =
        LocatedAt(name_, pos, "malformed record", [&] { return Ros1FieldList(r.header).Op(); });
    if (op == static_cast<std::uint8_t>(Ros1BagOp::kChunk)) {
      if (r.data_size == 0) {  // the sizes its header was started with: never closed
        stopped = "its last chunk, at byte " + std::to_string(pos) + ", was never closed (" +
                  std::to_string(size_ - pos) + " bytes not read)";
        break;
      }
      // As `rosbag reindex`: a chunk that cannot be read ends what a cut recording holds.
      try {
        LoadChunk(pos, layout.connections, data, messages);
      } catch (const core::IoError& e) {
        stopped = std::string(e.what()).substr(name_.size() + 2) + ": the bag is read up to it (" +
                  std::to_string(size_ - pos) + " bytes not read)";
        break;
      }
      if (!messages.empty()) layout.chunks.push_back(SummarizeChunk(pos, messages));
    } else if (op == static_cast<std::uint8_t>(Ros1BagOp::kConnection)) {
      const Record full = ReadRecord(pos, true);
      LocatedAt(name_, pos, "malformed connection record", [&] {
        layout.connections.insert(ParseConnection(Ros1FieldList(full.header), full.data));
      });
    }
    pos = r.end();
  }
  const std::string chunks = std::to_string(layout.chunks.size());
  layout.notes.push_back("the bag has no index (a recording that was cut off or not closed): its " +
                         chunks +
                         " chunks were read by scanning them (`rosbag reindex` writes "
                         "the index)");
  if (!stopped.empty()) layout.notes.push_back(stopped);
  return layout;
}

Ros1ChunkInfo SummarizeChunk(std::uint64_t pos, const std::vector<Ros1MessageEntry>& messages) {
  Ros1ChunkInfo info;
  info.pos = pos;
  info.start_ns = std::numeric_limits<std::int64_t>::max();
  info.end_ns = std::numeric_limits<std::int64_t>::min();
  for (const Ros1MessageEntry& m : messages) {
    info.start_ns = std::min(info.start_ns, m.time_ns);
    info.end_ns = std::max(info.end_ns, m.time_ns);
    ++info.counts[m.conn];
  }
  if (messages.empty()) info.start_ns = info.end_ns = 0;
  return info;
}

void Ros1BagFile::ReadChunkData(const Record& chunk, std::string_view compression,
                                std::uint64_t size, std::vector<std::uint8_t>& data) {
  if (size > kRos1BagMaxChunkBytes) {
    Fail("chunk declares " + std::to_string(size) + " uncompressed bytes, more than the limit of " +
             std::to_string(kRos1BagMaxChunkBytes),
         chunk.offset);
  }
  if (compression == "none") {
    if (chunk.data_size != size) {
      Fail("uncompressed chunk holds " + std::to_string(chunk.data_size) + " bytes but declares " +
               std::to_string(size),
           chunk.offset);
    }
    data.resize(chunk.data_size);
    ReadAt(chunk.data_offset, data.data(), chunk.data_size);
    return;
  }
  if (compression != "bz2" && compression != "lz4") {
    Fail("unsupported chunk compression '" + std::string(compression) + "'", chunk.offset);
  }
  if (chunk.data_size > kRos1BagMaxChunkBytes) {
    Fail("chunk of " + std::to_string(chunk.data_size) + " compressed bytes, more than the limit",
         chunk.offset);
  }
  compressed_.resize(chunk.data_size);
  ReadAt(chunk.data_offset, compressed_.data(), chunk.data_size);
  LocatedAt(name_, chunk.offset, std::string(compression) + " chunk", [&] {
    if (compression == "bz2") {
      DecompressBz2(compressed_, static_cast<std::size_t>(size), data);
    } else {
      DecompressLz4(compressed_, static_cast<std::size_t>(size), data);
    }
  });
}

void Ros1BagFile::ListChunkRecords(std::uint64_t pos, std::span<const std::uint8_t> records,
                                   std::map<std::uint32_t, Ros1Connection>& connections,
                                   std::vector<Ros1MessageEntry>& messages) const {
  messages.clear();
  ByteReader r(records);
  // The messages are many: the error's text is built only when there is one.
  const auto fail = [&](std::string_view what, std::size_t at, const core::IoError& e) {
    Fail(std::string(what) + " at offset " + std::to_string(at) + " of the chunk's records (" +
             e.what() + ")",
         pos);
  };
  while (!r.AtEnd()) {
    const std::size_t at = r.offset();
    std::span<const std::uint8_t> header, data;
    try {
      header = r.Bytes(r.U32());
      data = r.Bytes(r.U32());
    } catch (const core::IoError& e) {
      fail("truncated record", at, e);
    }
    try {
      const Ros1FieldList fields(header);
      const std::uint8_t op = fields.Op();
      if (op == static_cast<std::uint8_t>(Ros1BagOp::kMessageData)) {
        const std::uint32_t conn = fields.U32("conn");
        if (!connections.contains(conn)) {
          throw core::IoError("a message on connection " + std::to_string(conn) +
                              ", which no connection record declares");
        }
        const auto offset = static_cast<std::uint32_t>(data.data() - records.data());
        messages.push_back(
            {fields.TimeNs("time"), conn, offset, static_cast<std::uint32_t>(data.size())});
      } else if (op == static_cast<std::uint8_t>(Ros1BagOp::kConnection)) {
        connections.insert(ParseConnection(fields, data));
      }
    } catch (const core::IoError& e) {
      fail("malformed record", at, e);
    }
  }
}

void Ros1BagFile::LoadChunk(std::uint64_t pos, std::map<std::uint32_t, Ros1Connection>& connections,
                            std::vector<std::uint8_t>& data,
                            std::vector<Ros1MessageEntry>& messages) {
  const Record chunk = ReadRecord(pos, false);
  std::string compression;
  std::uint32_t size = 0;
  LocatedAt(name_, pos, "malformed chunk record", [&] {
    const Ros1FieldList fields(chunk.header);
    const std::uint8_t op = fields.Op();
    if (op != static_cast<std::uint8_t>(Ros1BagOp::kChunk)) {
      throw core::IoError("a " + OpText(op) + " record where a chunk belongs");
    }
    compression = fields.Text("compression");
    size = fields.U32("size");
  });
  ReadChunkData(chunk, compression, size, data);
  ListChunkRecords(pos, data, connections, messages);
}

void Ros1BagFile::CheckChunk(const Ros1ChunkInfo& info,
                             const std::vector<Ros1MessageEntry>& messages) const {
  const Ros1ChunkInfo held = SummarizeChunk(info.pos, messages);
  if (!messages.empty() && (held.start_ns < info.start_ns || held.end_ns > info.end_ns)) {
    Fail("chunk holds messages from " + std::to_string(held.start_ns) + " to " +
             std::to_string(held.end_ns) + " ns, outside its chunk info's " +
             std::to_string(info.start_ns) + " to " + std::to_string(info.end_ns) + " ns",
         info.pos);
  }
  if (held.counts == info.counts) return;
  for (const auto& [conn, count] : info.counts) {
    const auto it = held.counts.find(conn);
    const std::uint32_t n = it == held.counts.end() ? 0 : it->second;
    if (n != count) {
      Fail("chunk holds " + std::to_string(n) + " messages on connection " + std::to_string(conn) +
               ", its chunk info " + std::to_string(count),
           info.pos);
    }
  }
  Fail("chunk holds messages on connections its chunk info does not list", info.pos);
}

}  // namespace retrace::logs::internal
