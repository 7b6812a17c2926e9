#include "io/json_writer.hpp"

#include <string>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/read_file.hpp"

namespace retrace::io {

namespace {

template <class Json>
void Write(const std::filesystem::path& path, const Json& value) {
  // nlohmann::json prints non-finite numbers as null and doubles in shortest round-trip form;
  // `replace` keeps a stray non-UTF-8 byte from aborting the write.
  std::string text = value.dump(2, ' ', false, Json::error_handler_t::replace);
  text += '\n';
  WriteFileAtomic(path, text);
}

}  // namespace

void WriteJsonAtomic(const std::filesystem::path& path, const nlohmann::json& value) {
  Write(path, value);
}

void WriteJsonAtomic(const std::filesystem::path& path, const nlohmann::ordered_json& value) {
  Write(path, value);
}

nlohmann::json ReadJsonFile(const std::filesystem::path& path) {
  const std::string text = ReadFileBytes(path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // what() is "[json.exception.parse_error.101] parse error at line L, column C: ...".
    std::string message = e.what();
    const auto bracket = message.find("] ");
    if (bracket != std::string::npos) message.erase(0, bracket + 2);
    throw core::IoError(path.string() + ": invalid JSON: " + message);
  }
}

}  // namespace retrace::io
