#pragma once
// Reading a rosbag2 bag's folder description, `<bag>/metadata.yaml`, without ROS: which storage
// files hold the messages (SQLite .db3 or MCAP), how many messages of which topics, and when.
// The keys are rosbag2's (rosbag2_storage/src/rosbag2_storage/metadata_io.cpp): all versions
// from 1 on are read; compression_format and compression_mode exist from version 3 on, and up to
// version 3 the file names carry the bag folder's name as their first component.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace retrace::logs {

/// One entry of topics_with_message_count.
struct Rosbag2TopicInfo {
  std::string name;                  ///< "/scan"
  std::string type;                  ///< "sensor_msgs/msg/LaserScan"
  std::string serialization_format;  ///< "cdr"
  std::uint64_t message_count = 0;
};

/// `rosbag2_bagfile_information` of a metadata.yaml.
struct Rosbag2Metadata {
  int version = 0;
  std::string storage_identifier;  ///< "sqlite3" or "mcap"
  /// relative_file_paths as written in the file.
  std::vector<std::string> relative_file_paths;
  /// The storage files, in order: relative_file_paths resolved against the bag folder.
  std::vector<std::filesystem::path> files;
  std::int64_t duration_ns = 0;       ///< duration.nanoseconds
  std::int64_t starting_time_ns = 0;  ///< starting_time.nanoseconds_since_epoch
  std::uint64_t message_count = 0;
  std::vector<Rosbag2TopicInfo> topics;  ///< topics_with_message_count
  std::string compression_format;        ///< "" for an uncompressed bag
  std::string compression_mode;          ///< "" (or "NONE") for an uncompressed bag
};

/// Reads `<folder>/metadata.yaml`. Throws core::IoError "<folder>/metadata.yaml[:<line>]: ..."
/// if it is missing or not YAML, a key is missing or of the wrong type, the storage is neither
/// sqlite3 nor mcap, the bag is compressed (retrace reads uncompressed bags only: the message
/// says to run `ros2 bag decompress` or `ros2 bag convert`), or a file path is absolute or leads
/// out of the folder ("..").
Rosbag2Metadata ReadRosbag2Metadata(const std::filesystem::path& folder);

}  // namespace retrace::logs
