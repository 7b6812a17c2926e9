#include "logs/cdr.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

#include "core/errors.hpp"

namespace retrace::logs {
namespace {

constexpr std::size_t kHeaderBytes = 4;

std::string Hex(unsigned v) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s = "0x";
  s += kDigits[(v >> 4) & 0xF];
  s += kDigits[v & 0xF];
  return s;
}

// The byte order of the encapsulation header, or an error for anything but plain CDR.
std::endian EncapsulationOrder(std::span<const std::uint8_t> message) {
  if (message.size() < kHeaderBytes) {
    throw core::IoError("truncated: " + std::to_string(message.size()) +
                        " bytes, shorter than the 4-byte CDR encapsulation header");
  }
  if (message[0] == 0x00 && message[1] == 0x01) return std::endian::little;
  if (message[0] == 0x00 && message[1] == 0x00) return std::endian::big;
  std::string what = "unsupported CDR encapsulation " + Hex(message[0]) + " " + Hex(message[1]);
  if (message[0] == 0x00 && (message[1] == 0x02 || message[1] == 0x03)) {
    what += " (parameter-list CDR)";
  } else if (message[0] == 0x00 && message[1] >= 0x06 && message[1] <= 0x0B) {
    what += " (XCDR2)";
  }
  throw core::IoError(what + ": only plain CDR, little or big endian, is read");
}

}  // namespace

CdrReader::CdrReader(std::span<const std::uint8_t> message)
    : reader_(message.subspan(std::min(message.size(), kHeaderBytes)),
              EncapsulationOrder(message)) {}

void CdrReader::Align(std::size_t n) {
  const std::size_t pad = (n - reader_.offset() % n) % n;
  reader_.Skip(pad);
}

template <typename T>
T CdrReader::Read() {
  Align(sizeof(T));
  return reader_.Read<T>();
}

bool CdrReader::ReadBool() {
  const std::size_t at = reader_.offset();
  const std::uint8_t b = reader_.U8();
  if (b > 1) {
    throw core::IoError("bool of value " + std::to_string(b) + " at byte " + std::to_string(at));
  }
  return b == 1;
}

std::string CdrReader::ReadString() {
  const std::size_t at = reader_.offset();
  const std::uint32_t length = Read<std::uint32_t>();
  if (length > reader_.remaining()) {
    throw core::IoError("string length " + std::to_string(length) + " at byte " +
                        std::to_string(at) + " beyond the end (" +
                        std::to_string(reader_.remaining()) + " bytes left)");
  }
  std::string_view chars = reader_.Chars(length);
  if (!chars.empty() && chars.back() == '\0') chars.remove_suffix(1);
  return std::string(chars);
}

std::uint32_t CdrReader::ReadSequenceLength(std::size_t min_element_bytes) {
  const std::size_t at = reader_.offset();
  const std::uint32_t count = Read<std::uint32_t>();
  const std::uint64_t need =
      static_cast<std::uint64_t>(count) * std::max<std::uint64_t>(min_element_bytes, 1);
  if (need > reader_.remaining()) {
    throw core::IoError("sequence of " + std::to_string(count) + " elements at byte " +
                        std::to_string(at) + " needs at least " + std::to_string(need) +
                        " bytes, " + std::to_string(reader_.remaining()) + " left");
  }
  return count;
}

std::vector<float> CdrReader::ReadFloat32Sequence() {
  const std::uint32_t n = ReadSequenceLength(sizeof(float));
  std::vector<float> out(n);
  for (float& v : out) v = Read<float>();
  return out;
}

void CdrReader::SkipFloat32Sequence() {
  const std::uint32_t n = ReadSequenceLength(sizeof(float));
  reader_.Skip(std::uint64_t{n} * sizeof(float));  // aligned already: the count is 4 bytes
}

std::vector<double> CdrReader::ReadFloat64Sequence() {
  // An 8-byte element may need 4 bytes of padding before the first one: checked per read.
  const std::uint32_t n = ReadSequenceLength(sizeof(double));
  std::vector<double> out(n);
  for (double& v : out) v = Read<double>();
  return out;
}

void CdrReader::ReadFloat64Array(std::span<double> out) {
  for (double& v : out) v = Read<double>();
}

void CdrReader::SkipFloat64Array(std::size_t n) {
  if (n == 0) return;
  Align(sizeof(double));
  reader_.Skip(static_cast<std::uint64_t>(n) * sizeof(double));
}

CdrWriter::CdrWriter() : data_{0x00, 0x01, 0x00, 0x00} {}

void CdrWriter::Align(std::size_t n) {
  const std::size_t body = data_.size() - kHeaderBytes;
  data_.resize(data_.size() + (n - body % n) % n, 0);
}

template <typename T>
void CdrWriter::Write(T v) {
  Align(sizeof(T));
  std::uint8_t raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  data_.insert(data_.end(), raw, raw + sizeof(T));
}

void CdrWriter::WriteBool(bool v) { data_.push_back(v ? 1 : 0); }

void CdrWriter::WriteString(std::string_view s) {
  Write<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
  data_.insert(data_.end(), s.begin(), s.end());
  data_.push_back(0);
}

void CdrWriter::WriteSequenceLength(std::uint32_t count) { Write<std::uint32_t>(count); }

void CdrWriter::WriteFloat32Sequence(std::span<const float> values) {
  WriteSequenceLength(static_cast<std::uint32_t>(values.size()));
  for (float v : values) Write<float>(v);
}

void CdrWriter::WriteFloat64Sequence(std::span<const double> values) {
  WriteSequenceLength(static_cast<std::uint32_t>(values.size()));
  WriteFloat64Array(values);
}

void CdrWriter::WriteFloat64Array(std::span<const double> values) {
  for (double v : values) Write<double>(v);
}

// The primitive types of ROS 2 messages.
template std::int8_t CdrReader::Read<std::int8_t>();
template std::uint8_t CdrReader::Read<std::uint8_t>();
template std::int16_t CdrReader::Read<std::int16_t>();
template std::uint16_t CdrReader::Read<std::uint16_t>();
template std::int32_t CdrReader::Read<std::int32_t>();
template std::uint32_t CdrReader::Read<std::uint32_t>();
template std::int64_t CdrReader::Read<std::int64_t>();
template std::uint64_t CdrReader::Read<std::uint64_t>();
template float CdrReader::Read<float>();
template double CdrReader::Read<double>();
template void CdrWriter::Write<std::int8_t>(std::int8_t);
template void CdrWriter::Write<std::uint8_t>(std::uint8_t);
template void CdrWriter::Write<std::int16_t>(std::int16_t);
template void CdrWriter::Write<std::uint16_t>(std::uint16_t);
template void CdrWriter::Write<std::int32_t>(std::int32_t);
template void CdrWriter::Write<std::uint32_t>(std::uint32_t);
template void CdrWriter::Write<std::int64_t>(std::int64_t);
template void CdrWriter::Write<std::uint64_t>(std::uint64_t);
template void CdrWriter::Write<float>(float);
template void CdrWriter::Write<double>(double);

}  // namespace retrace::logs
