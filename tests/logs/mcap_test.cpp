#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.hpp"
#include "logs/cdr.hpp"
#include "logs/internal/byte_reader.hpp"
#include "logs/mcap_reader.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/ros_messages.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace mcap_test {

namespace fs = std::filesystem;
using Buffer = std::vector<std::uint8_t>;
using internal::ByteReader;

const fs::path kBags = fs::path(RETRACE_SOURCE_DIR) / "tests/data/rosbag2";

// A message as read, with copies of the views.
struct Message {
  std::string topic;
  std::string type;
  std::string encoding;
  std::int64_t log_time_ns = 0;
  Buffer data;
  bool operator==(const Message&) const = default;
};

std::vector<Message> ReadAll(const fs::path& file) {
  McapReader reader(file);
  std::vector<Message> out;
  RawMessage m;
  while (reader.Next(m)) {
    out.push_back({std::string(m.topic), std::string(m.type), std::string(m.encoding),
                   m.log_time_ns, Buffer(m.data.begin(), m.data.end())});
  }
  EXPECT_FALSE(reader.Next(m)) << "the end is sticky";
  return out;
}

// The IoError message of reading all of `file`, or "" if it read without one.
std::string ReadError(const fs::path& file) {
  try {
    ReadAll(file);
  } catch (const core::IoError& e) {
    return e.what();
  }
  return "";
}

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

