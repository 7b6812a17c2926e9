#pragma once
// A log as retrace uses it (docs/DESIGN.md §10): one LiDAR's scans, the robot's odometry, the
// LiDAR's mount on the robot and, when the log carries one, a reference trajectory. Which
// messages give them:
//
//   stream     ROS 2 bag or ROS 1 bag                      CARMEN log
//   ---------  ------------------------------------------  -----------------------------------
//   scans      the sensor_msgs/msg/LaserScan topic (ROS 1:  FLASER, else ROBOTLASER1, RAWLASER1
//              also MultiEchoLaserScan, its first echo)
//   odometry   the nav_msgs/msg/Odometry topic, else the    the robot pose of the laser lines,
//              tf transforms odom → base                    else ODOM lines
//   mount X_RL static tf (tf_static) from the base to the   laser pose relative to robot pose in
//              scan's frame, through any chain              the laser lines
//   reference  the geometry_msgs/msg/PoseStamped topic      TRUEPOS lines
//              (ROS 1: also PoseWithCovarianceStamped)
//
// ROS 1 types count as their ROS 2 twins (logs/stream_messages.hpp): sensor_msgs/LaserScan as
// sensor_msgs/msg/LaserScan, tf/tfMessage and tf2_msgs/TFMessage as tf2_msgs/msg/TFMessage.
// A topic is found automatically when it is the only one of its type; otherwise StreamChoice
// names it. Stamps are the messages' own (header stamps; CARMEN: the ipc timestamp), in s;
// times given by the user (--from, --to) count in s of log time from the first scan of the scan
// stream (not the first message: PARAM lines or tf_static may carry another clock).
// A message stamped before the one before it in its stream is dropped; a used stream in which
// more than 1 % of the messages do that has a broken clock and is refused (IndexLog's problem).
// So is a scan stream whose scans mostly repeat the stamp before them (stamps printed with too
// few digits, or none at all: no clock to interpolate the odometry at; StreamChoice::scan_rate_hz
// gives such a log nominal stamps), and odometry that does not overlap the scans in time. Messages whose log times lie far (over kOtherClock) outside the scans' are
// named in a note, as are scans whose angle_max is a little off (ros_messages.hpp).
//
// A log is read in two passes, so that a long one is streamed, never held whole: IndexLog reads
// everything but the scans into memory (poses are small), ReadScans then streams the scans.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.hpp"
#include "io/tum.hpp"
#include "logs/log_messages.hpp"
#include "logs/log_source.hpp"

namespace retrace::logs {

using io::StampedPose;

/// Which topics (CARMEN: message names) to use where the log has several; empty: automatic.
struct StreamChoice {
  std::string scan_topic;
  std::string odometry_topic;
  std::string reference_topic;
  std::string odom_frame = "odom";  ///< tf odometry: the parent frame
  std::string base_frame;           ///< tf odometry: the robot's frame (empty: found)
  /// > 0: the log's stamps are not used (a log written without time): the k-th scan is stamped
  /// k / scan_rate_hz s, every other message with the stamp of the last scan before it. Needs a
  /// log with one scan topic.
  double scan_rate_hz = 0.0;
};

/// Messages of one topic.
struct LogTopic {
  std::string topic;
  std::string type;
  std::uint64_t messages = 0;
  double first_s = 0.0;  ///< log time of its first message (s since LogIndex::origin_ns)
  double last_s = 0.0;
};

/// The chosen scan topic's geometry (of its first scan) and rate.
struct ScanGeometry {
  std::uint64_t scans = 0;
  std::size_t beams = 0;
  double angle_min = 0.0;         ///< rad
  double angle_increment = 0.0;   ///< rad
  double range_min = 0.0;         ///< m
  double range_max = 0.0;         ///< m
  double first_stamp = 0.0;       ///< s
  double last_stamp = 0.0;        ///< s
  std::int64_t first_log_ns = 0;  ///< log time of the first scan used
  std::int64_t last_log_ns = 0;   ///< ... and of the last
  /// Scans whose angle_max is 1 to 2 increments off angle_min + (n − 1)·angle_increment
  /// (ScanMessage::angle_max): used all the same, noted once.
  std::uint64_t inconsistent_angle_max = 0;
  /// Scans stamped exactly as the scan before them (stamps printed with too few digits).
  std::uint64_t repeated_stamps = 0;
  /// rad from the first beam to the last
  double field_of_view() const {
    return beams > 1 ? static_cast<double>(beams - 1) * angle_increment : 0.0;
  }
};

/// One topic of laser scans (CARMEN: one laser message name).
struct ScanStream {
  std::string topic;
  std::string frame;  ///< the scans' frame_id
  ScanGeometry geometry;
};

/// What a log holds (the first pass).
struct LogIndex {
  std::string name;  ///< the path
  LogFormat format = LogFormat::kCarmen;
  std::vector<LogTopic> topics;  ///< in order of first appearance
  std::int64_t start_ns = 0;     ///< log time of the first message
  std::int64_t end_ns = 0;       ///< log time of the last message
  /// Where log times for people start (--from, --to, LogTopic::first_s): the first scan of the
  /// chosen scan topic; with none chosen, the first scan of any; with no scans, start_ns. Not
  /// the first message: a CARMEN log's PARAM lines may carry another clock than its scans.
  std::int64_t origin_ns = 0;

