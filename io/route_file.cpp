#include "io/route_file.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/config.hpp"
#include "core/errors.hpp"
#include "core/quaternion.hpp"
#include "io/atomic_file.hpp"
#include "io/internal/text_lines.hpp"

namespace retrace::io {
namespace {

using internal::FailAt;

struct NumberLine {
  int line = 0;
  std::vector<double> values;
};

// The non-empty lines of a file, comments removed, each with the same column count.
std::vector<NumberLine> ReadNumberLines(const std::filesystem::path& path) {
  std::vector<NumberLine> lines;
  for (const internal::TextLine& l : internal::ReadTextLines(path)) {
    std::vector<double> values = internal::ParseNumbers(l.text, path, l.line);
    if (!lines.empty() && values.size() != lines.front().values.size()) {
      FailAt(path, l.line,
             "expected " + std::to_string(lines.front().values.size()) + " columns as on line " +
                 std::to_string(lines.front().line) + ", got " + std::to_string(values.size()));
    }
    lines.push_back({l.line, std::move(values)});
  }
  return lines;
}

double YawOf(const NumberLine& l, const std::filesystem::path& path) {
  const std::optional<double> yaw =
      core::QuaternionYaw(l.values[3], l.values[4], l.values[5], l.values[6]);
  if (!yaw) FailAt(path, l.line, "the quaternion is zero or not finite");
  return *yaw;
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
      text += core::FormatNumber(values[i]);
    }
    text += '\n';
  }
  WriteFileAtomic(path, text);
}

}  // namespace retrace::io