Buffer FileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return Buffer(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

fs::path WriteBytes(const fs::path& file, const Buffer& bytes) {
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return file;
}

// ---- a hand-built MCAP file ---------------------------------------------------------------

class Builder {
 public:
  Builder& U8(std::uint8_t v) { return Int(v, 1); }
  Builder& U16(std::uint16_t v) { return Int(v, 2); }
  Builder& U32(std::uint32_t v) { return Int(v, 4); }
  Builder& U64(std::uint64_t v) { return Int(v, 8); }
  Builder& Str(const std::string& s) {
    U32(static_cast<std::uint32_t>(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    return *this;
  }
  Builder& Raw(const Buffer& b) {
    bytes_.insert(bytes_.end(), b.begin(), b.end());
    return *this;
  }
  Builder& Record(std::uint8_t op, const Builder& body) {
    U8(op).U64(body.bytes_.size());
    return Raw(body.bytes_);
  }
  const Buffer& bytes() const { return bytes_; }

 private:
  Builder& Int(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  Buffer bytes_;
};

const Buffer kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

Builder Start() {
  Builder b;
  b.Raw(kMagic).Record(0x01, Builder().Str("ros2").Str("test"));
  return b;
}

Buffer Finish(Builder b) {
  b.Record(0x0F, Builder().U32(0));
  b.Record(0x02, Builder().U64(0).U64(0).U32(0));
  b.Raw(kMagic);
  return b.bytes();
}

Builder SchemaRecord(std::uint16_t id, const std::string& name) {
  return Builder().U16(id).Str(name).Str("ros2msg").Str("string data\n");
}

Builder ChannelRecord(std::uint16_t id, std::uint16_t schema, const std::string& topic) {
  return Builder().U16(id).U16(schema).Str(topic).Str("cdr").U32(0);
}

Builder MessageRecord(std::uint16_t channel, std::uint64_t time, const Buffer& data) {
  return Builder().U16(channel).U32(0).U64(time).U64(time).Raw(data);
}

Builder ChunkRecord(std::uint64_t size, std::uint32_t crc, const std::string& compression,
                    const Buffer& records) {
  return Builder()
      .U64(0)
      .U64(0)
      .U64(size)
      .U32(crc)
      .Str(compression)
      .U64(records.size())
      .Raw(records);
}

// ---- the records of a written file, walked independently of McapReader --------------------

struct Record {
  std::uint8_t op = 0;
  std::uint64_t offset = 0;  // of the opcode
  std::span<const std::uint8_t> body;
};

std::vector<Record> TopLevelRecords(const Buffer& file) {
  std::vector<Record> out;
  ByteReader r(file);
  r.Skip(8);
  for (;;) {
    Record rec;
    rec.offset = r.offset();
    rec.op = r.U8();
    rec.body = r.Bytes(r.U64());
    out.push_back(rec);
    if (rec.op == 0x02) break;
  }
  EXPECT_EQ(r.remaining(), 8u);
  return out;
}

std::string Text(std::span<const std::uint8_t> std_msgs_string) {
  CdrReader r(std_msgs_string);
  return r.ReadString();
}

// ---- the bags rosbag2 wrote -----------------------------------------------------------------

TEST(McapReader, ReadsTheTalkerBagOfRosbag2) {
  // rosbag2's zstd-compressed talker bag: std_msgs/String "Hello, world! <i>" on /topic and
  // the talker's log lines on /rosout, interleaved (see metadata.yaml beside it).
  const std::vector<Message> all = ReadAll(kBags / "talker_mcap/talker.mcap");
  std::map<std::string, int> count;
  std::vector<std::string> texts;
  for (const Message& m : all) {
    ++count[m.topic];
    EXPECT_EQ(m.encoding, "cdr");
    if (m.topic == "/topic") {
      EXPECT_EQ(m.type, "std_msgs/msg/String");
      texts.push_back(Text(m.data));
    } else {
      EXPECT_EQ(m.type, "rcl_interfaces/msg/Log");
    }
  }
  EXPECT_EQ(count, (std::map<std::string, int>{{"/rosout", 10}, {"/topic", 10}}));
  ASSERT_EQ(texts.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(texts[i], "Hello, world! " + std::to_string(i));
  // starting_time and duration of metadata.yaml.
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front().log_time_ns, 1585866235112411371);
  EXPECT_EQ(all.front().topic, "/rosout");
  EXPECT_EQ(all.back().log_time_ns, 1585866235112411371 + 4531096768);
  EXPECT_EQ(all.back().topic, "/topic");
  EXPECT_EQ(all[1].log_time_ns, 1585866235112609068);
}

// test_msgs/msg/BasicTypes, field by field.
struct BasicTypes {
  bool bool_value = false;
  std::uint8_t byte_value = 0, char_value = 0;
  float float32_value = 0;
  double float64_value = 0;
  std::int8_t int8_value = 0;
  std::uint8_t uint8_value = 0;
  std::int16_t int16_value = 0;
  std::uint16_t uint16_value = 0;
  std::int32_t int32_value = 0;
  std::uint32_t uint32_value = 0;
  std::int64_t int64_value = 0;
  std::uint64_t uint64_value = 0;
  bool operator==(const BasicTypes&) const = default;
};

BasicTypes ReadBasicTypes(CdrReader& r) {
  BasicTypes b;
  b.bool_value = r.ReadBool();
  b.byte_value = r.Read<std::uint8_t>();
  b.char_value = r.Read<std::uint8_t>();
  b.float32_value = r.Read<float>();
  b.float64_value = r.Read<double>();
  b.int8_value = r.Read<std::int8_t>();
  b.uint8_value = r.Read<std::uint8_t>();
  b.int16_value = r.Read<std::int16_t>();
  b.uint16_value = r.Read<std::uint16_t>();
  b.int32_value = r.Read<std::int32_t>();
  b.uint32_value = r.Read<std::uint32_t>();
  b.int64_value = r.Read<std::int64_t>();
  b.uint64_value = r.Read<std::uint64_t>();
  return b;
}

// Checks one test_msgs/msg/Arrays as rosbag2's cdr_test bag holds it, to the last byte.
void ExpectCdrTestArrays(std::span<const std::uint8_t> data) {
  CdrReader r(data);
  EXPECT_TRUE(r.ReadBool());  // bool_values {true, false, true}
  EXPECT_FALSE(r.ReadBool());
  EXPECT_TRUE(r.ReadBool());
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::uint8_t>(), 0);  // byte_values
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::uint8_t>(), 0);  // char_values
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<float>(), 0.0f);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<double>(), 0.0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::int8_t>(), 0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::uint8_t>(), 0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::int16_t>(), 0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::uint16_t>(), 0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::int32_t>(), 0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::uint32_t>(), 0u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::int64_t>(), 0);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::uint64_t>(), 0u);
  EXPECT_EQ(r.ReadString(), "Complex Hello1");  // string_values
  EXPECT_EQ(r.ReadString(), "Complex Hello2");
  EXPECT_EQ(r.ReadString(), "Complex Hello3");
  for (int i = 0; i < 3; ++i) EXPECT_EQ(ReadBasicTypes(r), BasicTypes{});  // basic_types_values
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Read<std::uint8_t>(), 0);  // constants_values: empty structs
  const BasicTypes defaults{true,  50,   100,    1.125f, 1.125,     -50,     200,
                            -1000, 2000, -30000, 60000,  -40000000, 50000000};
  for (int i = 0; i < 3; ++i) EXPECT_EQ(ReadBasicTypes(r), defaults);  // defaults_values
  EXPECT_FALSE(r.ReadBool());  // bool_values_default {false, true, false}
  EXPECT_TRUE(r.ReadBool());
  EXPECT_FALSE(r.ReadBool());
  for (int v : {0, 1, 255}) EXPECT_EQ(r.Read<std::uint8_t>(), v);  // byte_values_default
  for (int v : {0, 1, 127}) EXPECT_EQ(r.Read<std::uint8_t>(), v);  // char_values_default
  for (float v : {1.125f, 0.0f, -1.125f}) EXPECT_EQ(r.Read<float>(), v);
  for (double v : {3.1415, 0.0, -3.1415}) EXPECT_EQ(r.Read<double>(), v);
  for (int v : {0, 127, -128}) EXPECT_EQ(r.Read<std::int8_t>(), v);
  for (int v : {0, 1, 255}) EXPECT_EQ(r.Read<std::uint8_t>(), v);
  for (int v : {0, 32767, -32768}) EXPECT_EQ(r.Read<std::int16_t>(), v);
  for (int v : {0, 1, 65535}) EXPECT_EQ(r.Read<std::uint16_t>(), v);
  for (std::int32_t v : {0, 2147483647, -2147483647 - 1}) EXPECT_EQ(r.Read<std::int32_t>(), v);
  for (std::uint32_t v : {0u, 1u, 4294967295u}) EXPECT_EQ(r.Read<std::uint32_t>(), v);
  EXPECT_EQ(r.Read<std::int64_t>(), 0);
  EXPECT_EQ(r.Read<std::int64_t>(), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(r.Read<std::int64_t>(), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(r.Read<std::uint64_t>(), 0u);
  EXPECT_EQ(r.Read<std::uint64_t>(), 1u);
  EXPECT_EQ(r.Read<std::uint64_t>(), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(r.ReadString(), "");  // string_values_default
  EXPECT_EQ(r.ReadString(), "max value");
  EXPECT_EQ(r.ReadString(), "min value");
  EXPECT_EQ(r.Read<std::int32_t>(), 0);  // alignment_check
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(McapReader, ReadsTheCdrTestBagOfRosbag2) {
  // rosbag2's uncompressed cdr_test bag: 3 test_msgs/msg/BasicTypes on /test_topic (all zero but
  // int32_value = 123, which rosbag2's play test checks) and 4 test_msgs/msg/Arrays on
  // /array_topic (bool_values {true, false, true}, string_values "Complex Hello1..3").
  const std::vector<Message> all = ReadAll(kBags / "cdr_test_mcap/cdr_test_0.mcap");
  std::map<std::string, int> count;
  for (const Message& m : all) {
    ++count[m.topic];
    EXPECT_EQ(m.encoding, "cdr");
    if (m.topic == "/test_topic") {
      EXPECT_EQ(m.type, "test_msgs/msg/BasicTypes");
      CdrReader r(m.data);
      BasicTypes expected;
      expected.int32_value = 123;
      EXPECT_EQ(ReadBasicTypes(r), expected);
      EXPECT_EQ(r.remaining(), 0u);
    } else {
      EXPECT_EQ(m.type, "test_msgs/msg/Arrays");
      ExpectCdrTestArrays(m.data);
    }
  }
  EXPECT_EQ(count, (std::map<std::string, int>{{"/array_topic", 4}, {"/test_topic", 3}}));
  ASSERT_EQ(all.size(), 7u);
  EXPECT_EQ(all.front().log_time_ns, 1586406456763032325);
  EXPECT_EQ(all.back().log_time_ns, 1586406456763032325 + 151137181);
}

// ---- writing -------------------------------------------------------------------------------

// Writes `n` messages alternating over a /scan and an /odom channel (sizes 0 to ~700 bytes)
// and returns them as they should read back.
std::vector<Message> WriteSample(const fs::path& file, McapCompression compression, int n,
                                 std::size_t chunk_bytes = kMcapChunkBytes) {
  McapWriter w(file, compression, "ros2", chunk_bytes);
  const std::uint16_t scan = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
  const std::uint16_t odom = w.AddChannel("/odom", "nav_msgs/msg/Odometry");
  std::vector<Message> expected;
  for (int i = 0; i < n; ++i) {
    const bool is_scan = i % 3 != 2;
    Buffer data(static_cast<std::size_t>((i * 37) % 700));
    for (std::size_t k = 0; k < data.size(); ++k) data[k] = static_cast<std::uint8_t>(i + 7 * k);
    const std::int64_t t = 1'700'000'000'000'000'000 + std::int64_t{i} * 50'000'000 + (i % 5);
    w.Write(is_scan ? scan : odom, t, data);
    expected.push_back({is_scan ? "/scan" : "/odom",
                        is_scan ? "sensor_msgs/msg/LaserScan" : "nav_msgs/msg/Odometry", "cdr", t,
                        data});
  }
  w.Close();
  return expected;
}

// A small valid file for the loops over every byte: two channels of one schema, six messages in
// three chunks.
void WriteSmall(const fs::path& file, McapCompression compression) {
  McapWriter w(file, compression, "ros2", 120);
  const std::uint16_t a = w.AddChannel("/a", "geometry_msgs/msg/PoseStamped");
  const std::uint16_t b = w.AddChannel("/b", "geometry_msgs/msg/PoseStamped");
  for (int i = 0; i < 6; ++i)
    w.Write(i % 2 == 0 ? a : b, 1000 + i, Buffer(16, static_cast<std::uint8_t>(i)));
  w.Close();
}

class McapRoundTrip : public ::testing::TestWithParam<McapCompression> {
 protected:
  testing::TempDir tmp_;
};

TEST_P(McapRoundTrip, ReadsBackEveryMessageExactlyAcrossManyChunks) {
  const fs::path file = tmp_.path() / "out.mcap";
  const std::vector<Message> expected = WriteSample(file, GetParam(), 600, std::size_t{16} * 1024);
  const std::vector<Message> read = ReadAll(file);
  ASSERT_EQ(read.size(), expected.size());
  for (std::size_t i = 0; i < read.size(); ++i) EXPECT_EQ(read[i], expected[i]) << i;
  int chunks = 0;
  const Buffer bytes = FileBytes(file);
  for (const Record& r : TopLevelRecords(bytes)) chunks += r.op == 0x06 ? 1 : 0;
  EXPECT_GE(chunks, 8);
}

// The chunks and message indexes of a written file's data section, by their offsets.
struct DataSection {
  std::map<std::uint64_t, const Record*> chunk_at;
  std::map<std::uint64_t, const Record*> index_at;
  std::uint64_t indexed_messages = 0;
};

std::string_view CompressionName(McapCompression c) {
  return c == McapCompression::kNone ? "" : c == McapCompression::kLz4 ? "lz4" : "zstd";
}

// A Chunk record: its time range, compression, and (uncompressed) size and CRC.
void CheckChunk(const Record& r, McapCompression compression) {
  ByteReader c(r.body);
  const std::uint64_t start = c.U64(), end = c.U64(), size = c.U64();
  const std::uint32_t crc = c.U32();
  EXPECT_LE(start, end);
  const std::string_view name = c.Chars(c.U32());
  EXPECT_EQ(name, CompressionName(compression));
  const std::span<const std::uint8_t> stored = c.Bytes(c.U64());
  EXPECT_TRUE(c.AtEnd());
  if (name.empty()) {
    EXPECT_EQ(stored.size(), size);
    EXPECT_EQ(crc, crc32_z(0, stored.data(), stored.size()));
  }
  EXPECT_NE(crc, 0u);
}

// Data: chunks, each followed by one Message Index per channel it holds; then Data End. *i is
// the first record of the data section, and afterwards the first of the summary.
DataSection CheckDataSection(const std::vector<Record>& records, std::size_t* i,
                             McapCompression compression) {
  DataSection data;
  for (; records[*i].op != 0x0F; ++*i) {
    const Record& r = records[*i];
    if (r.op == 0x06) {
      data.chunk_at[r.offset] = &r;
      CheckChunk(r, compression);
      continue;
    }
    EXPECT_EQ(r.op, 0x07) << "only chunks and message indexes in the data section";
    data.index_at[r.offset] = &r;
    ByteReader m(r.body);
    m.U16();
    const std::uint32_t length = m.U32();
    EXPECT_EQ(length % 16, 0u);
    data.indexed_messages += length / 16;
  }
  ByteReader data_end(records[*i].body);
  EXPECT_EQ(data_end.U32(), 0u);
  ++*i;
  return data;
}

void CheckSchema(const Record& r) {
  ByteReader s(r.body);
  s.U16();
  const std::string name(s.Chars(s.U32()));
  EXPECT_EQ(s.Chars(s.U32()), "ros2msg");
  EXPECT_EQ(s.Chars(s.U32()), RosMessageDefinition(name));
}

void CheckChannel(const Record& r) {
  ByteReader c(r.body);
  c.U16();
  c.U16();
  c.Chars(c.U32());
  EXPECT_EQ(c.Chars(c.U32()), "cdr");
  ByteReader metadata(c.Bytes(c.U32()));
  EXPECT_EQ(metadata.Chars(metadata.U32()), "offered_qos_profiles");
  EXPECT_EQ(metadata.Chars(metadata.U32()), "");
}

// The Statistics record of WriteSample's file: 200 scans on channel 1, 100 odometry on 2.
void CheckStatistics(const Record& r, const std::vector<Message>& expected, std::size_t chunks) {
  ByteReader s(r.body);
  EXPECT_EQ(s.U64(), expected.size());  // messages
  EXPECT_EQ(s.U16(), 2u);               // schemas
  EXPECT_EQ(s.U32(), 2u);               // channels
  EXPECT_EQ(s.U32(), 0u);               // attachments
  EXPECT_EQ(s.U32(), 0u);               // metadata
  EXPECT_EQ(s.U32(), chunks);           // chunks
  EXPECT_EQ(s.U64(), static_cast<std::uint64_t>(expected.front().log_time_ns));
  EXPECT_EQ(s.U64(), static_cast<std::uint64_t>(expected.back().log_time_ns));
  ByteReader counts(s.Bytes(s.U32()));
  EXPECT_EQ(counts.U16(), 1u);
  EXPECT_EQ(counts.U64(), 200u);  // /scan
  EXPECT_EQ(counts.U16(), 2u);
  EXPECT_EQ(counts.U64(), 100u);  // /odom
}

// A Chunk Index: it points at a chunk of the data section and at that chunk's message indexes.
void CheckChunkIndex(const Record& r, const DataSection& data) {
  ByteReader c(r.body);
  c.U64();
  c.U64();
  const std::uint64_t chunk_offset = c.U64(), chunk_length = c.U64();
  ASSERT_EQ(data.chunk_at.count(chunk_offset), 1u);
  const Record& chunk_record = *data.chunk_at.at(chunk_offset);
  EXPECT_EQ(chunk_length, 9 + chunk_record.body.size());
  ByteReader offsets(c.Bytes(c.U32()));
  std::uint64_t index_bytes = 0;
  while (!offsets.AtEnd()) {
    const std::uint16_t channel = offsets.U16();
    const std::uint64_t at = offsets.U64();
    ASSERT_EQ(data.index_at.count(at), 1u);
    ByteReader index(data.index_at.at(at)->body);
    EXPECT_EQ(index.U16(), channel);
    index_bytes += 9 + data.index_at.at(at)->body.size();
  }
  EXPECT_EQ(c.U64(), index_bytes);  // message_index_length
  ByteReader chunk(chunk_record.body);
  chunk.Skip(16);
  const std::uint64_t uncompressed_size = chunk.U64();
  chunk.U32();
  EXPECT_EQ(c.Chars(c.U32()), chunk.Chars(chunk.U32()));  // compression
  EXPECT_EQ(c.U64(), chunk.U64());                        // compressed_size
  EXPECT_EQ(c.U64(), uncompressed_size);
  EXPECT_TRUE(c.AtEnd());
}

using SummaryGroups = std::map<std::uint8_t, std::pair<std::uint64_t, std::uint64_t>>;

// Summary: Schema, Channel, Statistics and Chunk Index records, grouped by opcode. Returns each
// group's start and length; *i ends at the first Summary Offset.
SummaryGroups CheckSummary(const std::vector<Record>& records, std::size_t* i,
                           const DataSection& data, const std::vector<Message>& expected) {
  SummaryGroups groups;  // op -> start, length
  std::uint8_t previous = 0;
  for (; records[*i].op != 0x0E; ++*i) {
    const Record& r = records[*i];
    if (r.op != previous) {
      EXPECT_EQ(groups.count(r.op), 0u) << "records grouped by opcode";
      groups[r.op] = {r.offset, 0};
      previous = r.op;
    }
    groups[r.op].second += 9 + r.body.size();
    switch (r.op) {
      case 0x03: CheckSchema(r); break;
      case 0x04: CheckChannel(r); break;
      case 0x0B: CheckStatistics(r, expected, data.chunk_at.size()); break;
      case 0x08: CheckChunkIndex(r, data); break;
      default: ADD_FAILURE() << "unexpected opcode " << int{r.op} << " in the summary";
    }
  }
  EXPECT_EQ(groups.size(), 4u);
  return groups;
}

TEST_P(McapRoundTrip, WritesTheStructureTheSpecRequires) {
  const fs::path file = tmp_.path() / "out.mcap";
  const std::vector<Message> expected = WriteSample(file, GetParam(), 300, std::size_t{8} * 1024);
  const Buffer bytes = FileBytes(file);
  ASSERT_GE(bytes.size(), 16u);
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), bytes.begin()));
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), bytes.end() - 8));
  const std::vector<Record> records = TopLevelRecords(bytes);

  // Header: profile ros2.
  ASSERT_EQ(records.front().op, 0x01);
  ByteReader header(records.front().body);
  EXPECT_EQ(header.Chars(header.U32()), "ros2");
  EXPECT_EQ(header.Chars(header.U32()), "retrace");

  std::size_t i = 1;
  const DataSection data = CheckDataSection(records, &i, GetParam());
  EXPECT_EQ(data.indexed_messages, expected.size());
  const std::uint64_t summary_start = records[i].offset;
  SummaryGroups groups = CheckSummary(records, &i, data, expected);

  // Summary Offsets (one per group), then the Footer.
  const std::uint64_t summary_offset_start = records[i].offset;
  for (; records[i].op == 0x0E; ++i) {
    ByteReader s(records[i].body);
    const std::uint8_t op = s.U8();
    ASSERT_EQ(groups.count(op), 1u);
    EXPECT_EQ(s.U64(), groups[op].first);
    EXPECT_EQ(s.U64(), groups[op].second);
    groups.erase(op);
  }
  EXPECT_TRUE(groups.empty()) << "a Summary Offset for every group";
  ASSERT_EQ(records[i].op, 0x02);
  ByteReader footer(records[i].body);
  EXPECT_EQ(footer.U64(), summary_start);
  EXPECT_EQ(footer.U64(), summary_offset_start);
  const std::size_t crc_end = static_cast<std::size_t>(records[i].offset) + 9 + 16;
  EXPECT_EQ(footer.U32(), crc32_z(0, bytes.data() + summary_start, crc_end - summary_start));
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapRoundTrip,
                         ::testing::Values(McapCompression::kNone, McapCompression::kLz4,
                                           McapCompression::kZstd),
                         [](const auto& param_info) {
                           switch (param_info.param) {
                             case McapCompression::kNone:
                               return std::string("None");
                             case McapCompression::kLz4:
                               return std::string("Lz4");
                             case McapCompression::kZstd:
                               return std::string("Zstd");
                           }
                           return std::string("?");
                         });

