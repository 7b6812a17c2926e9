#include "logs/ros1_serialization.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "core/config.hpp"
#include "core/errors.hpp"

namespace retrace::logs {

double Ros1StampSeconds(Ros1Time t) {
  return static_cast<double>(t.sec) + static_cast<double>(t.nsec) * 1e-9;
}

Ros1Time ToRos1Time(double stamp) {
  const auto outside = [&] {
    return core::IoError("stamp " + core::FormatNumber(stamp) +
                         " s is outside the uint32 seconds of ROS 1 time");
  };
  if (!std::isfinite(stamp)) {
    throw core::IoError("stamp " + core::FormatNumber(stamp) + " is not finite");
  }
  const double sec = std::floor(stamp);
  if (sec < 0.0 || sec > static_cast<double>(std::numeric_limits<std::uint32_t>::max())) {
    throw outside();
  }
  std::int64_t s = static_cast<std::int64_t>(sec);
  std::int64_t ns = std::llround((stamp - sec) * 1e9);
  if (ns >= 1'000'000'000) {
    ns -= 1'000'000'000;
    ++s;
  }
  if (s > std::numeric_limits<std::uint32_t>::max()) throw outside();
  return {static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(ns)};
}

Ros1Time Ros1Reader::ReadTime() {
  Ros1Time t;
  t.sec = reader_.U32();
  t.nsec = reader_.U32();
  return t;
}

std::string Ros1Reader::ReadString() {
  const std::size_t at = reader_.offset();
  const std::uint32_t length = reader_.U32();
  if (length > reader_.remaining()) {
    throw core::IoError("string length " + std::to_string(length) + " at byte " +
                        std::to_string(at) + " beyond the end (" +
                        std::to_string(reader_.remaining()) + " bytes left)");
  }
  return std::string(reader_.Chars(length));
}

std::uint32_t Ros1Reader::ReadSequenceLength(std::size_t min_element_bytes) {
  const std::size_t at = reader_.offset();
  const std::uint32_t count = reader_.U32();
  const std::uint64_t need =
      static_cast<std::uint64_t>(count) * std::max<std::uint64_t>(min_element_bytes, 1);
  if (need > reader_.remaining()) {
    throw core::IoError("array of " + std::to_string(count) + " elements at byte " +
                        std::to_string(at) + " needs at least " + std::to_string(need) +
                        " bytes, " + std::to_string(reader_.remaining()) + " left");
  }
  return count;
}

std::vector<float> Ros1Reader::ReadFloat32Sequence() {
  const std::uint32_t n = ReadSequenceLength(sizeof(float));
  std::vector<float> out(n);
  if constexpr (std::endian::native == std::endian::little) {
    // One copy: the array is little endian and packed, as a float vector is here.
    const std::span<const std::uint8_t> bytes = reader_.Bytes(std::uint64_t{n} * sizeof(float));
    if (n > 0) std::memcpy(out.data(), bytes.data(), bytes.size());
  } else {
    for (float& v : out) v = reader_.Read<float>();
  }
  return out;
}

void Ros1Reader::SkipFloat32Sequence() {
  const std::uint32_t n = ReadSequenceLength(sizeof(float));
  reader_.Skip(std::uint64_t{n} * sizeof(float));
}

template <typename T>
void Ros1Writer::Write(T v) {
  std::uint8_t raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  data_.insert(data_.end(), raw, raw + sizeof(T));
}

void Ros1Writer::WriteTime(Ros1Time t) {
  Write<std::uint32_t>(t.sec);
  Write<std::uint32_t>(t.nsec);
}

void Ros1Writer::WriteString(std::string_view s) {
  Write<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
  data_.insert(data_.end(), s.begin(), s.end());
}

void Ros1Writer::WriteSequenceLength(std::uint32_t count) { Write<std::uint32_t>(count); }

void Ros1Writer::WriteFloat32Sequence(std::span<const float> values) {
  WriteSequenceLength(static_cast<std::uint32_t>(values.size()));
  for (float v : values) Write<float>(v);
}

void Ros1Writer::WriteFloat64Array(std::span<const double> values) {
  for (double v : values) Write<double>(v);
}

// The primitive types of ROS 1 messages.
template void Ros1Writer::Write<std::int8_t>(std::int8_t);
template void Ros1Writer::Write<std::uint8_t>(std::uint8_t);
template void Ros1Writer::Write<std::int16_t>(std::int16_t);
template void Ros1Writer::Write<std::uint16_t>(std::uint16_t);
template void Ros1Writer::Write<std::int32_t>(std::int32_t);
template void Ros1Writer::Write<std::uint32_t>(std::uint32_t);
template void Ros1Writer::Write<std::int64_t>(std::int64_t);
template void Ros1Writer::Write<std::uint64_t>(std::uint64_t);
template void Ros1Writer::Write<float>(float);
template void Ros1Writer::Write<double>(double);

}  // namespace retrace::logs
