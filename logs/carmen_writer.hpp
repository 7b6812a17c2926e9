#pragma once
// Writing CARMEN logs that CARMEN's own tools and logs/carmen_reader.hpp read back: a `#` header
// in the style of CARMEN's logger (what wrote the file and the format of each message type),
// PARAM lines for the laser geometry, ODOM, ROBOTLASER1 (it carries the exact start angle,
// increment and maximum range, which the old FLASER line does not) and TRUEPOS for ground truth.
//
// Every line ends in `ipc_timestamp ipc_hostname logger_timestamp`; both timestamps are the
// message's stamp (s) and the hostname is "retrace". Poses, angles and stamps are written with
// the shortest decimals that read back to the same double, ranges with the shortest that read
// back to the same float (CARMEN's logger writes millimetres; more digits read the same way), so
// that a scan round-trips bit for bit. A range of +inf (no return) or at or beyond the scan's
// range_max is written as the exact maximum range, which reads back as no return; -inf, NaN and
// zero (no reading) are written as 0, which reads back as -inf.

#include <filesystem>
#include <memory>
#include <string_view>

#include "core/laser_scan.hpp"
#include "core/pose2.hpp"

namespace retrace::logs {

/// Writes one CARMEN log, line by line. Every Write* throws core::IoError "<file>: ..." for a
/// non-finite stamp, pose or speed (it would not read back), after Close(), and when the line
/// cannot be written.
class CarmenWriter {
 public:
  /// Creates (or truncates) `file` and writes the header. A name ending in ".gz" is written
  /// gzip-compressed; anything else as plain text. The folder must exist. Throws core::IoError
  /// "<file>: ..." if the file cannot be created.
  explicit CarmenWriter(const std::filesystem::path& file);
  /// Closes the file if Close() was not called, ignoring errors: call Close() to see them.
  ~CarmenWriter();
  CarmenWriter(const CarmenWriter&) = delete;
  CarmenWriter& operator=(const CarmenWriter&) = delete;

  /// `PARAM name value`. Throws core::IoError if the name or value is empty or holds
  /// whitespace (CARMEN splits lines at spaces).
  void WriteParam(std::string_view name, std::string_view value, double stamp = 0.0);

  /// The front laser's PARAM lines, from a scan with n beams and the mount X_RL:
  /// laser_front_laser_fov ((n - 1) * increment, deg), laser_front_laser_resolution (deg),
  /// laser_front_laser_flipped (0), robot_front_laser_max (m), robot_frontlaser_offset,
  /// robot_frontlaser_side_offset (m) and robot_frontlaser_angular_offset (rad). WriteLaser()
  /// writes them before the first laser line unless this was called before.
  void WriteLaserParams(const core::LaserScan& scan, const core::Pose2& X_RL, double stamp = 0.0);

  /// `ODOM x y theta tv rv 0`: the robot's pose in the odometry frame O, its forward speed tv
  /// (m/s) and turn rate rv (rad/s).
  void WriteOdometry(double stamp, const core::Pose2& X_OR, double tv, double rv);

  /// `ROBOTLASER1`: the scan (stamped scan.stamp) with the laser's pose X_OL = X_OR * X_RL and
  /// the robot's pose X_OR in the odometry frame, and the robot's speeds tv (m/s), rv (rad/s).
  /// Throws core::IoError for a scan with a non-finite angle_min or angle_increment, or a
  /// range_max that is not positive and finite.
  void WriteLaser(const core::LaserScan& scan, const core::Pose2& X_OR, const core::Pose2& X_RL,
                  double tv, double rv);

  /// `TRUEPOS`: the robot's true pose X_WR (the simulator's ground truth) and its odometry pose
  /// X_OR at the same instant.
  void WriteTruePose(double stamp, const core::Pose2& X_WR, const core::Pose2& X_OR);

  /// Flushes and closes the file. Throws core::IoError if anything could not be written. A second
  /// Close() does nothing.
  void Close();

  const std::filesystem::path& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace retrace::logs
