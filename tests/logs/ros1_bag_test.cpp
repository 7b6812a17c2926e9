#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "logs/log_source.hpp"
#include "logs/ros1_bag_reader.hpp"
#include "logs/ros1_bag_writer.hpp"
#include "logs/ros1_messages.hpp"
#include "tests/support/io_error_of.hpp"
#include "tests/support/ros1_bag_builder.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace ros1_bag_test {

namespace fs = std::filesystem;
using Buffer = std::vector<std::uint8_t>;
using testing::IoErrorOf;
using testing::Ros1BagBuilder;

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A message as read, with copies of the views.
struct Message {
  std::string topic;
  std::string type;
  std::string md5sum;
  std::string encoding;
  std::int64_t log_time_ns = 0;
  Buffer data;
  bool operator==(const Message&) const = default;
};

std::vector<Message> ReadAll(const fs::path& file) {
  Ros1BagReader reader(file);
  std::vector<Message> out;
  RawMessage m;
  while (reader.Next(m)) {
    out.push_back({std::string(m.topic), std::string(m.type), std::string(m.md5sum),
                   std::string(m.encoding), m.log_time_ns, Buffer(m.data.begin(), m.data.end())});
  }
  EXPECT_FALSE(reader.Next(m)) << "the end is sticky";
  return out;
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

// A scan of `beams` beams at `t` s.
ScanMessage Scan(double t, int beams = 100) {
  ScanMessage m;
  m.frame_id = "laser";
  m.scan.stamp = t;
  m.scan.angle_min = -1.0;
  m.scan.angle_increment = 0.02;
  m.scan.range_min = 0.1;
  m.scan.range_max = 30.0;
  for (int i = 0; i < beams; ++i) m.scan.ranges.push_back(1.0f + 0.01f * static_cast<float>(i));
  return m;
}

// 2 s of a drive at 10 Hz (scans, odometry, tf, reference) from t = 1000 s, in chunks of about
// `chunk_bytes`; messages in the order the writer got them.
std::vector<Message> WriteDrive(const fs::path& file, Ros1BagCompression compression,
                                std::size_t chunk_bytes = 4096, bool close = true) {
  Ros1BagWriter w(file, compression, chunk_bytes);
  const std::uint32_t scan = w.AddConnection("/scan", "sensor_msgs/LaserScan");
  const std::uint32_t odom = w.AddConnection("/odom", "nav_msgs/Odometry");
  const std::uint32_t tf = w.AddConnection("/tf", "tf2_msgs/TFMessage");
  const std::uint32_t truth = w.AddConnection("/ground_truth", "geometry_msgs/PoseStamped");
  w.AddConnection("/unused", "nav_msgs/Odometry");  // never written: not in the bag
  std::vector<Message> written;
  const auto put = [&](std::uint32_t conn, const std::string& topic, std::string_view type,
                       std::int64_t ns, const Buffer& data) {
    w.Write(conn, ns, data);
    written.push_back({topic, std::string(type), std::string(Ros1TypeMd5(type)), "ros1", ns, data});
  };
  for (int k = 0; k < 20; ++k) {
    const double t = 1000.0 + 0.1 * k;
    const std::int64_t ns = LogTimeNs(t);
    const core::Pose2 X(0.1 * k, 0.0, 0.01 * k);
    put(scan, "/scan", kRos1LaserScanType, ns, EncodeRos1LaserScan(Scan(t)));
    put(odom, "/odom", kRos1OdometryType, ns, EncodeRos1Odometry({t, "odom", "base_link", X}));
    put(tf, "/tf", kRos1TfMessageType, ns, EncodeRos1TfMessage({{{t, "odom", "base_link", X}}}));
    put(truth, "/ground_truth", kRos1PoseStampedType, ns, EncodeRos1PoseStamped({t, "world", X}));
  }
  if (close) w.Close();
  return written;
}

class Ros1BagRoundTrip : public ::testing::TestWithParam<Ros1BagCompression> {
 protected:
  testing::TempDir tmp_;
};

TEST_P(Ros1BagRoundTrip, WrittenBagReadsBackMessageForMessage) {
  const fs::path bag = tmp_.path() / "drive.bag";
  const std::vector<Message> written = WriteDrive(bag, GetParam());
  EXPECT_EQ(ReadAll(bag), written);
  Ros1BagReader reader(bag);
  EXPECT_TRUE(reader.indexed());
  EXPECT_GT(reader.chunk_count(), 5U);
  EXPECT_TRUE(reader.notes().empty());
}

TEST_P(Ros1BagRoundTrip, CorruptChunkIsRefusedNamingItsOffset) {
  const fs::path bag = tmp_.path() / "drive.bag";
  WriteDrive(bag, GetParam(), 1 << 20);  // one chunk, right after the bag header
  Buffer bytes = FileBytes(bag);
  const std::size_t chunk_at = 13 + 4 + 4096 + 4;  // version line, bag header record
  const std::size_t header_length = bytes[chunk_at] | (bytes[chunk_at + 1] << 8);
  // The start of the chunk's data: the compressed stream's header, or the first record's length.
  const std::size_t data_at = chunk_at + 4 + header_length + 4;
  for (std::size_t i = 0; i < 64; ++i) bytes[data_at + i] ^= 0x5a;
  const std::string error =
      IoErrorOf([&] { ReadAll(WriteBytes(tmp_.path() / "corrupt.bag", bytes)); });
  EXPECT_TRUE(Contains(error, "corrupt.bag: ")) << error;
  EXPECT_TRUE(Contains(error, "at byte " + std::to_string(chunk_at))) << error;
}

INSTANTIATE_TEST_SUITE_P(Compressions, Ros1BagRoundTrip,
                         ::testing::Values(Ros1BagCompression::kNone, Ros1BagCompression::kBz2,
                                           Ros1BagCompression::kLz4),
                         [](const auto& param_info) {
                           switch (param_info.param) {
                             case Ros1BagCompression::kNone:
                               return std::string("None");
                             case Ros1BagCompression::kBz2:
                               return std::string("Bz2");
                             case Ros1BagCompression::kLz4:
                               return std::string("Lz4");
                           }
                           return std::string("Unknown");
                         });

using Ros1BagTest = testing::TempDirTest;

TEST_F(Ros1BagTest, OpenLogKnowsABagByItsVersionLine) {
  const fs::path bag = tmp_.path() / "drive.log";  // the name does not matter
  WriteDrive(bag, Ros1BagCompression::kLz4);
  EXPECT_EQ(DetectLogFormat(bag), LogFormat::kRos1Bag);
  EXPECT_EQ(LogFormatName(LogFormat::kRos1Bag), "ROS 1 bag");
  EXPECT_NE(dynamic_cast<Ros1BagReader*>(OpenLog(bag).get()), nullptr);

  const fs::path old = tmp_.Write("old.bag", Ros1BagBuilder("1.2").Text());
  EXPECT_EQ(DetectLogFormat(old), LogFormat::kRos1Bag);
  EXPECT_EQ(IoErrorOf([&] { OpenLog(old); }),
            old.string() +
                ": a ROS bag of format 1.2; retrace reads format 2.0 (`rosbag filter old.bag "
                "new.bag True` rewrites it so)");
}

TEST_F(Ros1BagTest, ChunksStoredOutOfTimeOrderOrOverlappingAreMerged) {
  // Chunk A: t = 30, 40; chunk B (stored second): 10, 20; chunk C: 25 (within A's span),
  // 35 (on conn 1), and 40 (a tie with A's 40: storage order keeps A's first).
  Ros1BagBuilder b;
  const auto msg = [&](std::uint32_t conn, std::int64_t t) {
    return Ros1BagBuilder::Message(conn, t, Buffer{static_cast<std::uint8_t>(t), 0});
  };
  const Buffer c0 = Ros1BagBuilder::Connection(0, "/a", "nav_msgs/Odometry");
  const Buffer c1 = Ros1BagBuilder::Connection(1, "/b", "nav_msgs/Odometry");
  const std::uint64_t a = b.Chunk({c0, msg(0, 40), msg(0, 30)});  // out of order in the chunk
  const std::uint64_t bb = b.Chunk({msg(0, 10), msg(0, 20)});
  const std::uint64_t c = b.Chunk({c1, msg(0, 25), msg(1, 35), msg(1, 40)});
  b.Index({c0, c1}, {{a, 30, 40, {{0, 2}}}, {bb, 10, 20, {{0, 2}}}, {c, 25, 40, {{0, 1}, {1, 2}}}});
  const std::vector<Message> read = ReadAll(tmp_.Write("merged.bag", b.Text()));
  std::vector<std::pair<std::int64_t, std::string>> order;
  for (const Message& m : read) order.emplace_back(m.log_time_ns, m.topic);
  const std::vector<std::pair<std::int64_t, std::string>> expected = {
      {10, "/a"}, {20, "/a"}, {25, "/a"}, {30, "/a"}, {35, "/b"}, {40, "/a"}, {40, "/b"}};
  EXPECT_EQ(order, expected);
  for (const Message& m : read) EXPECT_EQ(m.data[0], static_cast<std::uint8_t>(m.log_time_ns));
}

TEST_F(Ros1BagTest, EmptyBagHasNoMessages) {
  const fs::path bag = tmp_.path() / "empty.bag";
  Ros1BagWriter(bag, Ros1BagCompression::kBz2).Close();
  EXPECT_TRUE(ReadAll(bag).empty());
}

TEST_F(Ros1BagTest, BagWithoutIndexIsReadByScanningItsChunksWithANote) {
  const fs::path bag = tmp_.path() / "cut.bag";
  const std::vector<Message> written = WriteDrive(bag, Ros1BagCompression::kLz4, 4096, false);
  const std::vector<Message> read = ReadAll(bag);
  // The chunks written before the recording stopped: all but the open one.
  ASSERT_GT(read.size(), written.size() / 2);
  ASSERT_LT(read.size(), written.size());
  EXPECT_TRUE(std::equal(read.begin(), read.end(), written.begin()));
  const Ros1BagReader reader(bag);
  EXPECT_FALSE(reader.indexed());
  ASSERT_EQ(reader.notes().size(), 1U);
  EXPECT_TRUE(Contains(reader.notes()[0], "the bag has no index")) << reader.notes()[0];

  // A chunk that was never closed (sizes 0, records after it), as a killed recorder leaves it.
  Buffer bytes = FileBytes(bag);
  Ros1BagBuilder open;
  open.Chunk({}, "lz4", 0);
  const std::size_t open_at = bytes.size();
  const Buffer& tail = open.bytes();
  bytes.insert(bytes.end(), tail.begin() + static_cast<long>(open.chunk_pos(0)), tail.end());
  bytes.insert(bytes.end(), {0x04, 0x22, 0x4d, 0x18, 0x64, 0x60});  // lz4 data that follows
  const Ros1BagReader unclosed(WriteBytes(tmp_.path() / "unclosed.bag", bytes));
  ASSERT_EQ(unclosed.notes().size(), 2U);
  EXPECT_EQ(unclosed.notes()[1], "its last chunk, at byte " + std::to_string(open_at) +
                                     ", was never closed (" +
                                     std::to_string(bytes.size() - open_at) + " bytes not read)");
  EXPECT_EQ(ReadAll(tmp_.path() / "unclosed.bag"), read);

  // A last chunk that cannot be read (written whole, its data not): the bag is read up to it.
  bytes = FileBytes(bag);
  Ros1BagBuilder garbled;
  garbled.Chunk({Buffer(40, 0xab)}, "lz4", 1000);
  const std::size_t garbled_at = bytes.size();
  bytes.insert(bytes.end(), garbled.bytes().begin() + static_cast<long>(garbled.chunk_pos(0)),
               garbled.bytes().end());
  const Ros1BagReader unreadable(WriteBytes(tmp_.path() / "garbled.bag", bytes));
  ASSERT_EQ(unreadable.notes().size(), 2U);
  EXPECT_TRUE(Contains(unreadable.notes()[1],
                       "lz4 chunk (lz4 data corrupt: ERROR_frameType_unknown) at byte " +
                           std::to_string(garbled_at) + ": the bag is read up to it"))
      << unreadable.notes()[1];
  EXPECT_EQ(ReadAll(tmp_.path() / "garbled.bag"), read);

  // A record cut off by the end of the file.
  bytes = FileBytes(bag);
  bytes.insert(bytes.end(), {200, 0, 0, 0, 1, 2});
  const Ros1BagReader cut(WriteBytes(tmp_.path() / "cutoff.bag", bytes));
  ASSERT_EQ(cut.notes().size(), 2U);
  EXPECT_TRUE(Contains(cut.notes()[1], "it ends in a record cut off at byte")) << cut.notes()[1];
}

TEST_F(Ros1BagTest, TruncatedBagGivesOneErrorNamingTheOffset) {
  const fs::path bag = tmp_.path() / "drive.bag";
  WriteDrive(bag, Ros1BagCompression::kLz4, 2048);
  const Buffer bytes = FileBytes(bag);
  std::uint64_t index_pos = 0;  // the bag header's index_pos field, after "index_pos="
  const std::string text(bytes.begin(), bytes.begin() + 4117);
  const std::size_t field = text.find("index_pos=") + 10;
  for (int i = 7; i >= 0; --i) index_pos = (index_pos << 8) | bytes[field + i];
  ASSERT_GT(index_pos, 10000U);
  // Every chunk boundary (the chunk records' starts) and many points between.
  std::vector<std::size_t> cuts = {0, 5, 13, 20, 4116, 4117, index_pos, index_pos + 1};
  for (std::size_t n = 4117; n < bytes.size(); n += 797) cuts.push_back(n);
  for (std::size_t n = 1; n + 4 < bytes.size(); ++n) {
    if (bytes[n] == 'o' && bytes[n + 1] == 'p' && bytes[n + 2] == '=' && bytes[n + 3] == 0x05)
      cuts.push_back(n - 8);  // the chunk record's header length, before "<len>op=\x05"
  }
  ASSERT_GE(cuts.size(), 8U + 19U + 8U);  // 8 chunks at least
  for (const std::size_t n : cuts) {
    const Buffer prefix(bytes.begin(), bytes.begin() + static_cast<long>(n));
    const fs::path file = WriteBytes(tmp_.path() / "truncated.bag", prefix);
    const std::string error = IoErrorOf([&] { ReadAll(file); });
    ASSERT_TRUE(Contains(error, file.string() + ": ")) << n << ": " << error;
    if (n >= 4117) {  // past the bag header
      EXPECT_TRUE(Contains(error, "truncated: ")) << n << ": " << error;
      EXPECT_TRUE(Contains(error, " at byte ")) << n << ": " << error;
    }
    if (n >= 4117 && n < index_pos) {  // the index is gone
      EXPECT_TRUE(Contains(error, "truncated: the bag header puts the index at byte " +
                                      std::to_string(index_pos) +
                                      ", past the end of the file at byte " + std::to_string(n)))
          << error;
    }
  }
}

TEST_F(Ros1BagTest, IndexThatDisagreesWithItsChunkIsRefused) {
  const Buffer c0 = Ros1BagBuilder::Connection(0, "/a", "nav_msgs/Odometry");
  const Buffer data = {1};
  const auto bag = [&](const std::vector<Ros1BagBuilder::Info>& infos) {
    Ros1BagBuilder b;
    const std::uint64_t pos = b.Chunk({c0, Ros1BagBuilder::Message(0, 50, data)});
    std::vector<Ros1BagBuilder::Info> placed = infos;
    for (auto& info : placed) info.pos = info.pos == 0 ? pos : info.pos;
    b.Index({c0}, placed);
    return tmp_.Write("bad.bag", b.Text());
  };
  EXPECT_TRUE(Contains(IoErrorOf([&] {
                         ReadAll(bag({{0, 50, 50, {{0, 2}}}}));
                       }),
                       "chunk holds 1 messages on connection 0, its chunk info 2 at byte 4117"));
  EXPECT_TRUE(Contains(IoErrorOf([&] {
                         ReadAll(bag({{0, 60, 70, {{0, 1}}}}));
                       }),
                       "chunk holds messages from 50 to 50 ns, outside its chunk info's 60 to 70"));
  EXPECT_TRUE(Contains(IoErrorOf([&] {
                         ReadAll(bag({{0, 50, 50, {{0, 1}}}, {0, 50, 50, {}}}));
                       }),
                       "the index lists the chunk at byte 4117 twice"));
  EXPECT_TRUE(Contains(IoErrorOf([&] {
                         ReadAll(bag({{99, 50, 50, {{0, 1}}}}));
                       }),
                       "the index puts a chunk at byte 99, outside the chunks"));
  EXPECT_TRUE(Contains(IoErrorOf([&] {
                         ReadAll(bag({{0, 70, 60, {{0, 1}}}}));
                       }),
                       "its end_time is before its start_time"));
}

TEST_F(Ros1BagTest, MalformedChunksAreRefusedNamingTheChunk) {
  const Buffer c0 = Ros1BagBuilder::Connection(0, "/a", "nav_msgs/Odometry");
  const Buffer data = {1};
  const auto error_of = [&](const std::vector<Buffer>& records, std::string_view compression,
                            std::int64_t size = -1) {
    Ros1BagBuilder b;
    const std::uint64_t pos = b.Chunk(records, compression, size);
    b.Index({c0}, {{pos, 50, 50, {{0, 1}}}});
    return IoErrorOf([&] { ReadAll(tmp_.Write("bad.bag", b.Text())); });
  };
  const Buffer message = Ros1BagBuilder::Message(0, 50, data);
  EXPECT_TRUE(Contains(error_of({c0, message}, "zstd"),
                       "bad.bag: unsupported chunk compression 'zstd' at byte 4117"));
  EXPECT_TRUE(Contains(error_of({c0, message}, "none", 10),
                       "uncompressed chunk holds " + std::to_string(c0.size() + message.size()) +
                           " bytes but declares 10 at byte 4117"));
  EXPECT_TRUE(Contains(error_of({c0, message}, "bz2"), "bz2 chunk (bz2 data corrupt"));
  EXPECT_TRUE(Contains(error_of({c0, Ros1BagBuilder::Message(3, 50, data)}, "none"),
                       "a message on connection 3, which no connection record declares"));
  Buffer cut = message;
  cut.resize(cut.size() - 1);
  EXPECT_TRUE(Contains(error_of({c0, cut}, "none"), "truncated record at offset"));
  // A header of one field "op=" with an empty value, and no data.
  const Buffer empty_op = {7, 0, 0, 0, 3, 0, 0, 0, 'o', 'p', '=', 0, 0, 0, 0};
  EXPECT_TRUE(Contains(error_of({c0, empty_op}, "none"),
                       "malformed record at offset " + std::to_string(c0.size()) +
                           " of the chunk's records (field 'op' of 0 bytes, not 1) at byte 4117"));
  EXPECT_TRUE(Contains(error_of({c0, message}, "none", 1ll << 31),
                       "chunk declares 2147483648 uncompressed bytes, more than the limit"));
}

TEST_F(Ros1BagTest, MalformedHeaderAndIndexAreRefused) {
  EXPECT_TRUE(Contains(IoErrorOf([&] { ReadAll(tmp_.Write("short.bag", "#ROSBAG V2")); }),
                       "not a ROS bag: too short for the version line"));
  EXPECT_TRUE(Contains(IoErrorOf([&] { ReadAll(tmp_.Write("x.bag", "#ROSBAG V2.0\n\x05")); }),
                       "truncated: the file (14 bytes) ends within the header length of the "
                       "record at byte 13"));
  // An encrypted bag (rosbag's encryptor fields in the bag header).
  logs::internal::Ros1FieldWriter encrypted;
  encrypted.U8("op", 0x03).U64("index_pos", 0).U32("conn_count", 0).U32("chunk_count", 0);
  encrypted.Text("encryptor", "rosbag/AesCbcEncryptor");
  Buffer bytes(logs::internal::kRos1BagMagic.begin(), logs::internal::kRos1BagMagic.end());
  logs::internal::AppendRos1Record(bytes, encrypted.bytes(), Buffer(100, ' '));
  const fs::path secret = WriteBytes(tmp_.path() / "secret.bag", bytes);
  EXPECT_EQ(IoErrorOf([&] { ReadAll(secret); }),
            secret.string() +
                ": an encrypted bag (rosbag/AesCbcEncryptor); retrace reads unencrypted bags "
                "(`rosbag decrypt` decrypts it)");
  // The index lists more records than it holds.
  Ros1BagBuilder b;
  b.Index({}, {}, 2, 1);
  EXPECT_TRUE(Contains(IoErrorOf([&] { ReadAll(tmp_.Write("i.bag", b.Text())); }),
                       "truncated: the file ends after 0 of the index's 2 connection records "
                       "and 0 of its 1 chunk info records at byte 4117"));
  // A connection header without a type.
  Ros1BagBuilder c;
  logs::internal::Ros1FieldWriter header, fields;
  header.U8("op", 0x07).U32("conn", 0).Text("topic", "/a");
  fields.Text("topic", "/a").Text("md5sum", "x");
  Buffer record;
  logs::internal::AppendRos1Record(record, header.bytes(), fields.bytes());
  c.Index({record}, {});
  EXPECT_TRUE(Contains(IoErrorOf([&] { ReadAll(tmp_.Write("c.bag", c.Text())); }),
                       "malformed index record (no 'type' field) at byte 4117"));
}

}  // namespace ros1_bag_test
}  // namespace retrace::logs
