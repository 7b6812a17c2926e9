#include "logs/rosbag2_metadata.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/errors.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::logs {
// A namespace per file, not an anonymous one: the test files are compiled as one unity source.
namespace rosbag2_metadata_test {

namespace fs = std::filesystem;

const fs::path kBags = fs::path(RETRACE_SOURCE_DIR) / "tests" / "data" / "rosbag2";

TEST(Rosbag2Metadata, ReadsTheTalkerBags) {
  for (const char* storage : {"sqlite3", "mcap"}) {
    const fs::path folder = kBags / (std::string("talker_") + storage);
    const Rosbag2Metadata meta = ReadRosbag2Metadata(folder);
    EXPECT_EQ(meta.version, 4);
    EXPECT_EQ(meta.storage_identifier, storage);
    const std::string file =
        std::string("talker.") + (meta.storage_identifier == "mcap" ? "mcap" : "db3");
    ASSERT_EQ(meta.relative_file_paths.size(), 1U);
    EXPECT_EQ(meta.relative_file_paths[0], file);
    ASSERT_EQ(meta.files.size(), 1U);
    EXPECT_EQ(meta.files[0], folder / file);
    EXPECT_TRUE(fs::exists(meta.files[0]));
    EXPECT_EQ(meta.duration_ns, 4531096768);
    EXPECT_EQ(meta.starting_time_ns, 1585866235112411371);
    EXPECT_EQ(meta.message_count, 20U);
    EXPECT_EQ(meta.compression_format, "");
    EXPECT_EQ(meta.compression_mode, "");
    ASSERT_EQ(meta.topics.size(), 3U);
    std::uint64_t total = 0;
    for (const Rosbag2TopicInfo& t : meta.topics) {
      total += t.message_count;
      EXPECT_EQ(t.serialization_format, "cdr");
      if (t.name == "/topic") {
        EXPECT_EQ(t.type, "std_msgs/msg/String");
        EXPECT_EQ(t.message_count, 10U);
      } else if (t.name == "/rosout") {
        EXPECT_EQ(t.type, "rcl_interfaces/msg/Log");
        EXPECT_EQ(t.message_count, 10U);
      } else {
        EXPECT_EQ(t.name, "/parameter_events");
        EXPECT_EQ(t.type, "rcl_interfaces/msg/ParameterEvent");
        EXPECT_EQ(t.message_count, 0U);
      }
    }
    EXPECT_EQ(total, meta.message_count);
  }
}

TEST(Rosbag2Metadata, ReadsTheCdrTestBags) {
  for (const char* storage : {"sqlite3", "mcap"}) {
    const fs::path folder = kBags / (std::string("cdr_test_") + storage);
    const Rosbag2Metadata meta = ReadRosbag2Metadata(folder);
    EXPECT_EQ(meta.version, 7);
    EXPECT_EQ(meta.storage_identifier, storage);
    ASSERT_EQ(meta.files.size(), 1U);
    EXPECT_TRUE(fs::exists(meta.files[0])) << meta.files[0];
    EXPECT_EQ(meta.message_count, 7U);
    EXPECT_EQ(meta.duration_ns, 151137181);
    EXPECT_EQ(meta.starting_time_ns, 1586406456763032325);
    ASSERT_EQ(meta.topics.size(), 2U);
    EXPECT_EQ(meta.topics[0].name, "/array_topic");
    EXPECT_EQ(meta.topics[0].type, "test_msgs/msg/Arrays");
    EXPECT_EQ(meta.topics[0].message_count, 4U);
    EXPECT_EQ(meta.topics[1].name, "/test_topic");
    EXPECT_EQ(meta.topics[1].type, "test_msgs/msg/BasicTypes");
    EXPECT_EQ(meta.topics[1].message_count, 3U);
  }
}

// ---------------------------------------------------------------------------------------------
// Hand-made metadata.yaml files

class Rosbag2MetadataFile : public retrace::testing::TempDirTest {
 protected:
  // A bag folder whose metadata.yaml has `files` as relative_file_paths, and a compressed bag's
  // compression keys if `compression_mode` is not empty.
  fs::path Bag(const std::string& files, int version = 5,
               const std::string& compression_mode = "") {
    fs::path folder = tmp_.path() / "bag";
    fs::create_directories(folder);
    tmp_.Write("bag/metadata.yaml",
               "rosbag2_bagfile_information:\n"
               "  version: " +
                   std::to_string(version) +
                   "\n"
                   "  storage_identifier: sqlite3\n"
                   "  relative_file_paths:\n" +
                   files +
                   "  duration:\n"
                   "    nanoseconds: 10\n"
                   "  starting_time:\n"
                   "    nanoseconds_since_epoch: 20\n"
                   "  message_count: 1\n"
                   "  topics_with_message_count:\n"
                   "    - topic_metadata:\n"
                   "        name: /scan\n"
                   "        type: sensor_msgs/msg/LaserScan\n"
                   "        serialization_format: cdr\n"
                   "        offered_qos_profiles: ''\n"
                   "      message_count: 1\n"
                   "  compression_format: \"" +
                   (compression_mode.empty() ? "" : "zstd") +
                   "\"\n"
                   "  compression_mode: \"" +
                   compression_mode + "\"\n");
    return folder;
  }

