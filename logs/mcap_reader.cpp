#include "logs/mcap_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <span>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/errors.hpp"
#include "logs/internal/byte_reader.hpp"
#include "logs/internal/decompression.hpp"
#include "logs/internal/mcap_format.hpp"

namespace retrace::logs {
namespace {

using internal::ByteReader;
using internal::DecompressLz4;
using internal::DecompressZstd;
using internal::kMcapMagic;
using internal::kMcapRecordPrefixBytes;
using internal::McapOp;

std::string Hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), "0x%08x", v);
  return buf;
}

std::string OpName(std::uint8_t op) {
  switch (static_cast<McapOp>(op)) {
    case McapOp::kHeader:
      return "Header";
    case McapOp::kFooter:
      return "Footer";
    case McapOp::kSchema:
      return "Schema";
    case McapOp::kChannel:
      return "Channel";
    case McapOp::kMessage:
      return "Message";
    case McapOp::kChunk:
      return "Chunk";
    case McapOp::kMessageIndex:
      return "Message Index";
    case McapOp::kChunkIndex:
      return "Chunk Index";
    case McapOp::kAttachment:
      return "Attachment";
    case McapOp::kAttachmentIndex:
      return "Attachment Index";
    case McapOp::kStatistics:
      return "Statistics";
    case McapOp::kMetadata:
      return "Metadata";
    case McapOp::kMetadataIndex:
      return "Metadata Index";
    case McapOp::kSummaryOffset:
      return "Summary Offset";
    case McapOp::kDataEnd:
      return "Data End";
  }
  return "opcode " + std::to_string(op);
}

// An error that already names the file and the offset.
class LocatedError : public core::IoError {
 public:
  using core::IoError::IoError;
};

struct Channel {
  std::string topic;
  std::string encoding;
  std::string type;  // the schema name
};

}  // namespace

struct McapReader::State {
  std::filesystem::path path;
  std::string name;
  std::ifstream in;
  std::uint64_t file_size = 0;
  std::uint64_t stream_pos = 0;  // where `in` stands
  std::uint64_t pos = 0;         // the next top-level record
  bool done = false;

  std::unordered_map<std::uint16_t, std::string> schemas;  // id -> name
  std::unordered_map<std::uint16_t, Channel> channels;

  std::vector<std::uint8_t> body;        // the last top-level record's body
  std::vector<std::uint8_t> chunk_data;  // the decompressed records of the current chunk
  std::span<const std::uint8_t> chunk_records;
  std::size_t chunk_pos = 0;
  std::uint64_t chunk_offset = 0;  // of the current Chunk record in the file
  bool in_chunk = false;

  [[noreturn]] void Fail(const std::string& what, std::uint64_t offset) const {
    throw LocatedError(name + ": " + what + " at byte " + std::to_string(offset));
  }

  // Reads `n` bytes at `offset` (within the file, checked by the caller) into `out`.
  void ReadAt(std::uint64_t offset, std::uint8_t* out, std::uint64_t n) {
    if (offset != stream_pos) {
      in.clear();
      in.seekg(static_cast<std::streamoff>(offset));
      stream_pos = offset;
    }
    in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    if (static_cast<std::uint64_t>(in.gcount()) != n) {
      stream_pos = std::numeric_limits<std::uint64_t>::max();
      Fail("cannot read " + std::to_string(n) + " bytes (the file shrank or is unreadable)",
           offset);
    }
    stream_pos += n;
  }

  // The opcode and body length of the record at `offset`, checked against the file.
  std::pair<std::uint8_t, std::uint64_t> ReadRecordPrefix(std::uint64_t offset) {
    if (file_size - offset < kMcapRecordPrefixBytes) {
      Fail("truncated record (the file ends before its Data End or Footer record)", offset);
    }
    std::array<std::uint8_t, kMcapRecordPrefixBytes> prefix{};
    ReadAt(offset, prefix.data(), prefix.size());
    ByteReader r(prefix);
    const std::uint8_t op = r.U8();
    const std::uint64_t length = r.U64();
    if (length > file_size - offset - kMcapRecordPrefixBytes) {
      Fail(OpName(op) + " record of " + std::to_string(length) +
               " bytes runs past the end of the file (" + std::to_string(file_size) + " bytes)",
           offset);
    }
    return {op, length};
  }

  // Loads the body of the record at `offset` into `body`.
  void LoadBody(std::uint8_t op, std::uint64_t offset, std::uint64_t length) {
    if (length > kMcapMaxRecordBytes) {
      Fail(OpName(op) + " record of " + std::to_string(length) + " bytes exceeds the limit of " +
               std::to_string(kMcapMaxRecordBytes) + " bytes",
           offset);
    }
    body.resize(static_cast<std::size_t>(length));
    ReadAt(offset + kMcapRecordPrefixBytes, body.data(), length);
  }

