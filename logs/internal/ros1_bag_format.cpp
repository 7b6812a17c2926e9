#include "logs/internal/ros1_bag_format.hpp"

#include <array>
#include <cstring>
#include <string>

#include "core/errors.hpp"
#include "logs/internal/byte_reader.hpp"

namespace retrace::logs::internal {
namespace {

constexpr std::uint32_t kNsPerSecond = 1'000'000'000;

// `value`'s lowest N bytes, little endian.
template <std::size_t N>
std::array<std::uint8_t, N> LittleEndian(std::uint64_t value) {
  std::array<std::uint8_t, N> bytes{};
  for (std::size_t i = 0; i < N; ++i) bytes[i] = static_cast<std::uint8_t>(value >> (8 * i));
  return bytes;
}

std::string Quoted(std::string_view name) { return "'" + std::string(name) + "'"; }

// The value of a field that must be `n` bytes.
std::span<const std::uint8_t> Sized(const Ros1FieldList& fields, std::string_view name,
                                    std::size_t n) {
  const std::span<const std::uint8_t> value = fields.Get(name);
  if (value.size() != n) {
    throw core::IoError("field " + Quoted(name) + " of " + std::to_string(value.size()) +
                        " bytes, not " + std::to_string(n));
  }
  return value;
}

}  // namespace

std::string_view Ros1BagOpName(std::uint8_t op) {
  switch (static_cast<Ros1BagOp>(op)) {
    case Ros1BagOp::kMessageDefinition:
      return "message definition";
    case Ros1BagOp::kMessageData:
      return "message data";
    case Ros1BagOp::kBagHeader:
      return "bag header";
    case Ros1BagOp::kIndexData:
      return "index data";
    case Ros1BagOp::kChunk:
      return "chunk";
    case Ros1BagOp::kChunkInfo:
      return "chunk info";
    case Ros1BagOp::kConnection:
      return "connection";
  }
  return "unknown";
}

Ros1FieldList::Ros1FieldList(std::span<const std::uint8_t> bytes) : bytes_(bytes) {
  ByteReader r(bytes);
  while (!r.AtEnd()) {
    const std::size_t at = r.offset();
    if (r.remaining() < 4) {
      throw core::IoError("header ends in " + std::to_string(r.remaining()) + " bytes at byte " +
                          std::to_string(at) + ", too few for a field length");
    }
    const std::uint32_t length = r.U32();
    if (length > r.remaining()) {
      throw core::IoError("header field of " + std::to_string(length) + " bytes at byte " +
                          std::to_string(at) + " runs past the header's end (" +
                          std::to_string(r.remaining()) + " bytes left)");
    }
    const std::span<const std::uint8_t> field = r.Bytes(length);
    if (std::memchr(field.data(), '=', field.size()) == nullptr) {
      throw core::IoError("header field at byte " + std::to_string(at) + " has no '='");
    }
  }
}

std::optional<std::span<const std::uint8_t>> Ros1FieldList::Find(std::string_view name) const {
  ByteReader r(bytes_);
  while (!r.AtEnd()) {
    const std::span<const std::uint8_t> field = r.Bytes(r.U32());
    const auto* chars = reinterpret_cast<const char*>(field.data());
    const auto* equals = static_cast<const char*>(std::memchr(chars, '=', field.size()));
    if (std::string_view(chars, static_cast<std::size_t>(equals - chars)) == name) {
      return field.subspan(static_cast<std::size_t>(equals - chars) + 1);
    }
  }
  return std::nullopt;
}

std::span<const std::uint8_t> Ros1FieldList::Get(std::string_view name) const {
  const std::optional<std::span<const std::uint8_t>> value = Find(name);
  if (!value) throw core::IoError("no " + Quoted(name) + " field");
  return *value;
}

std::uint8_t Ros1FieldList::Op() const { return Sized(*this, "op", 1)[0]; }

std::uint32_t Ros1FieldList::U32(std::string_view name) const {
  return ByteReader(Sized(*this, name, 4)).U32();
}

std::uint64_t Ros1FieldList::U64(std::string_view name) const {
  return ByteReader(Sized(*this, name, 8)).U64();
}

std::int64_t Ros1FieldList::TimeNs(std::string_view name) const {
  ByteReader r(Sized(*this, name, 8));
  const std::uint32_t sec = r.U32();
  const std::uint32_t nsec = r.U32();
  if (nsec >= kNsPerSecond) {
    throw core::IoError("field " + Quoted(name) + " holds " + std::to_string(nsec) +
                        " nanoseconds, more than a second");
  }
  return static_cast<std::int64_t>(sec) * kNsPerSecond + nsec;
}

std::string_view Ros1FieldList::Text(std::string_view name) const {
  const std::span<const std::uint8_t> value = Get(name);
  return {reinterpret_cast<const char*>(value.data()), value.size()};
}

Ros1FieldWriter& Ros1FieldWriter::Bytes(std::string_view name,
                                        std::span<const std::uint8_t> value) {
  AppendU32(bytes_, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
  bytes_.insert(bytes_.end(), name.begin(), name.end());
  bytes_.push_back('=');
  bytes_.insert(bytes_.end(), value.begin(), value.end());
  return *this;
}

Ros1FieldWriter& Ros1FieldWriter::Text(std::string_view name, std::string_view value) {
  return Bytes(name, {reinterpret_cast<const std::uint8_t*>(value.data()), value.size()});
}

Ros1FieldWriter& Ros1FieldWriter::U8(std::string_view name, std::uint8_t value) {
  return Bytes(name, std::span<const std::uint8_t>(&value, 1));
}

Ros1FieldWriter& Ros1FieldWriter::U32(std::string_view name, std::uint32_t value) {
  return Bytes(name, LittleEndian<4>(value));
}

Ros1FieldWriter& Ros1FieldWriter::U64(std::string_view name, std::uint64_t value) {
  return Bytes(name, LittleEndian<8>(value));
}

Ros1FieldWriter& Ros1FieldWriter::TimeNs(std::string_view name, std::int64_t ns) {
  const auto sec = static_cast<std::uint64_t>(ns / kNsPerSecond);
  const auto nsec = static_cast<std::uint64_t>(ns % kNsPerSecond);
  return Bytes(name, LittleEndian<8>((nsec << 32) | (sec & 0xFFFFFFFFu)));
}

void AppendU32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

void AppendRos1Record(std::vector<std::uint8_t>& out, std::span<const std::uint8_t> header,
                      std::span<const std::uint8_t> data) {
  AppendU32(out, static_cast<std::uint32_t>(header.size()));
  out.insert(out.end(), header.begin(), header.end());
  AppendU32(out, static_cast<std::uint32_t>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
}

}  // namespace retrace::logs::internal
