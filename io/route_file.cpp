#include "io/route_file.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace retrace::io {
namespace {

[[noreturn]] void FailAt(const std::filesystem::path& path, int line, const std::string& what) {
  throw core::IoError(path.string() + ":" + std::to_string(line) + ": " + what);
}

// 'token' (built by appending: GCC 12 warns falsely on "'" + std::string(...)).
std::string Quoted(std::string_view token) {
  std::string out;
  out.reserve(token.size() + 2);
  out += '\'';
  out += token;
  out += '\'';
  return out;
}

// Splits a line at spaces and tabs into finite numbers; fails on anything else.
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

struct NumberLine {
  int line = 0;
  std::vector<double> values;
};

// The non-empty lines of a file, comments removed, each with the same column count.
std::vector<NumberLine> ReadNumberLines(const std::filesystem::path& path) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ec)) {
    throw core::IoError(path.string() + ": cannot open file");
  }
  std::vector<NumberLine> lines;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::string_view text(line);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (const auto hash = text.find('#'); hash != std::string_view::npos) {
      text = text.substr(0, hash);
    }
    std::vector<double> values = ParseNumbers(text, path, line_number);
    if (values.empty()) continue;
    if (!lines.empty() && values.size() != lines.front().values.size()) {
      FailAt(path, line_number,
             "expected " + std::to_string(lines.front().values.size()) + " columns as on line " +
                 std::to_string(lines.front().line) + ", got " + std::to_string(values.size()));
    }
    lines.push_back({line_number, std::move(values)});
  }
  if (in.bad()) throw core::IoError(path.string() + ": cannot read file");
  return lines;
}

double YawOf(const NumberLine& l, const std::filesystem::path& path) {
  const double qx = l.values[3], qy = l.values[4], qz = l.values[5], qw = l.values[6];
  const double n2 = qx * qx + qy * qy + qz * qz + qw * qw;
  if (!(n2 > 1e-18)) FailAt(path, l.line, "the quaternion is zero");
  return std::atan2(2.0 * (qw * qz + qx * qy) / n2, 1.0 - 2.0 * (qy * qy + qz * qz) / n2);
}

void AppendNumber(std::string& out, double v) {
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  RETRACE_CHECK(ec == std::errc());
  out.append(buf, ptr);
}

}  // namespace

std::vector<core::Vec2> ReadRouteFile(const std::filesystem::path& path) {
  const std::vector<NumberLine> lines = ReadNumberLines(path);
  if (!lines.empty()) {
    const std::size_t columns = lines.front().values.size();
    if (columns != 2 && columns != 7) {
      FailAt(path, lines.front().line,
             "expected 2 columns (x y) or 7 (x y z qx qy qz qw), got " + std::to_string(columns));
    }
  }
  if (lines.size() == 1) {
    FailAt(path, lines.front().line, "a route needs at least 2 waypoints, got 1");
  }
  if (lines.empty())
    throw core::IoError(path.string() + ": a route needs at least 2 waypoints, got 0");
  std::vector<core::Vec2> route;
  route.reserve(lines.size());
  for (const NumberLine& l : lines) route.emplace_back(l.values[0], l.values[1]);
  return route;
}

core::Path ReadPathFile(const std::filesystem::path& path) {
  const std::vector<NumberLine> lines = ReadNumberLines(path);
  if (lines.empty()) throw core::IoError(path.string() + ": the path file holds no poses");
  if (lines.front().values.size() != 7) {
    FailAt(path, lines.front().line,
           "expected 7 columns (x y z qx qy qz qw), got " +
               std::to_string(lines.front().values.size()));
  }
  std::vector<core::Pose2> poses;
  poses.reserve(lines.size());
  for (const NumberLine& l : lines) {
    poses.emplace_back(l.values[0], l.values[1], YawOf(l, path));
  }
  return core::Path(std::move(poses));
}

void WritePathFile(const std::filesystem::path& path, const core::Path& poses) {
  std::string text;
  text.reserve(poses.size() * 80);
  for (const core::Pose2& p : poses.poses()) {
    const std::array<double, 7> values = {
        p.x, p.y, 0.0, 0.0, 0.0, std::sin(0.5 * p.theta), std::cos(0.5 * p.theta)};
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) text += ' ';
      AppendNumber(text, values[i]);
    }
    text += '\n';
  }
  WriteFileAtomic(path, text);
}

}  // namespace retrace::io