  void ParseSchema(std::span<const std::uint8_t> record) {
    ByteReader r(record);
    const std::uint16_t id = r.U16();
    const std::string_view schema_name = r.Chars(r.U32());
    r.Chars(r.U32());     // encoding
    r.Bytes(r.U32());     // data
    if (id == 0) return;  // invalid by the spec, to be ignored
    schemas[id] = std::string(schema_name);
  }

  // Returns "" or what is wrong.
  std::string ParseChannel(std::span<const std::uint8_t> record) {
    ByteReader r(record);
    const std::uint16_t id = r.U16();
    const std::uint16_t schema_id = r.U16();
    const std::string_view topic = r.Chars(r.U32());
    const std::string_view encoding = r.Chars(r.U32());
    r.Bytes(r.U32());  // metadata
    std::string type;
    if (schema_id != 0) {
      const auto it = schemas.find(schema_id);
      if (it == schemas.end()) {
        return "Channel " + std::to_string(id) + " (" + std::string(topic) +
               ") refers to unknown schema " + std::to_string(schema_id);
      }
      type = it->second;
    }
    channels[id] = Channel{std::string(topic), std::string(encoding), std::move(type)};
    return "";
  }

  // Fills `message` from a Message record; returns "" or what is wrong.
  std::string ParseMessage(std::span<const std::uint8_t> record, RawMessage& message) {
    ByteReader r(record);
    const std::uint16_t channel_id = r.U16();
    r.U32();  // sequence
    const std::uint64_t log_time = r.U64();
    r.U64();  // publish_time
    const auto it = channels.find(channel_id);
    if (it == channels.end()) {
      return "Message on unknown channel " + std::to_string(channel_id);
    }
    if (log_time > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      return "Message log time " + std::to_string(log_time) + " ns beyond 2^63";
    }
    message.topic = it->second.topic;
    message.type = it->second.type;
    message.encoding = it->second.encoding;
    message.log_time_ns = static_cast<std::int64_t>(log_time);
    message.data = r.Bytes(r.remaining());
    return "";
  }

  // Decompresses the Chunk record in `body` (at `offset`) and starts on its records.
  void OpenChunk(std::uint64_t offset) {
    ByteReader r(body);
    r.U64();  // message_start_time
    r.U64();  // message_end_time
    const std::uint64_t size = r.U64();
    const std::uint32_t crc = r.U32();
    const std::string_view compression = r.Chars(r.U32());
    const std::span<const std::uint8_t> records = r.Bytes(r.U64());
    if (size > kMcapMaxRecordBytes) {
      Fail("chunk declares " + std::to_string(size) +
               " uncompressed bytes, more than the limit of " + std::to_string(kMcapMaxRecordBytes),
           offset);
    }
    const auto usize = static_cast<std::size_t>(size);
    try {
      if (records.empty() && usize == 0) {
        chunk_records = records;  // an empty chunk, whatever its compression
      } else if (compression.empty()) {
        if (records.size() != usize) {
          Fail("uncompressed chunk holds " + std::to_string(records.size()) +
                   " bytes but declares " + std::to_string(usize),
               offset);
        }
        chunk_records = records;
      } else if (compression == "zstd") {
        DecompressZstd(records, usize, chunk_data);
        chunk_records = chunk_data;
      } else if (compression == "lz4") {
        DecompressLz4(records, usize, chunk_data);
        chunk_records = chunk_data;
      } else {
        Fail("unsupported chunk compression '" + std::string(compression) + "'", offset);
      }
    } catch (const LocatedError&) {
      throw;
    } catch (const core::IoError& e) {
      Fail(std::string("chunk: ") + e.what(), offset);
    }
    if (crc != 0) {
      const std::uint32_t actual =
          static_cast<std::uint32_t>(crc32_z(0, chunk_records.data(), chunk_records.size()));
      if (actual != crc) {
        Fail("chunk CRC mismatch: stored " + Hex32(crc) + ", computed " + Hex32(actual), offset);
      }
    }
    chunk_pos = 0;
    chunk_offset = offset;
    in_chunk = true;
  }

