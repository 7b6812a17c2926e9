// The rosbag2 SQLite reader on bags that rosbag2 itself wrote (tests/data/rosbag2, Apache-2.0),
// and on hand-made broken databases. SQLite's C API makes those: libsqlite3 comes with
// retrace::logs (a static library that links it) and its header is a system header.

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "logs/rosbag2_metadata.hpp"
#include "logs/sqlite_bag_reader.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace sqlite_bag_test {

namespace fs = std::filesystem;

const fs::path kBags = fs::path(RETRACE_SOURCE_DIR) / "tests" / "data" / "rosbag2";

struct Message {
  std::string topic;
  std::string type;
  std::string encoding;
  std::int64_t log_time_ns = 0;
  std::vector<std::uint8_t> data;
};

std::vector<Message> ReadAll(const fs::path& db3) {
  SqliteBagReader reader(db3);
  std::vector<Message> out;
  RawMessage m;
  while (reader.Next(m)) {
    out.push_back({std::string(m.topic), std::string(m.type), std::string(m.encoding),
                   m.log_time_ns, std::vector<std::uint8_t>(m.data.begin(), m.data.end())});
  }
  EXPECT_FALSE(reader.Next(m));  // and stays at the end
  return out;
}

// A std_msgs/msg/String in CDR, decoded by hand: a 4-byte encapsulation header (0x00 0x01: CDR
// little-endian), a uint32 length counting the terminating NUL, the bytes and the NUL.
std::string DecodeCdrString(const std::vector<std::uint8_t>& data) {
  EXPECT_GE(data.size(), 8U);
  if (data.size() < 8) return "";
  EXPECT_EQ(data[0], 0x00);
  EXPECT_EQ(data[1], 0x01);
  const std::uint32_t length =
      static_cast<std::uint32_t>(data[4]) | static_cast<std::uint32_t>(data[5]) << 8 |
      static_cast<std::uint32_t>(data[6]) << 16 | static_cast<std::uint32_t>(data[7]) << 24;
  EXPECT_GE(length, 1U);
  EXPECT_LE(8 + length, data.size());
  if (length == 0 || 8 + length > data.size()) return "";
  EXPECT_EQ(data[8 + length - 1], 0x00);
  return std::string(reinterpret_cast<const char*>(data.data() + 8), length - 1);
}

// The IoError message of opening `db3` and reading all of it, or "".
std::string ErrorReading(const fs::path& db3) {
  try {
    ReadAll(db3);
  } catch (const core::IoError& e) {
    return e.what();
  }
  return "";
}

TEST(SqliteBag, ReadsTheTalkerBagInTimestampOrder) {
  const fs::path db3 = kBags / "talker_sqlite3" / "talker.db3";
  {
    SqliteBagReader reader(db3);
    EXPECT_EQ(reader.name(), db3.string());
    EXPECT_EQ(reader.schema_version(), 4);
    ASSERT_EQ(reader.topics().size(), 3U);
    EXPECT_EQ(reader.topics()[0].name, "/rosout");
    EXPECT_EQ(reader.topics()[0].type, "rcl_interfaces/msg/Log");
    EXPECT_EQ(reader.topics()[2].name, "/topic");
    EXPECT_EQ(reader.topics()[2].type, "std_msgs/msg/String");
    EXPECT_EQ(reader.topics()[2].serialization_format, "cdr");
  }
  const std::vector<Message> messages = ReadAll(db3);
  const Rosbag2Metadata meta = ReadRosbag2Metadata(kBags / "talker_sqlite3");
  ASSERT_EQ(messages.size(), meta.message_count);
  EXPECT_EQ(messages.front().log_time_ns, meta.starting_time_ns);
  EXPECT_EQ(messages.back().log_time_ns - messages.front().log_time_ns, meta.duration_ns);

  std::map<std::string, std::uint64_t> counts;
  std::vector<std::string> texts;
  for (std::size_t i = 0; i < messages.size(); ++i) {
    const Message& m = messages[i];
    if (i > 0) {
      EXPECT_GE(m.log_time_ns, messages[i - 1].log_time_ns) << i;
    }
    EXPECT_EQ(m.encoding, "cdr");
    ++counts[m.topic];
    if (m.topic == "/topic") {
      EXPECT_EQ(m.type, "std_msgs/msg/String");
      texts.push_back(DecodeCdrString(m.data));
    } else {
      EXPECT_EQ(m.type, "rcl_interfaces/msg/Log");
    }
  }
  for (const Rosbag2TopicInfo& t : meta.topics)
    EXPECT_EQ(counts[t.name], t.message_count) << t.name;
  ASSERT_EQ(texts.size(), 10U);
  for (std::size_t i = 0; i < texts.size(); ++i) {
    EXPECT_EQ(texts[i], "Hello, world! " + std::to_string(i));
  }
}

