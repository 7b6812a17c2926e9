#include "logs/carmen_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/limits.hpp"

namespace retrace::logs {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Blanks are ' ', '\t', '\r', '\v' and '\f' (all at or below ' ').
bool IsBlank(char c) {
  return static_cast<unsigned char>(c) <= ' ' &&
         (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f');
}

// Splits at blanks into `out` (cleared first), keeping views into `line`.
void Tokenize(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  const char* p = line.data();
  const char* const end = p + line.size();
  while (p != end) {
    while (p != end && IsBlank(*p)) ++p;
    const char* start = p;
    while (p != end && static_cast<unsigned char>(*p) > ' ') ++p;
    while (p != end && !IsBlank(*p)) {  // other control characters belong to the token
      ++p;
      while (p != end && static_cast<unsigned char>(*p) > ' ') ++p;
    }
    if (p > start) out.emplace_back(start, static_cast<std::size_t>(p - start));
  }
}

// A token of at most this many characters in error messages.
std::string Shown(std::string_view token) {
  constexpr std::size_t kMax = 40;
  // Appended piece by piece: GCC 12 at -O3 misreads `"'" + std::string(...)` as an overflow.
  std::string out(1, '\'');
  out.append(token.substr(0, kMax));
  if (token.size() > kMax) out.append("...");
  out.push_back('\'');
  return out;
}

// The whole token as a double (any finite or non-finite value), or nullopt.
std::optional<double> ToDouble(std::string_view token) {
  double v = 0.0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;  // strtod (CARMEN's reader) accepts a '+'
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (ec != std::errc() || ptr != last || first == last) return std::nullopt;
  return v;
}

bool IsFiniteNumber(std::string_view token) {
  const std::optional<double> v = ToDouble(token);
  return v.has_value() && std::isfinite(*v);
}

// Decimal seconds ("1234.000246") to nanoseconds, exactly for plain decimals with up to nine
// fractional digits (further digits are cut), via double for other spellings ("1.2e3"). nullopt
// if the token is not a finite number or out of the int64 range.
std::optional<std::int64_t> SecondsToNs(std::string_view token) {
  constexpr std::int64_t kMaxSeconds = std::numeric_limits<std::int64_t>::max() / 1'000'000'000 - 1;
  std::string_view s = token;
  bool negative = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) {
    negative = s[0] == '-';
    s.remove_prefix(1);
  }
  const std::size_t dot = s.find('.');
  const std::string_view whole = s.substr(0, dot);
  const std::string_view frac =
      dot == std::string_view::npos ? std::string_view{} : s.substr(dot + 1);
  const auto all_digits = [](std::string_view d) {
    return std::all_of(d.begin(), d.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (!whole.empty() && whole.size() <= 11 && all_digits(whole) && all_digits(frac)) {
    std::int64_t seconds = 0;
    for (char c : whole) seconds = seconds * 10 + (c - '0');
    if (seconds > kMaxSeconds) return std::nullopt;
    std::int64_t ns = seconds * 1'000'000'000;
    std::int64_t scale = 100'000'000;
    for (std::size_t i = 0; i < frac.size() && scale > 0; ++i, scale /= 10) {
      ns += (frac[i] - '0') * scale;
    }
    return negative ? -ns : ns;
  }
  const std::optional<double> v = ToDouble(token);
  if (!v || !std::isfinite(*v) || std::abs(*v) >= static_cast<double>(kMaxSeconds)) {
    return std::nullopt;
  }
  return static_cast<std::int64_t>(std::llround(*v * 1e9));
}

// The fields of one line being decoded, with the checks every field gets.
class Fields {
 public:
  // The token list is reused from line to line (a scan line has a thousand fields and more).
  explicit Fields(std::string_view line) : tokens_(Buffer()) { Tokenize(line, tokens_); }
  Fields(const Fields&) = delete;
  Fields& operator=(const Fields&) = delete;

  std::size_t size() const { return tokens_.size(); }
  std::string_view name() const { return tokens_.empty() ? std::string_view{} : tokens_[0]; }
  std::string_view operator[](std::size_t i) const { return tokens_[i]; }

  [[noreturn]] void Fail(const std::string& what) const {
    throw core::IoError(std::string(name()) + ": " + what);
  }

  // Field i as a finite number; `what` names it in errors.
  double Number(std::size_t i, std::string_view what) const {
    if (i >= tokens_.size()) Fail("missing " + std::string(what));
    const std::optional<double> v = ToDouble(tokens_[i]);
    if (!v) Fail(std::string(what) + " " + Shown(tokens_[i]) + " is not a number");
    if (!std::isfinite(*v)) Fail(std::string(what) + " " + Shown(tokens_[i]) + " is not finite");
    return *v;
  }

  core::Pose2 Pose(std::size_t i, std::string_view what) const {
    const std::string w(what);
    const double x = Number(i, w + " x");
    const double y = Number(i + 1, w + " y");
    const double theta = Number(i + 2, w + " theta");
    return {x, y, theta};
  }

  // Field i as a count of the fields that follow it: a non-negative integer no larger than the
  // number of fields after it, so that a corrupt count never makes anyone allocate.
  std::size_t Count(std::size_t i, std::string_view what) const {
    if (i >= tokens_.size()) Fail("missing " + std::string(what));
    const std::string_view t = tokens_[i];
    std::uint64_t n = 0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), n);
    if (ec == std::errc::result_out_of_range) {
      Fail(std::string(what) + " " + Shown(t) + " is larger than the line's " +
           std::to_string(tokens_.size() - i - 1) + " remaining fields");
    }
    if (ec != std::errc() || ptr != t.data() + t.size() || t.empty()) {
      Fail(std::string(what) + " " + Shown(t) + " is not a non-negative integer");
    }
    const std::uint64_t remaining = tokens_.size() - i - 1;
    if (n > remaining) {
      Fail(std::string(what) + " " + std::to_string(n) + " is larger than the line's " +
           std::to_string(remaining) + " remaining fields");
    }
    return static_cast<std::size_t>(n);
  }

  // Requires exactly `expected` fields in all.
  void RequireSize(std::size_t expected, std::string_view format) const {
    if (tokens_.size() != expected) {
      Fail("expected " + std::to_string(expected) + " fields (" + std::string(format) + "), got " +
           std::to_string(tokens_.size()));
    }
  }

  // The trailer `ipc_timestamp ipc_hostname logger_timestamp` at `i` (the line's last three
  // fields); returns the ipc_timestamp.
  double Trailer(std::size_t i) const {
    const double ipc = Number(i, "ipc_timestamp");
    Number(i + 2, "logger_timestamp");
    return ipc;
  }

 private:
  static std::vector<std::string_view>& Buffer() {
    thread_local std::vector<std::string_view> buffer;
    return buffer;
  }
  std::vector<std::string_view>& tokens_;
};

void RequireName(const Fields& f, std::string_view expected) {
  if (f.name() != expected) {
    throw core::IoError(std::string(expected) + " line expected, got one that starts with " +
                        Shown(f.name()));
  }
}

// CARMEN's guess of the angular increment of an old-format laser with n readings (readlog.c).
double GuessedIncrement(const CarmenLaserGeometry& g, std::size_t n) {
  if (g.resolution_deg) return core::DegToRad(*g.resolution_deg);
  if (n == 180 || n == 181) return core::kPi / 180.0;
  if (n == 360 || n == 361) return core::kPi / 360.0;
  if (n == 400 || n == 401) return core::kPi / 720.0;
  return n > 1 ? core::DegToRad(g.fov_deg) / static_cast<double>(n - 1) : 0.0;
}

// Reads `n` ranges starting at field `first` into the scan, applying the max-range and failed
// reading conventions of the file comment.
void ReadRanges(const Fields& f, std::size_t first, std::size_t n, double max_range,
                core::LaserScan& scan) {
  if (n > static_cast<std::size_t>(core::kMaxBeams)) {
    f.Fail("num_readings " + std::to_string(n) + " is more than retrace's limit of " +
           std::to_string(core::kMaxBeams) + " beams");
  }
  scan.ranges.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // The field's name is spelled out only when it fails (this loop reads every range).
    const std::optional<double> parsed =
        first + i < f.size() ? ToDouble(f[first + i]) : std::optional<double>{};
    const double r = parsed && std::isfinite(*parsed)
                         ? *parsed
                         : f.Number(first + i, "range " + std::to_string(i));
    scan.ranges[i] = r >= max_range ? static_cast<float>(kInf)
                     : r <= 0.0     ? static_cast<float>(-kInf)
                                    : static_cast<float>(r);
  }
}

