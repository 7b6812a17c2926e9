#include "logs/carmen_writer.hpp"

#include <zlib.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>

#include "core/angle.hpp"
#include "core/errors.hpp"

namespace retrace::logs {
namespace {

constexpr std::string_view kHeader =
    "# CARMEN Logfile\n"
    "# written by retrace (logs/carmen_writer)\n"
    "# file format is one message per line\n"
    "# message_name [message contents] ipc_timestamp ipc_hostname logger_timestamp\n"
    "# message formats defined: PARAM ODOM TRUEPOS ROBOTLASER1\n"
    "# PARAM param_name param_value\n"
    "# ODOM x y theta tv rv accel\n"
    "# TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta\n"
    "# ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range "
    "accuracy remission_mode num_readings [range_readings] num_remissions [remission values] "
    "laser_pose_x laser_pose_y laser_pose_theta robot_pose_x robot_pose_y robot_pose_theta "
    "laser_tv laser_rv forward_safety_dist side_safety_dist turn_axis\n"
    "# units: m, rad, s; a range equal to maximum_range means no return\n";

// CARMEN's laser_type for a sensor it does not know (UMKNOWN_PROXIMITY_SENSOR in
// src/laser-new/laser_messages.h).
constexpr int kUnknownLaserType = 99;

bool HasSpace(std::string_view s) {
  return s.find_first_of(" \t\r\n\v\f") != std::string_view::npos;
}

// The shortest decimal that reads back as `v`.
std::string Shortest(double v) {
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, ptr);
}

void Append(std::string& line, double v) {
  line += Shortest(v);
  line += ' ';
}

void Append(std::string& line, std::string_view word) {
  line += word;
  line += ' ';
}

void Append(std::string& line, const core::Pose2& p) {
  Append(line, p.x);
  Append(line, p.y);
  Append(line, p.theta);
}

// Appends one range as the file comment says: the shortest text that reads back as the same
// float (so a log round-trips its scans bit for bit), no return as the exact range_max, and a
// failed reading (NaN, zero or negative) as 0.
void AppendRange(std::string& line, float r, const core::LaserScan& scan) {
  if (std::isnan(r) || r <= 0.0f) {
    line += "0 ";
    return;
  }
  if (static_cast<double>(r) >= scan.range_max) {
    Append(line, scan.range_max);
    return;
  }
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), r);
  line.append(buf, ptr);
  line += ' ';
}

bool Finite(const core::Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

}  // namespace

struct CarmenWriter::Impl {
  std::filesystem::path path;
  std::string name;
  gzFile gz = nullptr;
  bool laser_params_written = false;
  std::string line;

  [[noreturn]] void Fail(const std::string& what) const { throw core::IoError(name + ": " + what); }

  void RequireOpen() const {
    if (gz == nullptr) Fail("cannot write: the CARMEN log is closed");
  }

  void RequireFinite(double v, std::string_view what) const {
    if (!std::isfinite(v)) Fail("cannot write a non-finite " + std::string(what));
  }

  void RequireFinite(const core::Pose2& p, std::string_view what) const {
    if (!Finite(p)) Fail("cannot write a non-finite " + std::string(what));
  }

  // Ends `line` with the trailer and writes it.
  void Finish(double stamp) {
    Append(line, stamp);
    Append(line, "retrace");
    line += Shortest(stamp);
    line += '\n';
    Write(line);
  }

  void Write(std::string_view bytes) {
    RequireOpen();
    if (bytes.empty()) return;
    const int wrote = gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size()));
    if (wrote != static_cast<int>(bytes.size())) {
      int code = Z_OK;
      const char* message = gzerror(gz, &code);
      Fail(std::string("cannot write: ") + (code == Z_ERRNO ? std::strerror(errno) : message));
    }
  }
};

CarmenWriter::CarmenWriter(const std::filesystem::path& file) : impl_(std::make_unique<Impl>()) {
  impl_->path = file;
  impl_->name = file.string();
  // "T": zlib writes plain text through the same interface ("transparent" mode).
  const bool gzip = file.extension() == ".gz";
  impl_->gz = gzopen(impl_->name.c_str(), gzip ? "wb" : "wbT");
  if (impl_->gz == nullptr) {
    impl_->Fail(std::string("cannot create file: ") + std::strerror(errno));
  }
  gzbuffer(impl_->gz, 1U << 17);
  impl_->Write(kHeader);
}

CarmenWriter::~CarmenWriter() {
  if (impl_ && impl_->gz != nullptr) gzclose(impl_->gz);
}

void CarmenWriter::WriteParam(std::string_view name, std::string_view value, double stamp) {
  Impl& m = *impl_;
  m.RequireOpen();
  if (name.empty() || value.empty() || HasSpace(name) || HasSpace(value)) {
    m.Fail("PARAM '" + std::string(name) + "' '" + std::string(value) +
           "': the name and the value must be one word each");
  }
  m.RequireFinite(stamp, "PARAM stamp");
  m.line = "PARAM ";
  Append(m.line, name);
  Append(m.line, value);
  m.Finish(stamp);
}

