#include "nav/teach_bundle.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "core/angle.hpp"
#include "core/config.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/ros_map.hpp"
#include "io/route_file.hpp"

namespace retrace::nav {
namespace {

namespace fs = std::filesystem;

// Switch poses in switch_poses.txt and last_pose_k.txt must agree this closely (m, rad):
// AutoNavi-style writers print 6 decimals.
constexpr double kPoseAgreement = 1e-6;

fs::path MapYaml(const fs::path& dir, std::size_t k) {
  return dir / "maps" / ("ogm_" + std::to_string(k) + ".yaml");
}
fs::path PathFile(const fs::path& dir, std::size_t k) {
  return dir / "paths" / ("path_" + std::to_string(k) + ".txt");
}
fs::path LastPoseFile(const fs::path& dir, std::size_t k) {
  return dir / ("last_pose_" + std::to_string(k) + ".txt");
}
fs::path SwitchPosesFile(const fs::path& dir) { return dir / "switch_poses.txt"; }
fs::path CountFile(const fs::path& dir) { return dir / "sub_map_num.txt"; }
fs::path RevisitsFile(const fs::path& dir) { return dir / "revisits.txt"; }

std::string PoseLine(const core::Pose2& p) {
  return core::FormatNumber(p.x) + " " + core::FormatNumber(p.y) + " " +
         core::FormatNumber(p.theta) + "\n";
}

// Removes files a previous, longer bundle left in `dir` beyond map n-1, so that the folder
// holds exactly one bundle.
void RemoveStaleMaps(const fs::path& dir, std::size_t n) {
  for (std::size_t k = n;; ++k) {
    const fs::path yaml = MapYaml(dir, k);
    const fs::path files[] = {yaml, fs::path(yaml).replace_extension(".pgm"),
                              fs::path(yaml).replace_extension(".png"), PathFile(dir, k),
                              LastPoseFile(dir, k)};
    bool any = false;
    for (const fs::path& f : files) {
      std::error_code ec;
      if (fs::remove(f, ec)) any = true;
      if (ec) throw core::IoError(f.string() + ": cannot remove stale file: " + ec.message());
    }
    if (!any) return;
  }
}

struct NumberLine {
  int line = 0;
  std::vector<double> values;
};

[[noreturn]] void FailAt(const fs::path& file, int line, const std::string& what) {
  throw core::IoError(file.string() + ":" + std::to_string(line) + ": " + what);
}

// The lines of `file` holding something besides `#` comments and blanks, each split into
// finite numbers.
std::vector<NumberLine> ReadNumberLines(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) throw core::IoError(file.string() + ": file is missing");
  std::ifstream in(file, std::ios::binary);
  if (!in || fs::is_directory(file, ec)) throw core::IoError(file.string() + ": cannot open file");
  std::vector<NumberLine> lines;
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    std::string_view rest(text);
    if (const auto hash = rest.find('#'); hash != std::string_view::npos)
      rest = rest.substr(0, hash);
    NumberLine line{number, {}};
    while (true) {
      const std::size_t begin = rest.find_first_not_of(" \t\r");
      if (begin == std::string_view::npos) break;
      rest.remove_prefix(begin);
      const std::size_t end = std::min(rest.find_first_of(" \t\r"), rest.size());
      const std::string_view token = rest.substr(0, end);
      double v = 0.0;
      const auto [ptr, err] = std::from_chars(token.data(), token.data() + token.size(), v);
      if (err != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v)) {
        // Built by appending: GCC 12 warns falsely (-Wrestrict) on "'" + std::string(...).
        std::string what = "'";
        what += token;
        what += "' is not a finite number";
        FailAt(file, number, what);
      }
      line.values.push_back(v);
      rest.remove_prefix(end);
    }
    if (!line.values.empty()) lines.push_back(std::move(line));
  }
  if (in.bad()) throw core::IoError(file.string() + ": cannot read file");
  return lines;
}

core::Pose2 PoseOf(const NumberLine& line, const fs::path& file) {
  if (line.values.size() != 3) {
    FailAt(file, line.line,
           "expected 3 numbers (x y yaw), got " + std::to_string(line.values.size()));
  }
  return {line.values[0], line.values[1], line.values[2]};
}

std::size_t ReadCount(const fs::path& file) {
  const std::vector<NumberLine> lines = ReadNumberLines(file);
  if (lines.size() != 1 || lines.front().values.size() != 1) {
    throw core::IoError(file.string() + ": expected a single number, the count of partial maps");
  }
  const double n = lines.front().values.front();
  if (!(n >= 1.0) || n != std::floor(n) || n > 1e6) {
    FailAt(file, lines.front().line,
           "the count of partial maps must be a positive integer, got " + core::FormatNumber(n));
  }
  return static_cast<std::size_t>(n);
}

void RequireFile(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw core::IoError(file.string() + ": file is missing");
}

bool SamePose(const core::Pose2& a, const core::Pose2& b) {
  return std::abs(a.x - b.x) <= kPoseAgreement && std::abs(a.y - b.y) <= kPoseAgreement &&
         std::abs(core::AngleDiff(a.theta, b.theta)) <= kPoseAgreement;
}

