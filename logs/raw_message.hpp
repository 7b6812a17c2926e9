#pragma once
// A recorded message as its container stores it, before decoding (docs/DESIGN.md §1, logs/):
// every log reader — CARMEN, MCAP, rosbag2 SQLite, ROS 1 bags — is a MessageSource that hands out
// its messages one by one in storage order, so that a long log is streamed, never held whole.

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace retrace::logs {

/// One message of a log. The views stay valid until the source's next call to Next().
struct RawMessage {
  std::string_view topic;  ///< ROS topic ("/scan") or CARMEN message name ("FLASER")
  /// ROS type ("sensor_msgs/msg/LaserScan"; ROS 1: "sensor_msgs/LaserScan") or CARMEN name
  std::string_view type;
  std::string_view encoding;     ///< "cdr" (ROS 2), "ros1" (ROS 1) or "carmen" (one text line)
  std::string_view md5sum;       ///< ROS 1: the md5sum of the type's definition; else empty
  std::int64_t log_time_ns = 0;  ///< when the recorder received it (ns since the epoch)
  std::span<const std::uint8_t> data;  ///< the serialized message (a CARMEN line without '\n')
};

/// A log time in ns from seconds (rounded to the nearest nanosecond).
inline std::int64_t LogTimeNs(double s) { return std::llround(s * 1e9); }

/// A log's messages in storage order (a ROS 1 bag's in time order).
class MessageSource {
 public:
  virtual ~MessageSource() = default;
  /// Fills `message` with the next message and returns true, or returns false at the end.
  /// Throws core::IoError naming the file and what is wrong for a malformed container.
  virtual bool Next(RawMessage& message) = 0;
  /// The log's name (its path) for messages.
  virtual const std::string& name() const = 0;
  /// What the user should know about the container itself (a ROS 1 bag read without its index),
  /// complete once Next() has returned false.
  virtual std::vector<std::string> notes() const { return {}; }
};

}  // namespace retrace::logs
