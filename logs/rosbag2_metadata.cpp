#include "logs/rosbag2_metadata.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

#include "core/errors.hpp"
#include "io/read_file.hpp"

namespace retrace::logs {
namespace {

// Where a value is, for error messages: the file and a dotted key path.
struct Where {
  std::string file;
  std::string path;

  Where Child(std::string_view key) const {
    return {file, path.empty() ? std::string(key) : path + "." + std::string(key)};
  }
  Where Element(std::size_t i) const { return {file, path + "[" + std::to_string(i) + "]"}; }

  [[noreturn]] void Fail(const YAML::Node& node, const std::string& what) const {
    std::string where = file;
    const YAML::Mark mark = node.Mark();
    if (!mark.is_null() && mark.line >= 0) where += ":" + std::to_string(mark.line + 1);
    throw core::IoError(where + ": " + (path.empty() ? "" : path + ": ") + what);
  }
};

YAML::Node Required(const YAML::Node& parent, std::string_view key, const Where& at) {
  if (!parent.IsMap()) at.Fail(parent, "must be a mapping");
  const YAML::Node node = parent[std::string(key)];
  if (!node) at.Child(key).Fail(parent, "required key is missing");
  return node;
}

std::string ReadString(const YAML::Node& node, const Where& at) {
  if (!node.IsScalar()) at.Fail(node, "must be a string");
  return node.Scalar();
}

std::int64_t ReadInt(const YAML::Node& node, const Where& at) {
  std::int64_t v = 0;
  if (!node.IsScalar() || !YAML::convert<std::int64_t>::decode(node, v)) {
    at.Fail(node, "must be an integer");
  }
  return v;
}

std::uint64_t ReadCount(const YAML::Node& node, const Where& at) {
  std::uint64_t v = 0;
  if (!node.IsScalar() || node.Scalar().starts_with('-') ||
      !YAML::convert<std::uint64_t>::decode(node, v)) {
    at.Fail(node, "must be a non-negative integer");
  }
  return v;
}

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The storage file `relative` (an entry of relative_file_paths) inside `folder`. Up to version
// 3 rosbag2 wrote the bag folder's name as the first component and resolved the path against
// the folder's parent (rosbag2_cpp SequentialReader, resolve_relative_paths); that component is
// dropped here, so the bag still reads after its folder was renamed.
std::filesystem::path Resolve(const std::filesystem::path& folder, const std::string& relative,
                              int version, const YAML::Node& node, const Where& at) {
  const std::filesystem::path p(relative);
  if (relative.empty()) at.Fail(node, "a file path is empty");
  if (p.is_absolute() || p.has_root_path()) {
    at.Fail(node,
            "file path '" + relative + "' is absolute: a bag's files must be inside its folder");
  }
  for (const std::filesystem::path& part : p) {
    if (part == "..") {
      at.Fail(node, "file path '" + relative + "' leads out of the bag's folder ('..')");
    }
  }
  std::filesystem::path inside;
  bool first = true;
  const bool prefixed = version < 4 && std::distance(p.begin(), p.end()) > 1;
  for (const std::filesystem::path& part : p) {
    if (first && prefixed) {
      first = false;
      continue;
    }
    first = false;
    inside /= part;
  }
  return folder / inside;
}

// The parsed metadata.yaml of a bag (not empty); throws core::IoError for invalid YAML.
YAML::Node LoadBagMetadataYaml(const std::filesystem::path& file) {
  const std::string text = io::ReadFileBytes(file);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw core::IoError(file.string() + ":" + std::to_string(e.mark.line + 1) +
                        ": invalid YAML: " + e.msg);
  }
  if (!root || root.IsNull()) throw core::IoError(file.string() + ": file is empty");
  return root;
}

// The metadata version (1..1000).
int ReadBagVersion(const YAML::Node& info, const Where& at) {
  const std::int64_t version = ReadInt(Required(info, "version", at), at.Child("version"));
  if (version < 1 || version > 1000) {
    at.Child("version").Fail(info["version"],
                             "unknown metadata version " + std::to_string(version));
  }
  return static_cast<int>(version);
}

// The storage plugin's name, sqlite3 or mcap (the ones retrace reads).
std::string ReadBagStorage(const YAML::Node& info, const Where& at) {
  std::string storage =
      ReadString(Required(info, "storage_identifier", at), at.Child("storage_identifier"));
  if (storage != "sqlite3" && storage != "mcap") {
    at.Child("storage_identifier")
        .Fail(info["storage_identifier"], "storage '" + storage +
                                              "' is not supported: retrace reads sqlite3 and "
                                              "mcap bags");
  }
  return storage;
}

// The compression format and mode into *meta (required from version 3 on), refusing a
// compressed bag with how to make an uncompressed copy of `folder`.
void ReadBagCompression(const YAML::Node& info, const Where& at,
                        const std::filesystem::path& folder, Rosbag2Metadata* meta) {
  for (const char* key : {"compression_format", "compression_mode"}) {
    const YAML::Node node = info[key];
    if (!node) {
      if (meta->version >= 3) Required(info, key, at);
      continue;
    }
    std::string& out = std::string_view(key) == "compression_format" ? meta->compression_format
                                                                     : meta->compression_mode;
    out = node.IsNull() ? "" : ReadString(node, at.Child(key));
  }
  const std::string mode = Lower(meta->compression_mode);
  if (!mode.empty() && mode != "none") {
    at.Child("compression_mode")
        .Fail(info["compression_mode"] ? info["compression_mode"] : info,
              "the bag is compressed (compression_mode '" + meta->compression_mode +
                  "', compression_format '" + meta->compression_format +
                  "'): retrace reads uncompressed bags only; write an uncompressed copy with "
                  "`ros2 bag convert -i " +
                  folder.string() +
                  " -o out.yaml`, where out.yaml lists one output bag without compression "
                  "(output_bags: [{uri: <new folder>, all_topics: true}])");
  }
}

// The storage files as listed and resolved inside `folder` into *meta (at least one).
void ReadBagFiles(const YAML::Node& info, const Where& at, const std::filesystem::path& folder,
                  Rosbag2Metadata* meta) {
  const YAML::Node files = Required(info, "relative_file_paths", at);
  const Where files_at = at.Child("relative_file_paths");
  if (!files.IsSequence()) files_at.Fail(files, "must be a list");
  if (files.size() == 0) files_at.Fail(files, "the bag lists no storage files");
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string relative = ReadString(files[i], files_at.Element(i));
    meta->relative_file_paths.push_back(relative);
    meta->files.push_back(Resolve(folder, relative, meta->version, files[i], files_at.Element(i)));
  }
}