std::string RevisitsText(const TeachBundle& bundle) {
  std::string text =
      "# retrace teach bundle: the route graph's revisit edges, one per line: maps a < b, the\n"
      "# place's arc length on path a and on path b (m), and map b's frame in map a's as\n"
      "# registered there: x (m) y (m) yaw (rad)\n";
  for (const RevisitEdge& e : bundle.revisits) {
    text += std::to_string(e.a) + " " + std::to_string(e.b) + " " + core::FormatNumber(e.s_a) +
            " " + core::FormatNumber(e.s_b) + " " + PoseLine(e.X_ab);
  }
  return text;
}

// revisits.txt, when there is one (a folder written before the route graph has none: the map
// server links it when it loads it).
void ReadRevisits(const fs::path& dir, TeachBundle* bundle) {
  const fs::path file = RevisitsFile(dir);
  std::error_code ec;
  if (!fs::exists(file, ec)) return;
  const std::size_t n = bundle->maps.size();
  for (const NumberLine& line : ReadNumberLines(file)) {
    const std::vector<double>& v = line.values;
    if (v.size() != 7) {
      FailAt(file, line.line,
             "expected 7 numbers (a b s_a s_b x y yaw), got " + std::to_string(v.size()));
    }
    const auto index = [&](double x) {
      if (!(x >= 0.0) || x != std::floor(x) || x >= static_cast<double>(n)) {
        FailAt(file, line.line, "map index " + core::FormatNumber(x) + " is not one of the " +
                                    std::to_string(n) + " maps");
      }
      return static_cast<std::size_t>(x);
    };
    RevisitEdge e{index(v[0]), index(v[1]), v[2], v[3], core::Pose2(v[4], v[5], v[6])};
    if (!(e.a < e.b)) FailAt(file, line.line, "map a must come before map b");
    bundle->revisits.push_back(e);
  }
  bundle->linked = true;
}

TeachBundle ReadBundleFiles(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw core::IoError("no such folder");
  const std::size_t n = ReadCount(CountFile(dir));

  const fs::path switch_file = SwitchPosesFile(dir);
  const std::vector<NumberLine> switch_lines = ReadNumberLines(switch_file);
  if (switch_lines.size() != n) {
    throw core::IoError(switch_file.string() + ": holds " + std::to_string(switch_lines.size()) +
                        " switch poses, but " + CountFile(dir).filename().string() + " says " +
                        std::to_string(n) + " partial maps");
  }

  TeachBundle bundle;
  bundle.maps.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    PartialMap& map = bundle.maps[k];
    map.X_MS = PoseOf(switch_lines[k], switch_file);

    const fs::path yaml = MapYaml(dir, k);
    RequireFile(yaml);
    map.grid = io::ReadRosMap(yaml);

    const fs::path path_file = PathFile(dir, k);
    RequireFile(path_file);
    map.path = io::ReadPathFile(path_file);

    const fs::path last_file = LastPoseFile(dir, k);
    const std::vector<NumberLine> last = ReadNumberLines(last_file);
    if (last.size() != 1) {
      throw core::IoError(last_file.string() + ": expected one line `x y yaw`, got " +
                          std::to_string(last.size()));
    }
    if (!SamePose(PoseOf(last.front(), last_file), map.X_MS)) {
      throw core::IoError(last_file.string() + ": disagrees with line " +
                          std::to_string(switch_lines[k].line) + " of " +
                          switch_file.filename().string() + " on the switch pose of map " +
                          std::to_string(k));
    }
  }
  ReadRevisits(dir, &bundle);
  return bundle;
}

}  // namespace

void WriteTeachBundle(const fs::path& dir, const TeachBundle& bundle) {
  if (bundle.maps.empty()) {
    throw core::IoError(dir.string() + ": cannot write a teach bundle without partial maps");
  }
  const std::size_t n = bundle.maps.size();
  std::string switch_poses =
      "# retrace teach bundle: the switch pose X_{M_k S} of partial map k (the pose in map k's\n"
      "# frame where map k+1 starts), on data line k+1 (k = 0, 1, ...): x (m) y (m) yaw (rad)\n";
  for (std::size_t k = 0; k < n; ++k) {
    const PartialMap& map = bundle.maps[k];
    if (map.path.empty()) {
      throw core::IoError(PathFile(dir, k).string() + ": cannot write an empty path");
    }
    io::WriteRosMap(MapYaml(dir, k), map.grid);
    io::WritePathFile(PathFile(dir, k), map.path);
    io::WriteFileAtomic(LastPoseFile(dir, k), PoseLine(map.X_MS));  // AutoNavi's layout
    switch_poses += PoseLine(map.X_MS);
  }
  RemoveStaleMaps(dir, n);
  io::WriteFileAtomic(SwitchPosesFile(dir), switch_poses);
  if (bundle.linked) {
    io::WriteFileAtomic(RevisitsFile(dir), RevisitsText(bundle));
  } else {
    std::error_code ec;
    fs::remove(RevisitsFile(dir), ec);
  }
  // Last: a reader that finds the count finds everything it counts.
  io::WriteFileAtomic(CountFile(dir), std::to_string(n) + "\n");
}

TeachBundle ReadTeachBundle(const fs::path& dir) {
  try {
    return ReadBundleFiles(dir);
  } catch (const core::Error& e) {
    throw core::IoError("cannot read teach bundle '" + dir.string() + "': " + e.what());
  }
}

}  // namespace retrace::nav
