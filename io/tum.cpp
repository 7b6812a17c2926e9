#include "io/tum.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace retrace::io {
namespace {

void AppendNumber(std::string& out, double v) {
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  RETRACE_CHECK(ec == std::errc());
  out.append(buf, ptr);
}

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

}  // namespace

void WriteTum(const std::filesystem::path& path, const std::vector<StampedPose>& poses) {
  std::string text = "# t x y z qx qy qz qw\n";
  text.reserve(text.size() + poses.size() * 96);
  for (const StampedPose& s : poses) {
    const std::array<double, 8> values = {s.t,
                                          s.pose.x,
                                          s.pose.y,
                                          0.0,
                                          0.0,
                                          0.0,
                                          std::sin(0.5 * s.pose.theta),
                                          std::cos(0.5 * s.pose.theta)};
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) text += ' ';
      AppendNumber(text, values[i]);
    }
    text += '\n';
  }
  WriteFileAtomic(path, text);
}

std::vector<StampedPose> ReadTum(const std::filesystem::path& path) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ec)) {
    throw core::IoError(path.string() + ": cannot open file");
  }
  std::vector<StampedPose> poses;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::string_view text(line);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (const auto hash = text.find('#'); hash != std::string_view::npos) {
      text = text.substr(0, hash);
    }
    const std::vector<double> v = ParseNumbers(text, path, line_number);
    if (v.empty()) continue;
    if (v.size() != 8) {
      FailAt(path, line_number,
             "expected 8 numbers (t x y z qx qy qz qw), got " + std::to_string(v.size()));
    }
    const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
    const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    if (!(norm > 1e-9)) FailAt(path, line_number, "the quaternion is zero");
    // Yaw of the normalised quaternion (z-y-x Euler angles).
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy) / (norm * norm),
                                  1.0 - 2.0 * (qy * qy + qz * qz) / (norm * norm));
    poses.push_back({v[0], core::Pose2(v[1], v[2], yaw)});
  }
  if (in.bad()) throw core::IoError(path.string() + ": cannot read file");
  return poses;
}

}  // namespace retrace::io