std::string FrameFor(std::string_view name) {
  if (name == "FLASER" || name == "ROBOTLASER1") return "front_laser";
  if (name == "RLASER" || name == "ROBOTLASER2") return "rear_laser";
  return "laser" + std::string(name.substr(std::string_view("RAWLASER").size()));
}

CarmenLaser ParseOldLaser(const Fields& f, const CarmenLaserGeometry& g) {
  constexpr std::string_view kFormat =
      "num_readings r... x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname "
      "logger_timestamp";
  const std::size_t n = f.Count(1, "num_readings");
  f.RequireSize(n + 11, kFormat);
  CarmenLaser out;
  out.scan.frame_id = FrameFor(f.name());
  core::LaserScan& scan = out.scan.scan;
  scan.angle_min = -core::DegToRad(g.fov_deg) / 2.0;
  scan.angle_increment = GuessedIncrement(g, n);
  scan.range_min = 0.0;
  scan.range_max = g.max_range;
  ReadRanges(f, 2, n, g.max_range, scan);
  out.X_OL = f.Pose(2 + n, "laser pose");
  out.X_OR = f.Pose(5 + n, "robot pose");
  scan.stamp = f.Trailer(8 + n);
  return out;
}

CarmenLaser ParseNewLaser(const Fields& f, bool with_poses) {
  CarmenLaser out;
  out.scan.frame_id = FrameFor(f.name());
  core::LaserScan& scan = out.scan.scan;
  f.Number(1, "laser_type");
  scan.angle_min = f.Number(2, "start_angle");
  f.Number(3, "field_of_view");
  scan.angle_increment = f.Number(4, "angular_resolution");
  const double max_range = f.Number(5, "maximum_range");
  if (!(max_range > 0.0)) f.Fail("maximum_range " + Shown(f[5]) + " is not positive");
  f.Number(6, "accuracy");
  f.Number(7, "remission_mode");
  const std::size_t n = f.Count(8, "num_readings");
  if (n > 1 && scan.angle_increment == 0.0) {
    f.Fail("angular_resolution is 0 for " + std::to_string(n) + " readings");
  }
  scan.range_min = 0.0;
  scan.range_max = max_range;
  ReadRanges(f, 9, n, max_range, scan);
  const std::size_t m = f.Count(9 + n, "num_remissions");
  for (std::size_t i = 0; i < m; ++i) f.Number(10 + n + i, "remission " + std::to_string(i));
  std::size_t next = 10 + n + m;
  const std::size_t tail = with_poses ? 14 : 3;
  if (f.size() != next + tail) {
    f.Fail("expected " + std::to_string(tail) + " fields after the remissions (" +
           (with_poses ? "laser_pose_x laser_pose_y laser_pose_theta robot_pose_x robot_pose_y "
                         "robot_pose_theta laser_tv laser_rv forward_safety_dist "
                         "side_safety_dist turn_axis ipc_timestamp ipc_hostname "
                         "logger_timestamp"
                       : "ipc_timestamp ipc_hostname logger_timestamp") +
           "), got " + std::to_string(f.size() - next));
  }
  if (with_poses) {
    out.X_OL = f.Pose(next, "laser pose");
    out.X_OR = f.Pose(next + 3, "robot pose");
    f.Number(next + 6, "laser_tv");
    f.Number(next + 7, "laser_rv");
    f.Number(next + 8, "forward_safety_dist");
    f.Number(next + 9, "side_safety_dist");
    f.Number(next + 10, "turn_axis");
    next += 11;
  }
  scan.stamp = f.Trailer(next);
  return out;
}