  std::vector<ScanStream> scan_streams;  ///< every scan topic, in order of first appearance
  std::string scan_topic;
  ScanGeometry scan;
  std::string odometry_source;        ///< what the odometry came from, for people
  std::vector<StampedPose> odometry;  ///< X_OR, by stamp; empty: see odometry_missing
  /// Why the log has no odometry, for people ("no nav_msgs/msg/Odometry topic, no tf from
  /// 'odom'"); empty when it has. Not a problem: odometry can be drawn from the reference
  /// (--synthetic-odometry); the commands that drive on the log's own refuse it then.
  std::string odometry_missing;
  std::string reference_topic;         ///< the reference's topic (CARMEN: TRUEPOS); empty: none
  std::string reference_source;        ///< empty: no reference
  std::vector<StampedPose> reference;  ///< X_WR, by stamp
  std::string base_frame;
  std::string laser_frame;
  core::Pose2 X_RL;                ///< the LiDAR mount
  std::string mount_source;        ///< what X_RL came from
  std::vector<std::string> notes;  ///< things the user should know (an assumed mount, ...)
  std::string problem;             ///< why the log cannot be used as it is (empty: it can)
  /// > 0: the stamps are nominal, at this scan rate (StreamChoice::scan_rate_hz)
  double nominal_scan_rate_hz = 0.0;
  /// The problem is only that a stream has several topics and none was chosen: the log is
  /// described whole (log-info), only commands that use the streams need the choice.
  bool needs_choice = false;

  double duration_s() const { return static_cast<double>(end_ns - start_ns) * 1e-9; }
  /// Log time for people (s since origin_ns) of a log time in ns.
  double Since(std::int64_t log_time_ns) const {
    return static_cast<double>(log_time_ns - origin_ns) * 1e-9;
  }
};

/// Log times further than this (s) before the first scan or after the last follow another clock.
inline constexpr double kOtherClock = 3600.0;
/// A scan stream in which more than this share of the scans repeat the stamp before them is
/// refused (at least 10 scans).
inline constexpr double kMaxRepeatedStampFraction = 0.5;

/// Reads the log at `path` once, all but the scans. Throws core::IoError naming the log for a
/// missing or malformed file or message. A log that cannot be used — without scans, a topic in
/// `choice` that is not in the log or not of the right type, an ambiguous choice (several scan
/// or odometry topics) — is still described, with the reason in `problem`. A log without
/// odometry is usable (odometry_missing says so): only driving on its own odometry needs it.
LogIndex IndexLog(const std::filesystem::path& path, const StreamChoice& choice = {});

/// Throws core::IoError with `index.problem` if there is one.
void RequireUsable(const LogIndex& index);

/// Calls `on_scan(scan, log_time_s)` for every scan of `index.scan_topic` whose log time (s since
/// index.origin_ns, the first scan) lies in [from_s, to_s], in log order, but for a scan stamped
/// before the one before it (IndexLog drops those too). Throws core::IoError naming the log and the
/// message for a scan that cannot be decoded.
void ReadScans(const LogIndex& index, double from_s, double to_s,
               const std::function<void(const ScanMessage&, double)>& on_scan);

/// The pose at `stamp`, interpolated between the two samples around it (SE(2)), or nothing
/// before the first sample or after the last. `poses` must be sorted by stamp.
std::optional<core::Pose2> PoseAt(const std::vector<StampedPose>& poses, double stamp);

/// The length (m) of the path through `poses`.
double PathLength(const std::vector<StampedPose>& poses);

}  // namespace retrace::logs