using McapWriterTest = testing::TempDirTest;

TEST_F(McapWriterTest, ClosesChunksAtAboutOneMebibyte) {
  const fs::path file = tmp_.path() / "big.mcap";
  McapWriter w(file, McapCompression::kZstd);
  const std::uint16_t c = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
  const Buffer data(10'000, 0x5A);
  for (int i = 0; i < 300; ++i) w.Write(c, i, data);
  w.Close();
  std::vector<std::uint64_t> sizes;
  const Buffer bytes = FileBytes(file);
  for (const Record& r : TopLevelRecords(bytes)) {
    if (r.op != 0x06) continue;
    ByteReader chunk(r.body);
    chunk.Skip(16);
    sizes.push_back(chunk.U64());
  }
  ASSERT_EQ(sizes.size(), 3u);
  for (std::size_t i = 0; i + 1 < sizes.size(); ++i) {
    EXPECT_GE(sizes[i], kMcapChunkBytes);
    EXPECT_LT(sizes[i], kMcapChunkBytes + 10'100);
  }
  EXPECT_EQ(ReadAll(file).size(), 300u);
}

TEST_F(McapWriterTest, AnEmptyFileReadsAsNoMessages) {
  McapWriter(tmp_.path() / "empty.mcap", McapCompression::kLz4).Close();
  EXPECT_TRUE(ReadAll(tmp_.path() / "empty.mcap").empty());
  McapWriter w(tmp_.path() / "quiet.mcap", McapCompression::kNone);
  w.AddChannel("/tf", "tf2_msgs/msg/TFMessage");
  w.Close();
  w.Close();
  EXPECT_TRUE(ReadAll(tmp_.path() / "quiet.mcap").empty());
}

TEST_F(McapWriterTest, WritesRealMessagesThatDecode) {
  const fs::path file = tmp_.path() / "tf.mcap";
  {
    McapWriter w(file, McapCompression::kZstd);
    const std::uint16_t tf = w.AddChannel("/tf", "tf2_msgs/msg/TFMessage");
    const std::uint16_t pose = w.AddChannel("/pose", "geometry_msgs/msg/PoseStamped");
    TfMessage m;
    m.transforms.push_back({5.5, "odom", "base_link", core::Pose2(1, 2, 0.5)});
    w.Write(tf, 5'500'000'000, EncodeTfMessage(m));
    w.Write(pose, 5'600'000'000, EncodePoseStamped({5.6, "map", core::Pose2(3, 4, -0.5)}));
    w.Close();
  }
  McapReader r(file);
  EXPECT_EQ(r.name(), file.string());
  RawMessage m;
  ASSERT_TRUE(r.Next(m));
  EXPECT_EQ(m.type, kTfMessageType);
  EXPECT_EQ(DecodeTfMessage(m.data).transforms.at(0).child, "base_link");
  ASSERT_TRUE(r.Next(m));
  EXPECT_EQ(m.topic, "/pose");
  EXPECT_EQ(DecodePoseStamped(m.data).pose.y, 4.0);
  EXPECT_FALSE(r.Next(m));
}

TEST_F(McapWriterTest, DeliversMessagesInStorageOrderAndIndexesThemByTime) {
  const fs::path file = tmp_.path() / "order.mcap";
  {
    McapWriter w(file, McapCompression::kLz4);
    const std::uint16_t c = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
    for (std::int64_t t : {30, 10, 20}) w.Write(c, t, Buffer{static_cast<std::uint8_t>(t)});
    w.Close();
  }
  std::vector<std::int64_t> times;
  for (const Message& m : ReadAll(file)) {
    times.push_back(m.log_time_ns);
    EXPECT_EQ(m.data, Buffer{static_cast<std::uint8_t>(m.log_time_ns)});
  }
  EXPECT_EQ(times, (std::vector<std::int64_t>{30, 10, 20}));
  const Buffer bytes = FileBytes(file);
  const std::vector<Record> records = TopLevelRecords(bytes);
  ASSERT_EQ(records.at(2).op, 0x07);
  ByteReader index(records[2].body);
  index.U16();
  index.U32();
  std::vector<std::uint64_t> indexed;
  while (!index.AtEnd()) {
    indexed.push_back(index.U64());
    index.U64();
  }
  EXPECT_EQ(indexed, (std::vector<std::uint64_t>{10, 20, 30}));
  ByteReader chunk(records[1].body);
  EXPECT_EQ(chunk.U64(), 10u);  // message_start_time
  EXPECT_EQ(chunk.U64(), 30u);  // message_end_time
}

TEST_F(McapWriterTest, RefusesMisuse) {
  McapWriter w(tmp_.path() / "x.mcap", McapCompression::kNone);
  EXPECT_THROW(w.AddChannel("/chatter", "std_msgs/msg/String"), std::invalid_argument);
  const std::uint16_t c = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
  EXPECT_THROW(w.Write(c + 1, 0, {}), std::invalid_argument);
  try {
    w.Write(c, -1, {});
    ADD_FAILURE() << "no error for a negative time";
  } catch (const core::IoError& e) {
    EXPECT_TRUE(Contains(e.what(), "log time -1 ns is negative")) << e.what();
  }
  try {
    McapWriter unwritable(tmp_.path() / "missing_folder" / "x.mcap", McapCompression::kNone);
    ADD_FAILURE() << "no error for a missing folder";
  } catch (const core::IoError& e) {
    EXPECT_TRUE(Contains(e.what(), "missing_folder/x.mcap: cannot create the file")) << e.what();
  }
}

TEST_F(McapWriterTest, AFileNotClosedIsRefusedAsTruncated) {
  const fs::path file = tmp_.path() / "crashed.mcap";
  {
    McapWriter w(file, McapCompression::kNone, "ros2", 100);
    const std::uint16_t c = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
    for (int i = 0; i < 10; ++i) w.Write(c, i, Buffer(50, 1));
  }
  EXPECT_TRUE(Contains(ReadError(file), "no trailing MCAP magic")) << ReadError(file);
}

// ---- hand-built files and bad input ---------------------------------------------------------

TEST_F(McapWriterTest, ReadsMessagesOutsideChunksAndSkipsOtherRecords) {
  Builder b = Start();
  b.Record(0x03, SchemaRecord(1, "geometry_msgs/msg/PoseStamped"));
  b.Record(0x03, SchemaRecord(0, "ignored"));
  b.Record(0x04, ChannelRecord(3, 1, "/pose"));
  b.Record(0x04, ChannelRecord(4, 0, "/raw"));  // no schema
  b.Record(0x80, Builder().U64(123));           // an application's own record
  b.Record(0x09,
           Builder().U64(1).U64(2).Str("a.txt").Str("text/plain").U64(3).Raw({1, 2, 3}).U32(0));
  b.Record(0x0C, Builder().Str("meta").U32(0));
  b.Record(0x05, MessageRecord(3, 42, {9, 8, 7}));
  b.Record(0x05, MessageRecord(4, 43, {}));
  const std::vector<Message> read = ReadAll(WriteBytes(tmp_.path() / "hand.mcap", Finish(b)));
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0], (Message{"/pose", "geometry_msgs/msg/PoseStamped", "cdr", 42, {9, 8, 7}}));
  EXPECT_EQ(read[1], (Message{"/raw", "", "cdr", 43, {}}));
}

TEST_F(McapWriterTest, EveryTruncationIsRefused) {
  for (McapCompression c : {McapCompression::kNone, McapCompression::kZstd}) {
    const fs::path file = tmp_.path() / "small.mcap";
    WriteSmall(file, c);
    const Buffer full = FileBytes(file);
    ASSERT_EQ(ReadAll(file).size(), 6u);
    int chunks = 0;
    for (const Record& r : TopLevelRecords(full)) chunks += r.op == 0x06 ? 1 : 0;
    ASSERT_EQ(chunks, 3);
    // Cut shorter and shorter in place (rewriting a file thousands of times is slow on disk).
    const fs::path cut = WriteBytes(tmp_.path() / "cut.mcap", full);
    for (std::size_t n = full.size(); n-- > 0;) {
      fs::resize_file(cut, n);
      const std::string error = ReadError(cut);
      EXPECT_TRUE(Contains(error, cut.string() + ": ")) << n << ": '" << error << "'";
      EXPECT_TRUE(Contains(error, " at byte ")) << n << ": '" << error << "'";
    }
  }
}

TEST_F(McapWriterTest, CorruptBytesGiveAnIoErrorOrMessagesNeverACrash) {
  const fs::path file = tmp_.path() / "small.mcap";
  WriteSmall(file, McapCompression::kZstd);
  const Buffer full = FileBytes(file);
  const fs::path bad = WriteBytes(tmp_.path() / "bad.mcap", full);
  std::fstream patch(bad, std::ios::in | std::ios::out | std::ios::binary);
  const auto put = [&](std::size_t at, std::uint8_t byte) {
    patch.seekp(static_cast<std::streamoff>(at));
    patch.put(static_cast<char>(byte));
    patch.flush();
  };
  int refused = 0;
  for (std::size_t n = 0; n < full.size(); ++n) {
    put(n, full[n] ^ 0xFF);
    try {
      ReadAll(bad);
    } catch (const core::IoError&) {
      ++refused;
    }
    put(n, full[n]);
  }
  EXPECT_GT(refused, static_cast<int>(full.size()) / 4);
}

TEST_F(McapWriterTest, RefusesWrongMagicAndMissingFiles) {
  Buffer bytes = Finish(Start());
  ASSERT_TRUE(ReadAll(WriteBytes(tmp_.path() / "ok.mcap", bytes)).empty());
  bytes[4] = 'Q';
  const fs::path bad = WriteBytes(tmp_.path() / "bad.mcap", bytes);
  EXPECT_EQ(ReadError(bad), bad.string() + ": not an MCAP file: wrong magic at byte 0");
  const fs::path none = tmp_.path() / "none.mcap";
  EXPECT_EQ(ReadError(none), none.string() + ": cannot open the file");
  const fs::path tiny = WriteBytes(tmp_.path() / "tiny.mcap", {0x89, 'M'});
  EXPECT_TRUE(Contains(ReadError(tiny), "too short for the magic at byte 0"));
}

TEST_F(McapWriterTest, RefusesAChunkDeclaringAHugeSize) {
  Builder b = Start();
  b.Record(0x06, ChunkRecord(100'000'000'000ull, 0, "zstd", Buffer(16, 0)));
  const fs::path file = WriteBytes(tmp_.path() / "huge.mcap", Finish(b));
  EXPECT_EQ(ReadError(file), file.string() +
                                 ": chunk declares 100000000000 uncompressed bytes, more than "
                                 "the limit of 1073741824 at byte 33");
}

TEST_F(McapWriterTest, RefusesAChunkWhoseCrcDoesNotMatch) {
  const fs::path file = tmp_.path() / "crc.mcap";
  WriteSample(file, McapCompression::kNone, 3);
  Buffer bytes = FileBytes(file);
  const Record chunk = TopLevelRecords(bytes).at(1);
  ASSERT_EQ(chunk.op, 0x06);
  bytes[chunk.offset + 9 + 8 + 8 + 8 + 4 + 4 + 8 + 20] ^= 0x01;  // a byte of its records
  WriteBytes(file, bytes);
  EXPECT_TRUE(Contains(ReadError(file), "chunk CRC mismatch: stored 0x")) << ReadError(file);
  EXPECT_TRUE(Contains(ReadError(file), " at byte " + std::to_string(chunk.offset)));
}

// The only chunk of a file the writer compressed with `c`: its declared uncompressed size, its
// compression's name and its compressed bytes.
struct CompressedChunk {
  std::uint64_t size = 0;
  std::string compression;
  Buffer data;
};

CompressedChunk WrittenChunk(const fs::path& file, McapCompression c) {
  {
    McapWriter w(file, c);
    const std::uint16_t id = w.AddChannel("/y", "sensor_msgs/msg/LaserScan");
    w.Write(id, 5, Buffer(300, 3));
    w.Close();
  }
  const Buffer written = FileBytes(file);
  ByteReader r(TopLevelRecords(written).at(1).body);
  r.Skip(16);
  CompressedChunk chunk;
  chunk.size = r.U64();
  r.U32();
  chunk.compression = r.Chars(r.U32());
  const std::span<const std::uint8_t> stored = r.Bytes(r.U64());
  chunk.data.assign(stored.begin(), stored.end());
  return chunk;
}

TEST_F(McapWriterTest, RefusesCompressedChunksCutShortMisdeclaredOrCorrupt) {
  for (McapCompression c : {McapCompression::kLz4, McapCompression::kZstd}) {
    const CompressedChunk chunk = WrittenChunk(tmp_.path() / "compressed.mcap", c);
    const std::uint64_t size = chunk.size;
    const std::string& compression = chunk.compression;
    const Buffer& data = chunk.data;
    // The file of one chunk holding `stored` and declaring `declared` uncompressed bytes.
    const auto error = [&](const char* name, std::uint64_t declared, const Buffer& stored) {
      Builder b = Start();
      b.Record(0x06, ChunkRecord(declared, 0, compression, stored));
      return ReadError(WriteBytes(tmp_.path() / name, Finish(b)));
    };
    EXPECT_TRUE(Contains(error("cut.mcap", size, Buffer(data.begin(), data.end() - 5)),
                         "chunk: " + compression + " data"))
        << compression;
    EXPECT_TRUE(Contains(error("small.mcap", size - 10, data),
                         "holds more than the declared " + std::to_string(size - 10) + " bytes"))
        << compression;
    EXPECT_TRUE(Contains(error("large.mcap", size + 10, data),
                         "the chunk declares " + std::to_string(size + 10)))
        << compression;
    EXPECT_TRUE(Contains(error("garbage.mcap", size, Buffer(data.size(), 0xAB)),
                         compression + " data corrupt"))
        << compression;
  }
}

TEST_F(McapWriterTest, RefusesAnUnknownCompressionAndAMisdeclaredPlainChunk) {
  Builder records;
  records.Record(0x03, SchemaRecord(1, "x/msg/Y"));
  records.Record(0x04, ChannelRecord(1, 1, "/y"));
  records.Record(0x05, MessageRecord(1, 5, Buffer(300, 3)));
  const Buffer plain = records.bytes();
  const fs::path tmp = tmp_.path() / "plain.mcap";
  Builder unknown = Start();
  unknown.Record(0x06, ChunkRecord(plain.size(), 0, "brotli", plain));
  EXPECT_TRUE(Contains(ReadError(WriteBytes(tmp, Finish(unknown))),
                       "unsupported chunk compression 'brotli' at byte 33"));
  Builder mismatch = Start();
  mismatch.Record(0x06, ChunkRecord(plain.size() + 1, 0, "", plain));
  EXPECT_TRUE(Contains(ReadError(WriteBytes(tmp, Finish(mismatch))),
                       "uncompressed chunk holds " + std::to_string(plain.size()) +
                           " bytes but declares " + std::to_string(plain.size() + 1)));
  Builder ok = Start();
  ok.Record(0x06, ChunkRecord(plain.size(),
                              static_cast<std::uint32_t>(crc32_z(0, plain.data(), plain.size())),
                              "", plain));
  EXPECT_EQ(ReadAll(WriteBytes(tmp, Finish(ok))).size(), 1u);
}

TEST_F(McapWriterTest, RefusesBadReferencesAndLengths) {
  const fs::path file = tmp_.path() / "bad.mcap";
  {
    Builder b = Start();
    b.Record(0x05, MessageRecord(7, 1, {1}));
    EXPECT_EQ(ReadError(WriteBytes(file, Finish(b))),
              file.string() + ": Message on unknown channel 7 at byte 33");
  }
  {
    Builder b = Start();
    b.Record(0x04, ChannelRecord(2, 9, "/scan"));
    EXPECT_EQ(ReadError(WriteBytes(file, Finish(b))),
              file.string() + ": Channel 2 (/scan) refers to unknown schema 9 at byte 33");
  }
  {
    // The same inside a chunk.
    Builder records;
    records.Record(0x05, MessageRecord(7, 1, {1}));
    Builder b = Start();
    b.Record(0x06, ChunkRecord(records.bytes().size(), 0, "", records.bytes()));
    EXPECT_EQ(ReadError(WriteBytes(file, Finish(b))),
              file.string() +
                  ": Message on unknown channel 7 at offset 0 of the records of the chunk at "
                  "byte 33");
  }
  {
    Builder b = Start();
    b.U8(0x05).U64(std::uint64_t{1} << 40);
    const std::string error = ReadError(WriteBytes(file, Finish(b)));
    EXPECT_TRUE(Contains(error,
                         "Message record of 1099511627776 bytes runs past the end of the "
                         "file"))
        << error;
  }
  {
    Builder b = Start();
    b.Record(0x04, Builder().U16(1).U16(0).U32(100));  // topic length beyond the record
    const std::string error = ReadError(WriteBytes(file, Finish(b)));
    EXPECT_TRUE(Contains(error,
                         "malformed Channel record (truncated: needs 100 bytes at byte 8, "
                         "0 left) at byte 33"))
        << error;
  }
  {
    Builder b;
    b.Raw(kMagic).Record(0x05, MessageRecord(1, 1, {}));
    const std::string error = ReadError(WriteBytes(file, Finish(b)));
    EXPECT_TRUE(Contains(error, "expected a Header record, found Message at byte 8")) << error;
  }
  {
    // A Data End missing: the records run into the Footer, which also ends the data.
    Builder b = Start();
    b.Record(0x02, Builder().U64(0).U64(0).U32(0));
    b.Raw(kMagic);
    EXPECT_TRUE(ReadAll(WriteBytes(file, b.bytes())).empty());
  }
}

}  // namespace mcap_test
}  // namespace retrace::logs