double ParamNumber(std::string_view name, std::string_view value) {
  const std::optional<double> v = ToDouble(value);
  if (!v || !std::isfinite(*v)) {
    throw core::IoError("PARAM " + std::string(name) + ": " + Shown(value) +
                        " is not a finite number");
  }
  return *v;
}

// {name, value} of a PARAM line (ParseCarmenParam).
std::pair<std::string, std::string> ParamOf(const Fields& f) {
  RequireName(f, "PARAM");
  const std::size_t n = f.size();
  if (n < 3) f.Fail("expected a name and a value (PARAM name value ...)");
  // The value ends where the trailer begins: `ipc_timestamp hostname logger_timestamp`, or in
  // old logs `hostname logger_timestamp`.
  std::size_t end = n;
  if (n >= 6 && IsFiniteNumber(f[n - 3]) && IsFiniteNumber(f[n - 1])) {
    end = n - 3;
  } else if (n >= 5 && IsFiniteNumber(f[n - 1]) && !IsFiniteNumber(f[n - 2])) {
    end = n - 2;
  }
  std::string value(f[2]);
  for (std::size_t i = 3; i < end; ++i) {
    value += ' ';
    value += f[i];
  }
  return {std::string(f[1]), value};
}

// One of the old-format laser parameters ApplyCarmenParam reads: the laser it sets and which
// of its values ("fov", "resolution", "max" or "flipped").
struct LaserParam {
  bool rear = false;
  std::string_view key;
};

