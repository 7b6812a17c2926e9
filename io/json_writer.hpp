#pragma once
// JSON files (metrics.json, comparison.json): pretty-printed, atomically written.

#include <filesystem>
#include <nlohmann/json.hpp>

namespace retrace::io {

/// Writes `value` to `path` atomically, pretty-printed with 2-space indentation and a final
/// newline. Numbers use the shortest text that reads back to the same double; NaN and
/// infinities are written as null (JSON has no such numbers); invalid UTF-8 in strings is
/// replaced by U+FFFD. Throws core::IoError if the file cannot be written.
void WriteJsonAtomic(const std::filesystem::path& path, const nlohmann::json& value);

/// Reads and parses a JSON file. Throws core::IoError if the file cannot be read or is not
/// valid JSON (the message names the file, line and column).
nlohmann::json ReadJsonFile(const std::filesystem::path& path);

}  // namespace retrace::io