// One entry of topics_with_message_count: the topic's name, type, format and message count.
Rosbag2TopicInfo ReadBagTopic(const YAML::Node& entry, const Where& t_at) {
  const YAML::Node tm = Required(entry, "topic_metadata", t_at);
  const Where tm_at = t_at.Child("topic_metadata");
  Rosbag2TopicInfo topic;
  topic.name = ReadString(Required(tm, "name", tm_at), tm_at.Child("name"));
  topic.type = ReadString(Required(tm, "type", tm_at), tm_at.Child("type"));
  topic.serialization_format =
      ReadString(Required(tm, "serialization_format", tm_at), tm_at.Child("serialization_format"));
  topic.message_count =
      ReadCount(Required(entry, "message_count", t_at), t_at.Child("message_count"));
  return topic;
}

}  // namespace

Rosbag2Metadata ReadRosbag2Metadata(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "metadata.yaml";
  const YAML::Node root = LoadBagMetadataYaml(file);
  const Where top{file.string(), ""};
  const Where at = top.Child("rosbag2_bagfile_information");
  const YAML::Node info = Required(root, "rosbag2_bagfile_information", top);
  if (!info.IsMap()) at.Fail(info, "must be a mapping");

  Rosbag2Metadata meta;
  meta.version = ReadBagVersion(info, at);
  meta.storage_identifier = ReadBagStorage(info, at);
  // Compression first: a compressed bag's other fields are fine, but it cannot be read.
  ReadBagCompression(info, at, folder, &meta);
  ReadBagFiles(info, at, folder, &meta);

  const YAML::Node duration = Required(info, "duration", at);
  meta.duration_ns = ReadInt(Required(duration, "nanoseconds", at.Child("duration")),
                             at.Child("duration").Child("nanoseconds"));
  const YAML::Node start = Required(info, "starting_time", at);
  meta.starting_time_ns =
      ReadInt(Required(start, "nanoseconds_since_epoch", at.Child("starting_time")),
              at.Child("starting_time").Child("nanoseconds_since_epoch"));
  meta.message_count = ReadCount(Required(info, "message_count", at), at.Child("message_count"));

  const YAML::Node topics = Required(info, "topics_with_message_count", at);
  const Where topics_at = at.Child("topics_with_message_count");
  if (!topics.IsSequence()) topics_at.Fail(topics, "must be a list");
  for (std::size_t i = 0; i < topics.size(); ++i) {
    meta.topics.push_back(ReadBagTopic(topics[i], topics_at.Element(i)));
  }
  return meta;
}

}  // namespace retrace::logs