// The laser parameter `name` is, or nullopt for a parameter retrace does not read.
std::optional<LaserParam> FindLaserParam(std::string_view name) {
  for (const bool rear : {false, true}) {
    const std::string side = rear ? "rear" : "front";
    if (name == "robot_" + side + "_laser_max") return LaserParam{rear, "max"};
    const std::string prefix = "laser_" + side + "_laser_";
    if (!name.starts_with(prefix)) continue;
    const std::string_view rest = name.substr(prefix.size());
    for (const std::string_view key : {"fov", "resolution", "flipped"}) {
      if (rest == key) return LaserParam{rear, key};
    }
  }
  return std::nullopt;
}

// A boolean as CARMEN's ini files spell it: on/off as its param_daemon writes, and yes/no,
// true/false, 1/0 as people write them by hand, in any case; nullopt for anything else.
std::optional<bool> ParamBool(std::string_view value) {
  std::string v(value);
  std::transform(v.begin(), v.end(), v.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (v == "1" || v == "on" || v == "yes" || v == "true") return true;
  if (v == "0" || v == "off" || v == "no" || v == "false") return false;
  return std::nullopt;
}

}  // namespace

bool IsCarmenLaser(std::string_view name) {
  return name == "FLASER" || name == "RLASER" || name == "ROBOTLASER1" || name == "ROBOTLASER2" ||
         name == "RAWLASER1" || name == "RAWLASER2" || name == "RAWLASER3" || name == "RAWLASER4";
}

