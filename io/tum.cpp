#include "io/tum.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "core/quaternion.hpp"
#include "io/atomic_file.hpp"
#include "io/internal/text_lines.hpp"

namespace retrace::io {

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
      text += core::FormatNumber(values[i]);
    }
    text += '\n';
  }
  WriteFileAtomic(path, text);
}

std::vector<StampedPose> ReadTum(const std::filesystem::path& path) {
  std::vector<StampedPose> poses;
  for (const internal::TextLine& l : internal::ReadTextLines(path)) {
    const std::vector<double> v = internal::ParseNumbers(l.text, path, l.line);
    if (v.size() != 8) {
      internal::FailAt(path, l.line,
                       "expected 8 numbers (t x y z qx qy qz qw), got " + std::to_string(v.size()));
    }
    const std::optional<double> yaw = core::QuaternionYaw(v[4], v[5], v[6], v[7]);
    if (!yaw) internal::FailAt(path, l.line, "the quaternion is zero or not finite");
    poses.push_back({v[0], core::Pose2(v[1], v[2], *yaw)});
  }
  return poses;
}

}  // namespace retrace::io
