#pragma once
// Reading CARMEN logs (.log and .clf, plain or gzipped): CarmenReader hands out the log's lines
// one by one as RawMessages, and the Parse* functions below decode one line of the message types
// retrace uses (lasers, odometry, the simulator's true pose, parameters).
//
// A CARMEN log is one message per line, `NAME fields... ipc_timestamp ipc_hostname
// logger_timestamp`, with `#` comment lines (CARMEN src/logger/writelog.c writes the header that
// lists the formats). The ipc_timestamp is when the message was made (s, usually since the
// epoch); the logger_timestamp is when the logger wrote it (s since the logger started).
//
// Beam geometry of the old FLASER/RLASER lines, which do not carry it. CARMEN itself guesses it
// from the number of readings n when it reads such a line (src/logger/readlog.c,
// carmen_string_to_robot_laser_message_orig with carmen_laser_guess_fov and
// carmen_laser_guess_angle_increment): the first beam at -90 deg, the increment 1 deg for
// n = 180 or 181, 0.5 deg for 360 or 361, 0.25 deg for 400 or 401 and fov / (n - 1) (a fov of
// 180 deg) otherwise, and a maximum range of 80 m. The increment is therefore *not* fov / n:
// CARMEN reads the 180 beams of the Intel Research Lab log as -90 deg to +89 deg in 1 deg steps
// (and that log's no-return reading, 81.83 m, is beyond the 80 m). retrace follows
// CARMEN's guess, with PARAM lines overriding it where the log has them (CarmenLaserDefaults,
// filled by ApplyCarmenParam): laser_front_laser_fov (deg; the first beam is then at -fov / 2,
// as CARMEN's laser module sets start_angle = -0.5 fov), laser_front_laser_resolution (deg) and
// robot_front_laser_max (m), and the laser_rear_* / robot_rear_* ones for RLASER. Other readers
// differ (GMapping's carmenconfiguration places the beams symmetrically about 0, MRPT assumes
// 0.5 deg and 81 m); CARMEN is the format's owner, so its reading is the one taken here.
//
// Ranges: a reading >= the maximum range is no return (+inf, REP-117). A reading <= 0 is a
// failed measurement and reads as -inf, so that it never counts as a valid range (REP-117's NaN
// would be the exact code, but retrace keeps NaN out of scans).

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "core/pose2.hpp"
#include "logs/log_messages.hpp"
#include "logs/raw_message.hpp"