CarmenLaser ParseCarmenLaser(std::string_view line, const CarmenLaserDefaults& defaults) {
  const Fields f(line);
  const std::string_view name = f.name();
  if (name == "FLASER") return ParseOldLaser(f, defaults.front);
  if (name == "RLASER") return ParseOldLaser(f, defaults.rear);
  if (name == "ROBOTLASER1" || name == "ROBOTLASER2") return ParseNewLaser(f, true);
  if (IsCarmenLaser(name)) return ParseNewLaser(f, false);
  throw core::IoError(
      "not a CARMEN laser line (FLASER, RLASER, ROBOTLASER1/2, RAWLASER1-4): it "
      "starts with " +
      Shown(name));
}

OdometryMessage ParseCarmenOdometry(std::string_view line) {
  const Fields f(line);
  RequireName(f, "ODOM");
  f.RequireSize(10, "ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp");
  OdometryMessage out;
  out.frame_id = "odom";
  out.child_frame_id = "base_link";
  out.pose = f.Pose(1, "pose");
  f.Number(4, "tv");
  f.Number(5, "rv");
  f.Number(6, "accel");
  out.stamp = f.Trailer(7);
  return out;
}

PoseStampedMessage ParseCarmenTruePose(std::string_view line) {
  const Fields f(line);
  RequireName(f, "TRUEPOS");
  f.RequireSize(10,
                "TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta ipc_timestamp "
                "ipc_hostname logger_timestamp");
  PoseStampedMessage out;
  out.frame_id = "world";
  out.pose = f.Pose(1, "true pose");
  f.Pose(4, "odometry pose");
  out.stamp = f.Trailer(7);
  return out;
}

std::pair<std::string, std::string> ParseCarmenParam(std::string_view line) {
  const Fields f(line);
  return ParamOf(f);
}

bool ApplyCarmenParam(std::string_view name, std::string_view value,
                      CarmenLaserDefaults& defaults) {
  const std::optional<LaserParam> param = FindLaserParam(name);
  if (!param) return false;
  CarmenLaserGeometry& g = param->rear ? defaults.rear : defaults.front;
  if (param->key == "flipped") {
    // Information only (see CarmenLaserGeometry::flipped): a value that is no boolean is
    // ignored, never a reason to refuse the log.
    if (const std::optional<bool> flipped = ParamBool(value)) g.flipped = *flipped;
    return true;
  }
  const std::string label = "PARAM " + std::string(name);
  const double v = ParamNumber(name, value);
  if (param->key == "max") {
    if (!(v > 0.0)) throw core::IoError(label + ": " + Shown(value) + " is not a positive range");
    g.max_range = v;
  } else {
    if (!(v > 0.0 && v <= 360.0)) {
      throw core::IoError(label + ": " + Shown(value) + " is not an angle in (0, 360] deg");
    }
    if (param->key == "fov") {
      g.fov_deg = v;
    } else {
      g.resolution_deg = v;
    }
  }
  return true;
}

bool ApplyCarmenParamLine(std::string_view line, CarmenLaserDefaults& defaults) {
  const Fields f(line);
  RequireName(f, "PARAM");
  // Only a parameter retrace reads can refuse the log: any other line is skipped unread.
  if (f.size() < 2 || !FindLaserParam(f[1])) return false;
  if (f.size() < 3) throw core::IoError("PARAM " + std::string(f[1]) + ": no value");
  const auto [name, value] = ParamOf(f);
  return ApplyCarmenParam(name, value, defaults);
}

// ---------------------------------------------------------------------------------------------
// CarmenReader

struct CarmenReader::Impl {
  std::string name;
  gzFile gz = nullptr;
  std::vector<char> buffer = std::vector<char>(std::size_t{1} << 16);
  std::size_t pos = 0;
  std::size_t end = 0;
  bool eof = false;

  std::string text;               // the current line, without its line break
  std::size_t physical_line = 0;  // lines read so far
  std::size_t message_line = 0;   // line of the message Next() returned last
  std::size_t pending_line = 0;   // line of the message read ahead, 0 if none
  std::vector<std::string_view> tokens;

  ~Impl() {
    if (gz != nullptr) gzclose(gz);
  }

