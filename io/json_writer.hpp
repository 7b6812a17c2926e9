#pragma once
// JSON files (metrics.json, comparison.json): pretty-printed, atomically written.

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace retrace::io {

/// Writes `value` to `path` atomically, pretty-printed with 2-space indentation and a final
/// newline: every JSON file retrace writes goes through here. Numbers use the shortest text
/// that reads back to the same double; NaN and infinities are written as null (JSON has no
/// such numbers; JsonNumber makes them null in memory already); invalid UTF-8 in strings is
/// replaced by U+FFFD. An ordered_json keeps its keys in insertion order (a file's header fields
/// first). Throws core::IoError if the file cannot be written.
void WriteJsonAtomic(const std::filesystem::path& path, const nlohmann::json& value);
void WriteJsonAtomic(const std::filesystem::path& path, const nlohmann::ordered_json& value);

/// A number as JSON: null when it is NaN or infinite (what the files hold, and what readers of
/// an in-memory document see too).
inline nlohmann::json JsonNumber(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

/// Reads and parses a JSON file. Throws core::IoError if the file cannot be read or is not
/// valid JSON (the message names the file, line and column).
nlohmann::json ReadJsonFile(const std::filesystem::path& path);

}  // namespace retrace::io
