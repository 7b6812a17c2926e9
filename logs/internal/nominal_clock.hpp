#pragma once
// Nominal stamps for a log whose messages carry no time (--scan-rate HZ; logs/sensor_log.hpp):
// the k-th scan (k = 0, 1, ...) is stamped k / rate s, every other message with the stamp of the
// last scan before it (0 before the first). Both passes over a log (IndexLog, ReadScans) count
// the same messages, so they give every message the same stamp.

#include <cmath>
#include <cstdint>

namespace retrace::logs {

class NominalClock {
 public:
  /// rate_hz > 0: nominal stamps; 0: the log's own (on() is false).
  explicit NominalClock(double rate_hz) : rate_hz_(rate_hz) {}
  bool on() const { return rate_hz_ > 0.0; }
  /// The stamp (s) of the next message of the log, a scan or not.
  double Next(bool is_scan) {
    if (is_scan) now_s_ = static_cast<double>(scans_++) / rate_hz_;
    return now_s_;
  }
  static std::int64_t Nanoseconds(double s) { return std::llround(s * 1e9); }

 private:
  double rate_hz_;
  std::uint64_t scans_ = 0;
  double now_s_ = 0.0;
};

}  // namespace retrace::logs