  [[noreturn]] void Fail(const std::string& what) const { throw core::IoError(name + ": " + what); }

  void Fill() {
    pos = 0;
    end = 0;
    const int got = gzread(gz, buffer.data(), static_cast<unsigned>(buffer.size()));
    int code = Z_OK;
    const char* message = gzerror(gz, &code);
    if (got < 0 || (code != Z_OK && code != Z_BUF_ERROR)) {
      Fail(std::string("cannot read: ") + (code == Z_ERRNO ? std::strerror(errno) : message));
    }
    if (got == 0) {
      // Z_BUF_ERROR at the end: the input stopped in the middle of a gzip stream.
      if (code == Z_BUF_ERROR) Fail("truncated gzip file (unexpected end of the compressed data)");
      eof = true;
    }
    end = static_cast<std::size_t>(got);
  }

  // Reads the next line into `text`; false at the end of the file.
  bool ReadLine() {
    text.clear();
    bool any = false;
    while (true) {
      if (pos == end) {
        if (eof) break;
        Fill();
        continue;
      }
      any = true;
      const char* start = buffer.data() + pos;
      const std::size_t available = end - pos;
      const void* newline = std::memchr(start, '\n', available);
      const std::size_t take =
          newline != nullptr ? static_cast<std::size_t>(static_cast<const char*>(newline) - start)
                             : available;
      if (text.size() + take > kMaxLineBytes) {
        Fail("line " + std::to_string(physical_line + 1) + " is longer than " +
             std::to_string(kMaxLineBytes >> 20) + " MiB: not a CARMEN log");
      }
      text.append(start, take);
      pos += take;
      if (newline != nullptr) {
        ++pos;
        break;
      }
    }
    if (!any) return false;
    ++physical_line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    return true;
  }

  // Reads up to the next message line; false at the end of the file.
  bool ReadMessageLine() {
    while (ReadLine()) {
      const std::size_t first = text.find_first_not_of(" \t\r\v\f");
      if (first == std::string::npos || text[first] == '#') continue;
      return true;
    }
    return false;
  }
};

CarmenReader::CarmenReader(const std::filesystem::path& file) : impl_(std::make_unique<Impl>()) {
  impl_->name = file.string();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) impl_->Fail("cannot open file: it is a folder");
  impl_->gz = gzopen(impl_->name.c_str(), "rb");
  if (impl_->gz == nullptr) {
    impl_->Fail(std::string("cannot open file: ") + std::strerror(errno));
  }
  gzbuffer(impl_->gz, 1U << 17);
  if (!impl_->ReadMessageLine()) {
    impl_->Fail("no CARMEN messages: the file is empty or holds only comments");
  }
  impl_->pending_line = impl_->physical_line;
}

CarmenReader::~CarmenReader() = default;

bool CarmenReader::Next(RawMessage& message) {
  Impl& m = *impl_;
  if (m.pending_line != 0) {
    m.message_line = m.pending_line;
    m.pending_line = 0;
  } else {
    if (!m.ReadMessageLine()) return false;
    m.message_line = m.physical_line;
  }
  Tokenize(m.text, m.tokens);
  const std::size_t n = m.tokens.size();
  message.topic = m.tokens.front();
  message.type = m.tokens.front();
  message.encoding = "carmen";
  message.data = std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(m.text.data()),
                                               m.text.size());
  message.log_time_ns = 0;
  if (n >= 4 && IsFiniteNumber(m.tokens[n - 3])) {
    if (const std::optional<std::int64_t> ns = SecondsToNs(m.tokens[n - 1])) {
      message.log_time_ns = *ns;
    }
  }
  return true;
}

const std::string& CarmenReader::name() const { return impl_->name; }

std::size_t CarmenReader::line() const { return impl_->message_line; }

std::string CarmenReader::Location() const {
  return impl_->name + ":" + std::to_string(impl_->message_line);
}

}  // namespace retrace::logs