void CarmenWriter::WriteLaserParams(const core::LaserScan& scan, const core::Pose2& X_RL,
                                    double stamp) {
  Impl& m = *impl_;
  m.RequireFinite(scan.angle_increment, "laser angle_increment");
  m.RequireFinite(scan.range_max, "laser range_max");
  m.RequireFinite(X_RL, "laser mount");
  const double n = static_cast<double>(scan.size());
  const double fov = scan.size() > 1 ? (n - 1.0) * scan.angle_increment : 0.0;
  WriteParam("laser_front_laser_fov", Shortest(core::RadToDeg(fov)), stamp);
  WriteParam("laser_front_laser_resolution", Shortest(core::RadToDeg(scan.angle_increment)), stamp);
  WriteParam("laser_front_laser_flipped", "0", stamp);
  WriteParam("robot_front_laser_max", Shortest(scan.range_max), stamp);
  WriteParam("robot_frontlaser_offset", Shortest(X_RL.x), stamp);
  WriteParam("robot_frontlaser_side_offset", Shortest(X_RL.y), stamp);
  WriteParam("robot_frontlaser_angular_offset", Shortest(X_RL.theta), stamp);
  m.laser_params_written = true;
}

void CarmenWriter::WriteOdometry(double stamp, const core::Pose2& X_OR, double tv, double rv) {
  Impl& m = *impl_;
  m.RequireOpen();
  m.RequireFinite(stamp, "ODOM stamp");
  m.RequireFinite(X_OR, "ODOM pose");
  m.RequireFinite(tv, "ODOM tv");
  m.RequireFinite(rv, "ODOM rv");
  m.line = "ODOM ";
  Append(m.line, X_OR);
  Append(m.line, tv);
  Append(m.line, rv);
  Append(m.line, 0.0);
  m.Finish(stamp);
}

void CarmenWriter::WriteLaser(const core::LaserScan& scan, const core::Pose2& X_OR,
                              const core::Pose2& X_RL, double tv, double rv) {
  Impl& m = *impl_;
  m.RequireOpen();
  m.RequireFinite(scan.stamp, "laser stamp");
  m.RequireFinite(scan.angle_min, "laser angle_min");
  m.RequireFinite(scan.angle_increment, "laser angle_increment");
  if (!(std::isfinite(scan.range_max) && scan.range_max > 0.0)) {
    m.Fail("cannot write a laser scan whose range_max is not positive and finite");
  }
  m.RequireFinite(X_OR, "laser robot pose");
  m.RequireFinite(X_RL, "laser mount");
  m.RequireFinite(tv, "laser tv");
  m.RequireFinite(rv, "laser rv");
  if (!m.laser_params_written) WriteLaserParams(scan, X_RL, scan.stamp);

  const std::size_t n = scan.size();
  const double fov = n > 1 ? static_cast<double>(n - 1) * scan.angle_increment : 0.0;
  m.line = "ROBOTLASER1 ";
  m.line += std::to_string(kUnknownLaserType);
  m.line += ' ';
  Append(m.line, scan.angle_min);
  Append(m.line, fov);
  Append(m.line, scan.angle_increment);
  Append(m.line, scan.range_max);
  Append(m.line, 0.01);  // accuracy (m), CARMEN's value for SICK lasers
  Append(m.line, "0");   // remission_mode: none
  Append(m.line, std::to_string(n));
  for (const float r : scan.ranges) AppendRange(m.line, r, scan);
  Append(m.line, "0");  // num_remissions
  Append(m.line, X_OR * X_RL);
  Append(m.line, X_OR);
  Append(m.line, tv);
  Append(m.line, rv);
  Append(m.line, "0 0 0");  // forward_safety_dist side_safety_dist turn_axis: unused
  m.Finish(scan.stamp);
}

void CarmenWriter::WriteTruePose(double stamp, const core::Pose2& X_WR, const core::Pose2& X_OR) {
  Impl& m = *impl_;
  m.RequireOpen();
  m.RequireFinite(stamp, "TRUEPOS stamp");
  m.RequireFinite(X_WR, "TRUEPOS true pose");
  m.RequireFinite(X_OR, "TRUEPOS odometry pose");
  m.line = "TRUEPOS ";
  Append(m.line, X_WR);
  Append(m.line, X_OR);
  m.Finish(stamp);
}

void CarmenWriter::Close() {
  Impl& m = *impl_;
  if (m.gz == nullptr) return;
  gzFile gz = m.gz;
  m.gz = nullptr;
  const int code = gzclose(gz);
  if (code != Z_OK) {
    m.Fail(std::string("cannot write: ") +
           (code == Z_ERRNO ? std::strerror(errno) : "zlib error " + std::to_string(code)));
  }
}

const std::filesystem::path& CarmenWriter::path() const { return impl_->path; }

}  // namespace retrace::logs
