#pragma once
// Opening a log of any supported kind as one MessageSource (logs/raw_message.hpp), chosen by
// its content, not its name:
//   a folder with metadata.yaml            a rosbag2 bag: its files in order (MCAP or SQLite 3)
//   a file named metadata.yaml             the rosbag2 bag of its folder
//   a file starting with MCAP's magic      an MCAP file (ROS 2 bags record these since Iron)
//   a file starting with SQLite's magic    a rosbag2 .db3 file
//   a file starting with "#ROSBAG V"       a ROS 1 bag (.bag; only format 2.0 is read)
//   a gzip file or a text file             a CARMEN log (.log, .clf, plain or gzipped)

#include <filesystem>
#include <memory>
#include <string_view>

#include "logs/raw_message.hpp"

namespace retrace::logs {

enum class LogFormat { kCarmen, kMcap, kSqlite, kRosbag2, kRos1Bag };

/// "CARMEN log", "MCAP file", "rosbag2 SQLite 3 file", "rosbag2 folder", "ROS 1 bag".
std::string_view LogFormatName(LogFormat format);

/// The format of the log at `path`. Throws core::IoError "<path>: ..." when it is missing,
/// unreadable, an empty file, a folder without metadata.yaml, or binary data of no known kind.
LogFormat DetectLogFormat(const std::filesystem::path& path);

/// Opens the log at `path` (format as DetectLogFormat). Throws core::IoError like it, and like
/// the container's reader for a malformed file.
std::unique_ptr<MessageSource> OpenLog(const std::filesystem::path& path);

}  // namespace retrace::logs