  // The next record inside the current chunk; true if it was a message.
  bool NextInChunk(RawMessage& message) {
    const std::size_t at = chunk_pos;
    const auto fail = [&](const std::string& what) {
      Fail(what + " at offset " + std::to_string(at) + " of the records of the chunk",
           chunk_offset);
    };
    std::uint8_t op = 0;
    std::span<const std::uint8_t> record;
    try {
      ByteReader r(chunk_records);
      r.Seek(chunk_pos);
      op = r.U8();
      record = r.Bytes(r.U64());
      chunk_pos = r.offset();
    } catch (const core::IoError& e) {
      fail(std::string("truncated record (") + e.what() + ")");
    }
    try {
      switch (static_cast<McapOp>(op)) {
        case McapOp::kSchema:
          ParseSchema(record);
          return false;
        case McapOp::kChannel:
          if (std::string error = ParseChannel(record); !error.empty()) fail(error);
          return false;
        case McapOp::kMessage:
          if (std::string error = ParseMessage(record, message); !error.empty()) fail(error);
          return true;
        default:
          return false;  // other records do not belong in a chunk; unknown ones are skipped
      }
    } catch (const LocatedError&) {
      throw;
    } catch (const core::IoError& e) {
      fail("malformed " + OpName(op) + " record (" + e.what() + ")");
    }
    return false;
  }
};

McapReader::McapReader(const std::filesystem::path& file) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = file;
  s.name = file.string();
  s.in.open(file, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!s.in || ec) throw core::IoError(s.name + ": cannot open the file");
  s.file_size = size;

  // Magic, Header record, ..., Footer record, magic.
  constexpr std::uint64_t kFooterRecordBytes =
      kMcapRecordPrefixBytes + internal::kMcapFooterBodyBytes;
  std::array<std::uint8_t, kMcapMagic.size()> magic{};
  if (s.file_size < magic.size()) s.Fail("not an MCAP file: too short for the magic", 0);
  s.ReadAt(0, magic.data(), magic.size());
  if (magic != kMcapMagic) s.Fail("not an MCAP file: wrong magic", 0);
  if (s.file_size < 2 * magic.size() + kMcapRecordPrefixBytes + kFooterRecordBytes) {
    s.Fail("truncated MCAP file of " + std::to_string(s.file_size) + " bytes", s.file_size);
  }
  const std::uint64_t trailer = s.file_size - magic.size();
  s.ReadAt(trailer, magic.data(), magic.size());
  if (magic != kMcapMagic) {
    s.Fail("no trailing MCAP magic (the file is truncated or was not closed)", trailer);
  }
  const std::uint64_t footer = trailer - kFooterRecordBytes;
  std::array<std::uint8_t, kMcapRecordPrefixBytes> prefix{};
  s.ReadAt(footer, prefix.data(), prefix.size());
  ByteReader footer_reader(prefix);
  if (footer_reader.U8() != static_cast<std::uint8_t>(McapOp::kFooter) ||
      footer_reader.U64() != internal::kMcapFooterBodyBytes) {
    s.Fail("no Footer record before the trailing magic (the file is truncated)", footer);
  }
  const auto [op, length] = s.ReadRecordPrefix(magic.size());
  if (op != static_cast<std::uint8_t>(McapOp::kHeader)) {
    s.Fail("expected a Header record, found " + OpName(op), magic.size());
  }
  s.pos = magic.size() + kMcapRecordPrefixBytes + length;
}

McapReader::~McapReader() = default;

const std::string& McapReader::name() const { return state_->name; }

bool McapReader::Next(RawMessage& message) {
  State& s = *state_;
  while (!s.done) {
    if (s.in_chunk) {
      if (s.chunk_pos < s.chunk_records.size()) {
        if (s.NextInChunk(message)) return true;
        continue;
      }
      s.in_chunk = false;
    }
    const std::uint64_t offset = s.pos;
    const auto [op, length] = s.ReadRecordPrefix(offset);
    s.pos = offset + kMcapRecordPrefixBytes + length;
    switch (static_cast<McapOp>(op)) {
      case McapOp::kFooter:
      case McapOp::kDataEnd:
        s.done = true;
        return false;
      case McapOp::kSchema:
      case McapOp::kChannel:
      case McapOp::kMessage:
      case McapOp::kChunk: {
        s.LoadBody(op, offset, length);
        std::string error;
        try {
          if (op == static_cast<std::uint8_t>(McapOp::kSchema)) {
            s.ParseSchema(s.body);
          } else if (op == static_cast<std::uint8_t>(McapOp::kChannel)) {
            error = s.ParseChannel(s.body);
          } else if (op == static_cast<std::uint8_t>(McapOp::kMessage)) {
            error = s.ParseMessage(s.body, message);
            if (error.empty()) return true;
          } else {
            s.OpenChunk(offset);
          }
        } catch (const LocatedError&) {
          throw;
        } catch (const core::IoError& e) {
          error = "malformed " + OpName(op) + " record (" + e.what() + ")";
        }
        if (!error.empty()) s.Fail(error, offset);
        break;
      }
      default:
        break;  // indexes, attachments, metadata, unknown opcodes: skipped by their length
    }
  }
  return false;
}

}  // namespace retrace::logs
