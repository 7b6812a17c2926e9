#pragma once
// A recorded message as its container stores it, before decoding (docs/DESIGN.md §1, logs/):
// every log reader — CARMEN, MCAP, rosbag2 SQLite — is a MessageSource that hands out its
// messages one by one in storage order, so that a long log is streamed, never held whole.

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace retrace::logs {

/// One message of a log. The views stay valid until the source's next call to Next().
struct RawMessage {
  std::string_view topic;              ///< ROS topic ("/scan") or CARMEN message name ("FLASER")
  std::string_view type;               ///< ROS type ("sensor_msgs/msg/LaserScan") or CARMEN name
  std::string_view encoding;           ///< "cdr" (ROS 2) or "carmen" (one text line)
  std::int64_t log_time_ns = 0;        ///< when the recorder received it (ns since the epoch)
  std::span<const std::uint8_t> data;  ///< the serialized message (a CARMEN line without '\n')
};

/// A log time in ns from seconds (rounded to the nearest nanosecond).
inline std::int64_t LogTimeNs(double s) { return std::llround(s * 1e9); }

/// A log's messages in storage order.
class MessageSource {
 public:
  virtual ~MessageSource() = default;
  /// Fills `message` with the next message and returns true, or returns false at the end.
  /// Throws core::IoError naming the file and what is wrong for a malformed container.
  virtual bool Next(RawMessage& message) = 0;
  /// The log's name (its path) for messages.
  virtual const std::string& name() const = 0;
};

}  // namespace retrace::logs
