#pragma once
// Reading one storage file of a rosbag2 bag in the SQLite format (the ".db3" files that rosbag2's
// sqlite3 storage plugin writes), without ROS: the `topics` table gives each topic's name, type
// and serialization format, and the `messages` table (id, topic_id, timestamp, data) the
// serialized messages, streamed in timestamp order one row at a time.
//
// All rosbag2 versions are read: old bags have only `topics` (id, name, type,
// serialization_format, and from Foxy on offered_qos_profiles) and `messages`; newer ones add
// type_description_hash to `topics` and the tables `schema` (schema_version, ros_distro),
// `metadata` and `message_definitions`, which retrace does not need. The file is opened read-only
// and never changed.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "logs/raw_message.hpp"

namespace retrace::logs {

/// A rosbag2 SQLite storage file's messages in timestamp order (ties in insertion order).
/// RawMessage.topic, type and encoding come from the message's row of the `topics` table
/// (encoding = serialization_format, "cdr"), log_time_ns is the row's timestamp (the recorder's
/// receive time, ns since the epoch) and data the serialized message.
class SqliteBagReader final : public MessageSource {
 public:
  /// One row of the `topics` table.
  struct Topic {
    std::int64_t id = 0;
    std::string name;                  ///< "/scan"
    std::string type;                  ///< "sensor_msgs/msg/LaserScan"
    std::string serialization_format;  ///< "cdr"
  };

  /// Opens `db3` read-only and reads its topics. Throws core::IoError "<db3>: ..." if the file
  /// cannot be opened, is not a SQLite database, or lacks the `topics` or `messages` table.
  explicit SqliteBagReader(const std::filesystem::path& db3);
  ~SqliteBagReader() override;
  SqliteBagReader(const SqliteBagReader&) = delete;
  SqliteBagReader& operator=(const SqliteBagReader&) = delete;

  /// Throws core::IoError "<db3>: ..." for a message whose topic_id is not in `topics`, whose
  /// data is NULL, or when SQLite reports an error (a corrupt file).
  bool Next(RawMessage& message) override;
  const std::string& name() const override;

  /// The `topics` table, in id order.
  const std::vector<Topic>& topics() const;
  /// `schema.schema_version`, the version of rosbag2's SQLite layout, or 0 for an older bag
  /// without the `schema` table.
  int schema_version() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace retrace::logs