  std::string ErrorFor(const fs::path& folder) {
    try {
      ReadRosbag2Metadata(folder);
    } catch (const core::IoError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(Rosbag2MetadataFile, ReadsAValidFile) {
  const Rosbag2Metadata meta = ReadRosbag2Metadata(Bag("    - bag_0.db3\n    - bag_1.db3\n"));
  ASSERT_EQ(meta.files.size(), 2U);
  EXPECT_EQ(meta.files[1], tmp_.path() / "bag" / "bag_1.db3");
  EXPECT_EQ(meta.topics.at(0).name, "/scan");
  EXPECT_EQ(ReadRosbag2Metadata(Bag("    - sub/bag_0.db3\n")).files[0],
            tmp_.path() / "bag" / "sub" / "bag_0.db3");
}

TEST_F(Rosbag2MetadataFile, DropsTheFolderNameOfBagsUpToVersion3) {
  // Up to version 3 rosbag2 wrote the folder's name before each file name.
  const Rosbag2Metadata meta =
      ReadRosbag2Metadata(Bag("    - recorded_name/recorded_name_0.db3\n", 3));
  EXPECT_EQ(meta.files.at(0), tmp_.path() / "bag" / "recorded_name_0.db3");
  // Version 1 and 2 files have no compression keys.
  const fs::path folder = tmp_.path() / "v1";
  fs::create_directories(folder);
  tmp_.Write("v1/metadata.yaml",
             "rosbag2_bagfile_information:\n  version: 1\n  storage_identifier: sqlite3\n"
             "  relative_file_paths: [v1/v1_0.db3]\n  duration: {nanoseconds: 0}\n"
             "  starting_time: {nanoseconds_since_epoch: 0}\n  message_count: 0\n"
             "  topics_with_message_count: []\n");
  const Rosbag2Metadata v1 = ReadRosbag2Metadata(folder);
  EXPECT_EQ(v1.files.at(0), folder / "v1_0.db3");
  EXPECT_TRUE(v1.topics.empty());
}

TEST_F(Rosbag2MetadataFile, RefusesCompressedBags) {
  for (const char* mode : {"FILE", "MESSAGE"}) {
    const std::string error = ErrorFor(Bag("    - bag_0.db3.zstd\n", 5, mode));
    EXPECT_NE(error.find("metadata.yaml:"), std::string::npos) << error;
    EXPECT_NE(error.find("the bag is compressed (compression_mode '" + std::string(mode) +
                         "', compression_format 'zstd')"),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("ros2 bag convert"), std::string::npos) << error;
  }
  EXPECT_EQ(ErrorFor(Bag("    - bag_0.db3\n", 5, "NONE")), "");
}

TEST_F(Rosbag2MetadataFile, RefusesPathsOutsideTheFolder) {
  const std::string up = ErrorFor(Bag("    - ../x.db3\n"));
  EXPECT_NE(up.find("relative_file_paths[0]: file path '../x.db3' leads out of the bag's folder"),
            std::string::npos)
      << up;
  const std::string deep = ErrorFor(Bag("    - ok.db3\n    - sub/../../x.db3\n"));
  EXPECT_NE(deep.find("relative_file_paths[1]"), std::string::npos) << deep;
  const std::string absolute = ErrorFor(Bag("    - /tmp/x.db3\n"));
  EXPECT_NE(absolute.find("'/tmp/x.db3' is absolute"), std::string::npos) << absolute;
  const std::string none = ErrorFor(Bag("    []\n"));
  EXPECT_NE(none.find("lists no storage files"), std::string::npos) << none;
}

TEST_F(Rosbag2MetadataFile, NamesMissingKeysAndWrongTypes) {
  const fs::path folder = tmp_.path() / "m";
  fs::create_directories(folder);
  tmp_.Write("m/metadata.yaml",
             "rosbag2_bagfile_information:\n  version: 5\n  relative_file_paths: [a.db3]\n");
  const std::string missing = ErrorFor(folder);
  EXPECT_NE(missing.find("m/metadata.yaml:2: rosbag2_bagfile_information.storage_identifier: "
                         "required key is missing"),
            std::string::npos)
      << missing;

  fs::create_directories(tmp_.path() / "bag");
  tmp_.Write("bag/metadata.yaml",
             "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
             "  relative_file_paths: [a.db3]\n  duration: {nanoseconds: 1}\n"
             "  starting_time: {nanoseconds_since_epoch: 1}\n  message_count: -4\n"
             "  topics_with_message_count: []\n  compression_format: ''\n"
             "  compression_mode: ''\n");
  const std::string negative = ErrorFor(tmp_.path() / "bag");
  EXPECT_NE(negative.find("message_count: must be a non-negative integer"), std::string::npos)
      << negative;

  tmp_.Write("bag/metadata.yaml",
             "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: rosbag_v2\n");
  const std::string storage = ErrorFor(tmp_.path() / "bag");
  EXPECT_NE(storage.find("storage 'rosbag_v2' is not supported"), std::string::npos) << storage;

  tmp_.Write("bag/metadata.yaml", "rosbag2_bagfile_information: [unclosed\n");
  EXPECT_NE(ErrorFor(tmp_.path() / "bag").find("invalid YAML"), std::string::npos);
  tmp_.Write("bag/metadata.yaml", "");
  EXPECT_NE(ErrorFor(tmp_.path() / "bag").find("file is empty"), std::string::npos);
  tmp_.Write("bag/metadata.yaml", "other: 1\n");
  EXPECT_NE(ErrorFor(tmp_.path() / "bag").find("rosbag2_bagfile_information: required key"),
            std::string::npos);
  const std::string no_file = ErrorFor(tmp_.path() / "nothing_here");
  EXPECT_NE(no_file.find("nothing_here/metadata.yaml: cannot open file"), std::string::npos)
      << no_file;
}

}  // namespace rosbag2_metadata_test
}  // namespace retrace::logs
