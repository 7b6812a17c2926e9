#include "bench/replay/log_streams.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "core/format.hpp"

namespace retrace::bench {

namespace {

constexpr double kStepDistance = 0.02;  // m
constexpr double kStepAngle = 0.0175;   // rad

// The one line that refuses a log without odometry: what it lacks and, when a reference (the
// log's or `reference_file`) can stand in, the option that draws the odometry from it.
std::string NoOdometry(const logs::LogIndex& index, const LogStreams& streams,
                       const std::optional<std::filesystem::path>& reference_file,
                       bool synthetic_odometry) {
  const std::string line = index.name + ": no odometry (" + index.odometry_missing + ")";
  if (!streams.reference.empty()) {
    const std::string reference = reference_file ? "the reference '" + reference_file->string()
                                                 : "its reference '" + index.reference_topic;
    return line + "; " + reference + "' can stand in: add --synthetic-odometry";
  }
  return line + " and no reference to draw it from: give one with --reference FILE.tum" +
         (synthetic_odometry ? "" : " and add --synthetic-odometry");
}

// The stamps (s) a reference file must overlap: the log's odometry, else (a log without one)
// its scans.
struct StampSpan {
  double from = 0.0;
  double to = 0.0;
  std::string what;
};

StampSpan LogStampSpan(const logs::LogIndex& index) {
  if (index.odometry.empty()) return {index.scan.first_stamp, index.scan.last_stamp, "scans"};
  return {index.odometry.front().t, index.odometry.back().t, "odometry"};
}

}  // namespace

std::vector<io::StampedPose> SyntheticOdometry(const std::vector<io::StampedPose>& truth,
                                               const sim::OdometryConfig& config, core::Rng rng) {
  std::vector<io::StampedPose> odometry;
  if (truth.empty()) return odometry;
  sim::Odometry model(config, std::move(rng));
  odometry.reserve(truth.size());
  odometry.push_back({truth.front().t, model.pose()});
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const core::Pose2& a = truth[i - 1].pose;
    const core::Pose2& b = truth[i].pose;
    const double turn = std::abs(core::WrapAngle(b.theta - a.theta));
    const int steps = std::max(1, static_cast<int>(std::ceil(std::max(
                                      core::Distance(a, b) / kStepDistance, turn / kStepAngle))));
    core::Pose2 previous = a;
    for (int k = 1; k <= steps; ++k) {
      const core::Pose2 next = k == steps ? b : core::Interpolate(a, b, double(k) / steps);
      model.Update(previous, next);
      previous = next;
    }
    odometry.push_back({truth[i].t, model.pose()});
  }
  return odometry;
}

LogStreams PrepareLogStreams(const logs::LogIndex& index, const LogConfig& config,
                             bool synthetic_odometry,
                             const std::optional<std::filesystem::path>& reference_file) {
  logs::RequireUsable(index);
  LogStreams streams;
  streams.robot.X_RL = index.X_RL;
  streams.robot.range_min = index.scan.range_min;
  streams.robot.range_max = index.scan.range_max;
  streams.odometry = index.odometry;
  streams.odometry_source = index.odometry_source;
  if (reference_file) {
    streams.reference = io::ReadTum(*reference_file);
    streams.reference_source = reference_file->string();
    std::stable_sort(streams.reference.begin(), streams.reference.end(),
                     [](const io::StampedPose& a, const io::StampedPose& b) { return a.t < b.t; });
    const StampSpan log = LogStampSpan(index);
    if (streams.reference.empty() || streams.reference.back().t < log.from ||
        streams.reference.front().t > log.to) {
      throw core::IoError(reference_file->string() + ": the reference does not overlap the log's " +
                          log.what + " in time (stamps " + core::FormatNumber(log.from) + " to " +
                          core::FormatNumber(log.to) + " s)");
    }
  } else if (!index.reference.empty()) {
    streams.reference = index.reference;
    streams.reference_source = index.reference_source;
  }
  // Only driving on the log's own odometry needs it: a log without odometry (a motion-capture
  // bag) is driven on odometry drawn from its reference.
  if (index.odometry.empty() && (!synthetic_odometry || streams.reference.empty()))
    throw core::IoError(NoOdometry(index, streams, reference_file, synthetic_odometry));
  if (synthetic_odometry) {
    if (streams.reference.empty()) {
      streams.reference = index.odometry;
      streams.reference_source = index.odometry_source + " (taken as the reference)";
    }
    streams.odometry = SyntheticOdometry(streams.reference, config.sim.odometry,
                                         core::Rng(config.seed).Split("synthetic-odometry"));
    streams.odometry_source = "synthetic, drawn from " + streams.reference_source;
  }
  return streams;
}

std::vector<std::pair<std::string, std::string>> LogManifestFields(const logs::LogIndex& index,
                                                                   const LogStreams& streams,
                                                                   double from_s, double to_s) {
  const double rate = index.nominal_scan_rate_hz;
  return {{"log", index.name},
          {"log_format", std::string(logs::LogFormatName(index.format))},
          {"scan_topic", index.scan_topic},
          {"stamps",
           rate > 0.0 ? "nominal, --scan-rate " + core::FormatNumber(rate) + " Hz" : "the log's"},
          {"odometry", streams.odometry_source},
          {"reference", streams.reference_source.empty() ? "none" : streams.reference_source},
          {"lidar_mount", index.mount_source},
          {"from_s", core::FormatNumber(from_s)},
          {"to_s", core::FormatNumber(to_s)}};
}

}  // namespace retrace::bench
