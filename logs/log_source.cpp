#include "logs/log_source.hpp"

#include <array>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "logs/carmen_reader.hpp"
#include "logs/mcap_reader.hpp"
#include "logs/ros1_bag_reader.hpp"
#include "logs/rosbag2_metadata.hpp"
#include "logs/sqlite_bag_reader.hpp"

namespace retrace::logs {

namespace {

constexpr std::array<std::uint8_t, 8> kMcapMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};
// The start of a ROS bag's version line, of any format ("#ROSBAG V2.0\n", "#ROSBAG V1.2\n"): the
// reader names a format it does not read.
constexpr std::string_view kRosBagLine{"#ROSBAG V"};

// A rosbag2 folder: the files its metadata lists, one after the other.
class Rosbag2Source final : public MessageSource {
 public:
  explicit Rosbag2Source(const std::filesystem::path& folder)
      : name_(folder.string()), metadata_(ReadRosbag2Metadata(folder)) {}

  bool Next(RawMessage& message) override {
    for (;;) {
      if (!current_) {
        if (next_file_ == metadata_.files.size()) return false;
        const std::filesystem::path& file = metadata_.files[next_file_++];
        if (metadata_.storage_identifier == "mcap") {
          current_ = std::make_unique<McapReader>(file);
        } else {
          current_ = std::make_unique<SqliteBagReader>(file);
        }
      }
      if (current_->Next(message)) return true;
      current_.reset();
    }
  }
  const std::string& name() const override { return name_; }

 private:
  std::string name_;
  Rosbag2Metadata metadata_;
  std::size_t next_file_ = 0;
  std::unique_ptr<MessageSource> current_;
};

}  // namespace

std::string_view LogFormatName(LogFormat format) {
  switch (format) {
    case LogFormat::kCarmen:
      return "CARMEN log";
    case LogFormat::kMcap:
      return "MCAP file";
    case LogFormat::kSqlite:
      return "rosbag2 SQLite 3 file";
    case LogFormat::kRosbag2:
      return "rosbag2 folder";
    case LogFormat::kRos1Bag:
      return "ROS 1 bag";
  }
  return "log";
}

namespace {

// A rosbag2 bag's metadata.yaml stands for its folder: `ros2 bag info` users point at it.
bool IsBagMetadata(const std::filesystem::path& path) {
  std::error_code error;
  return path.filename() == "metadata.yaml" && std::filesystem::is_regular_file(path, error);
}

}  // namespace

LogFormat DetectLogFormat(const std::filesystem::path& path) {
  if (IsBagMetadata(path)) return LogFormat::kRosbag2;
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
    throw core::IoError(path.string() + ": no such file or folder");
  if (std::filesystem::is_directory(status)) {
    if (!std::filesystem::is_regular_file(path / "metadata.yaml", error)) {
      throw core::IoError(path.string() +
                          ": a folder without metadata.yaml is not a rosbag2 bag; give the bag "
                          "folder or one of its .mcap or .db3 files");
    }
    return LogFormat::kRosbag2;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::IoError(path.string() + ": cannot open file");
  std::array<char, 16> head{};
  in.read(head.data(), head.size());
  const std::size_t n = static_cast<std::size_t>(in.gcount());
  if (n == 0) throw core::IoError(path.string() + ": empty file, not a log");
  if (n >= kMcapMagic.size() && std::memcmp(head.data(), kMcapMagic.data(), kMcapMagic.size()) == 0)
    return LogFormat::kMcap;
  if (n == kSqliteMagic.size() && std::string_view(head.data(), n) == kSqliteMagic)
    return LogFormat::kSqlite;
  if (std::string_view(head.data(), n).starts_with(kRosBagLine)) return LogFormat::kRos1Bag;
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(head[i]); };
  if (n >= 2 && byte(0) == 0x1f && byte(1) == 0x8b) return LogFormat::kCarmen;  // gzip
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = byte(i);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t') {
      throw core::IoError(path.string() +
                          ": not a log retrace reads (CARMEN text or gzip, MCAP, rosbag2 SQLite "
                          "3, a rosbag2 folder or a ROS 1 bag)");
    }
  }
  return LogFormat::kCarmen;
}

std::unique_ptr<MessageSource> OpenLog(const std::filesystem::path& path) {
  switch (DetectLogFormat(path)) {
    case LogFormat::kCarmen:
      return std::make_unique<CarmenReader>(path);
    case LogFormat::kMcap:
      return std::make_unique<McapReader>(path);
    case LogFormat::kSqlite:
      return std::make_unique<SqliteBagReader>(path);
    case LogFormat::kRos1Bag:
      return std::make_unique<Ros1BagReader>(path);
    case LogFormat::kRosbag2:
      if (IsBagMetadata(path)) {
        const std::filesystem::path folder = path.parent_path();
        return std::make_unique<Rosbag2Source>(folder.empty() ? "." : folder);
      }
      return std::make_unique<Rosbag2Source>(path);
  }
  throw core::IoError(path.string() + ": unknown log format");
}

}  // namespace retrace::logs