TEST(SqliteBag, ReadsTheCdrTestBagOfANewerRosbag2) {
  const fs::path db3 = kBags / "cdr_test_sqlite3" / "cdr_test_0.db3";
  const std::vector<Message> messages = ReadAll(db3);
  const Rosbag2Metadata meta = ReadRosbag2Metadata(kBags / "cdr_test_sqlite3");
  ASSERT_EQ(messages.size(), 7U);
  ASSERT_EQ(messages.size(), meta.message_count);
  std::map<std::string, std::uint64_t> counts;
  for (std::size_t i = 0; i < messages.size(); ++i) {
    if (i > 0) {
      EXPECT_GT(messages[i].log_time_ns, messages[i - 1].log_time_ns) << i;
    }
    ++counts[messages[i].topic];
    EXPECT_EQ(messages[i].type, messages[i].topic == "/test_topic" ? "test_msgs/msg/BasicTypes"
                                                                   : "test_msgs/msg/Arrays");
    EXPECT_EQ(messages[i].data.size(), messages[i].topic == "/test_topic" ? 52U : 696U);
  }
  EXPECT_EQ(counts["/test_topic"], 3U);
  EXPECT_EQ(counts["/array_topic"], 4U);
  for (const Rosbag2TopicInfo& t : meta.topics)
    EXPECT_EQ(counts[t.name], t.message_count) << t.name;
  EXPECT_EQ(messages.front().log_time_ns, meta.starting_time_ns);
  EXPECT_EQ(messages.back().log_time_ns - messages.front().log_time_ns, meta.duration_ns);
}

// ---------------------------------------------------------------------------------------------
// Broken databases

class SqliteBagBroken : public retrace::testing::TempDirTest {
 protected:
  // A database made by running `sql`.
  fs::path Make(const std::string& name, const std::string& sql) const {
    fs::path file = tmp_.path() / name;
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
    char* error = nullptr;
    EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK)
        << (error != nullptr ? error : "");
    sqlite3_free(error);
    sqlite3_close(db);
    return file;
  }

  static constexpr const char* kTables =
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
      "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, "
      "data BLOB);"
      "INSERT INTO topics VALUES (1, '/scan', 'sensor_msgs/msg/LaserScan', 'cdr', '');";
};

TEST_F(SqliteBagBroken, RefusesAFileThatIsNotSqlite) {
  const std::string text = ErrorReading(tmp_.Write("notes.db3", "FLASER 0 0 0 0 0 0 0 1 h 1\n"));
  EXPECT_NE(text.find("notes.db3: not a SQLite database"), std::string::npos) << text;
  const std::string empty = ErrorReading(tmp_.Write("empty.db3", ""));
  EXPECT_NE(empty.find("empty.db3: not a SQLite database"), std::string::npos) << empty;
  const std::string missing = ErrorReading(tmp_.path() / "missing.db3");
  EXPECT_NE(missing.find("missing.db3: cannot open file"), std::string::npos) << missing;
  EXPECT_FALSE(fs::exists(tmp_.path() / "missing.db3"));  // not created by the attempt
  const std::string folder = ErrorReading(tmp_.path());
  EXPECT_NE(folder.find("folder"), std::string::npos) << folder;
  // SQLite's magic followed by garbage.
  std::string garbage("SQLite format 3\0", 16);
  garbage += std::string(4096, '\x7f');
  const std::string corrupt = ErrorReading(tmp_.Write("corrupt.db3", garbage));
  EXPECT_NE(corrupt.find("corrupt.db3: "), std::string::npos) << corrupt;
}

TEST_F(SqliteBagBroken, RefusesADatabaseWithoutRosbag2Tables) {
  const std::string no_messages =
      ErrorReading(Make("no_messages.db3",
                        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, "
                        "serialization_format TEXT);"));
  EXPECT_NE(no_messages.find("no_messages.db3: not a rosbag2 SQLite bag: it has no 'messages' "
                             "table"),
            std::string::npos)
      << no_messages;
  const std::string no_topics =
      ErrorReading(Make("no_topics.db3", "CREATE TABLE messages(id INTEGER PRIMARY KEY);"));
  EXPECT_NE(no_topics.find("no 'topics' table"), std::string::npos) << no_topics;
}

TEST_F(SqliteBagBroken, RefusesUnknownTopicsAndNullData) {
  const std::string unknown = ErrorReading(
      Make("unknown.db3", std::string(kTables) +
                              "INSERT INTO messages VALUES (1, 1, 100, x'00010000');"
                              "INSERT INTO messages VALUES (2, 7, 200, x'00010000');"));
  EXPECT_NE(unknown.find("unknown.db3: message 2 refers to topic_id 7"), std::string::npos)
      << unknown;
  const std::string null_data = ErrorReading(
      Make("null.db3", std::string(kTables) + "INSERT INTO messages VALUES (1, 1, 100, NULL);"));
  EXPECT_NE(null_data.find("null.db3: message 1 (topic /scan) has NULL data"), std::string::npos)
      << null_data;
}

TEST_F(SqliteBagBroken, ReadsAnOldBagWithoutSchemaTableAndEmptyData) {
  const fs::path db3 =
      Make("old.db3", std::string(kTables) +
                          "INSERT INTO messages VALUES (1, 1, 300, x'');"
                          "INSERT INTO messages VALUES (2, 1, 100, x'000100000102');"
                          "INSERT INTO messages VALUES (3, 1, 300, x'00010000');");
  EXPECT_EQ(SqliteBagReader(db3).schema_version(), 0);
  const std::vector<Message> messages = ReadAll(db3);
  ASSERT_EQ(messages.size(), 3U);
  EXPECT_EQ(messages[0].log_time_ns, 100);
  EXPECT_EQ(messages[0].data.size(), 6U);
  EXPECT_EQ(messages[1].log_time_ns, 300);
  EXPECT_TRUE(messages[1].data.empty());  // equal timestamps: in id order
  EXPECT_EQ(messages[2].data.size(), 4U);
  EXPECT_EQ(messages[2].topic, "/scan");
}

}  // namespace sqlite_bag_test
}  // namespace retrace::logs