namespace retrace::logs {

/// The beam geometry of one old-format laser (FLASER: front, RLASER: rear). See the file comment
/// for CARMEN's conventions.
struct CarmenLaserGeometry {
  /// Field of view (deg): the first beam is at -fov / 2. laser_<front|rear>_laser_fov.
  double fov_deg = 180.0;
  /// Angular increment (deg); unset: CARMEN's guess from the number of readings.
  /// laser_<front|rear>_laser_resolution.
  std::optional<double> resolution_deg;
  /// Maximum range (m): readings at or beyond it are no return. robot_<front|rear>_laser_max.
  double max_range = 80.0;
  /// laser_<front|rear>_laser_flipped: the laser was mounted upside down. Kept for information
  /// only: CARMEN's laser module reverses the readings before publishing them, so a log's
  /// ranges are already counter-clockwise and are not reversed again.
  bool flipped = false;
};

/// The beam geometry of the old FLASER and RLASER lines, from a log's PARAM lines (or CARMEN's
/// defaults where the log has none).
struct CarmenLaserDefaults {
  CarmenLaserGeometry front;  ///< FLASER
  CarmenLaserGeometry rear;   ///< RLASER
};

/// One laser line: the scan in the laser's frame L and, where the line carries them, the
/// laser's and the robot's pose in the odometry frame O (in a corrected log, such as the
/// "-corrected" logs of the Radish data sets, these are the corrected poses).
struct CarmenLaser {
  ScanMessage scan;  ///< scan.stamp is the line's ipc_timestamp (s)
  std::optional<core::Pose2> X_OL;
  std::optional<core::Pose2> X_OR;
};

/// True for the message names ParseCarmenLaser reads: FLASER, RLASER, ROBOTLASER1, ROBOTLASER2
/// and RAWLASER1..RAWLASER4.
bool IsCarmenLaser(std::string_view name);

/// Decodes a laser line:
///   FLASER|RLASER num_readings r... x y theta odom_x odom_y odom_theta  (old format; the beam
///       geometry from `defaults`; x y theta is the laser's pose, odom_* the robot's)
///   ROBOTLASER1|2 laser_type start_angle field_of_view angular_resolution maximum_range
///       accuracy remission_mode num_readings r... num_remissions rem... laser_pose_x
///       laser_pose_y laser_pose_theta robot_pose_x robot_pose_y robot_pose_theta laser_tv
///       laser_rv forward_safety_dist side_safety_dist turn_axis
///   RAWLASER1..4 (as ROBOTLASER up to the remissions, without poses)
/// each followed by ipc_timestamp ipc_hostname logger_timestamp. The scan's frame_id is
/// "front_laser" (FLASER, ROBOTLASER1), "rear_laser" (RLASER, ROBOTLASER2) or "laser1".."laser4".
/// Throws core::IoError with a short reason (no file or line: the caller adds them) for another
/// message, a wrong number of fields, a count beyond the line's fields, or a field that is not a
/// finite number.
CarmenLaser ParseCarmenLaser(std::string_view line, const CarmenLaserDefaults& defaults = {});

/// Decodes `ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp`: the robot
/// base's pose in the odometry frame (frame_id "odom", child_frame_id "base_link"), stamped with
/// the ipc_timestamp. Throws core::IoError as ParseCarmenLaser.
OdometryMessage ParseCarmenOdometry(std::string_view line);

/// Decodes `TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname
/// logger_timestamp`, the simulator's ground truth: the robot's true pose (frame_id "world"),
/// stamped with the ipc_timestamp. Throws core::IoError as ParseCarmenLaser.
PoseStampedMessage ParseCarmenTruePose(std::string_view line);

/// Decodes `PARAM name value ipc_timestamp ipc_hostname logger_timestamp` into {name, value}.
/// Also reads the short form of old logs, `PARAM name value hostname timestamp` (the Intel Research
/// Lab log's), and a bare `PARAM name value`. Throws core::IoError without a name and a value.
std::pair<std::string, std::string> ParseCarmenParam(std::string_view line);

/// Applies one PARAM to the old-format laser geometry: laser_front_laser_fov,
/// laser_front_laser_resolution, robot_front_laser_max, laser_front_laser_flipped and their rear
/// counterparts. Returns false (and changes nothing) for any other name. Throws core::IoError for
/// a value that is not a number in range (fov and resolution in (0, 360] deg, max > 0 m). flipped
/// is read as a boolean (1/0, on/off, yes/no, true/false, any case) and, being information only,
/// left unchanged for any other value.
bool ApplyCarmenParam(std::string_view name, std::string_view value, CarmenLaserDefaults& defaults);

/// Applies a PARAM line (ParseCarmenParam, then ApplyCarmenParam); returns whether it was one of
/// the parameters retrace reads. A parameter retrace does not read never refuses a log: its line
/// is skipped whatever its value (free text, a boolean, nothing). Throws core::IoError only for a
/// line that is not PARAM and for a parameter retrace reads whose value is missing or malformed.
bool ApplyCarmenParamLine(std::string_view line, CarmenLaserDefaults& defaults);

/// A CARMEN log's messages in file order, streamed line by line (gzip or plain, detected from
/// the content). Empty lines and `#` comments are skipped. Each RawMessage has topic = type =
/// the line's first word (FLASER, ODOM, PARAM, ..., any other word as it is), encoding
/// "carmen", data = the line without its line break, and log_time_ns = the logger_timestamp
/// (the last field) when the line ends in `number word number`, else 0.
class CarmenReader final : public MessageSource {
 public:
  /// A line longer than this (bytes) is an error: no CARMEN message comes close.
  static constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;

  /// Opens `file` and reads up to its first message. Throws core::IoError "<file>: ..." if it
  /// cannot be opened or read, holds no message (empty or only comments), or its first line is
  /// over kMaxLineBytes.
  explicit CarmenReader(const std::filesystem::path& file);
  ~CarmenReader() override;
  CarmenReader(const CarmenReader&) = delete;
  CarmenReader& operator=(const CarmenReader&) = delete;

  /// Throws core::IoError "<file>:<line>: ..." for a line over kMaxLineBytes and
  /// "<file>: ..." for a truncated or corrupt gzip stream.
  bool Next(RawMessage& message) override;
  const std::string& name() const override;

  /// The 1-based line number of the message Next() returned last (0 before the first call).
  std::size_t line() const;
  /// "<file>:<line>" of that message, to prefix the errors of the Parse* functions.
  std::string Location() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace retrace::logs
