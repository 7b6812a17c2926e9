#include "io/internal/text_lines.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <system_error>

#include "core/errors.hpp"

namespace retrace::io::internal {

void FailAt(const std::filesystem::path& path, int line, const std::string& what) {
  throw core::IoError(path.string() + ":" + std::to_string(line) + ": " + what);
}

// Built by appending: GCC 12 warns falsely on "'" + std::string(...).
std::string Quoted(std::string_view token) {
  std::string out;
  out.reserve(token.size() + 2);
  out += '\'';
  out += token;
  out += '\'';
  return out;
}

std::vector<double> ParseNumbers(std::string_view text, const std::filesystem::path& path,
                                 int line) {
  std::vector<double> out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == ' ' || text[i] == '\t') {
      ++i;
      continue;
    }
    const std::size_t end = text.find_first_of(" \t", i);
    const std::string_view token =
        text.substr(i, end == std::string_view::npos ? std::string_view::npos : end - i);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
      FailAt(path, line, Quoted(token) + " is not a number");
    }
    if (!std::isfinite(v)) FailAt(path, line, Quoted(token) + " is not finite");
    out.push_back(v);
    i += token.size();
  }
  return out;
}

std::vector<TextLine> ReadTextLines(const std::filesystem::path& path) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ec)) {
    throw core::IoError(path.string() + ": cannot open file");
  }
  std::vector<TextLine> lines;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::string_view text(line);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (const auto hash = text.find('#'); hash != std::string_view::npos) {
      text = text.substr(0, hash);
    }
    // Blank means what ParseNumbers skips: spaces and tabs only.
    if (text.find_first_not_of(" \t") == std::string_view::npos) continue;
    lines.push_back({line_number, std::string(text)});
  }
  if (in.bad()) throw core::IoError(path.string() + ": cannot read file");
  return lines;
}

}  // namespace retrace::io::internal
