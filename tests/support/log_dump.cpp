// retrace_log_dump <log>: every message of a log as retrace's readers hand it out and decode it,
// one JSON object a line, for the CLI tests that compare retrace's reading of a log field for field
// with a reference reader's (tests/cli/ros1_bag_test.sh with python3-rosbag). Non-finite floats
// are written as the strings "inf", "-inf" and "nan". Exits 2 with one line on stderr for a log
// retrace refuses, as `retrace` does.
//
//   {"topic": "/scan", "type": "sensor_msgs/LaserScan", "time_ns": 1000000000, "stamp": 1.0,
//    "frame_id": "laser", "angle_min": -1.5, ..., "ranges": [1.0, "inf", ...]}
//   {"topic": "/odom", ..., "child_frame_id": "base_link", "x": 0.5, "y": 0.0, "yaw": 0.1}

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "logs/log_source.hpp"
#include "logs/stream_messages.hpp"

namespace {

using nlohmann::json;
using namespace retrace;

json Number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

json Pose(json out, const core::Pose2& X) {
  out["x"] = Number(X.x);
  out["y"] = Number(X.y);
  out["yaw"] = Number(X.theta);
  return out;
}

json Scan(const logs::ScanMessage& m) {
  json out{{"stamp", m.scan.stamp},
           {"frame_id", m.frame_id},
           {"angle_min", Number(m.scan.angle_min)},
           {"angle_increment", Number(m.scan.angle_increment)},
           {"range_min", Number(m.scan.range_min)},
           {"range_max", Number(m.scan.range_max)}};
  json ranges = json::array();
  for (float r : m.scan.ranges) ranges.push_back(Number(r));
  out["ranges"] = std::move(ranges);
  return out;
}

json Decoded(const logs::RawMessage& m) {
  switch (logs::StreamKindOf(m)) {
    case logs::StreamKind::kScan:
      return Scan(logs::DecodeStreamScan(m));
    case logs::StreamKind::kOdometry: {
      const logs::OdometryMessage o = logs::DecodeStreamOdometry(m);
      return Pose(
          {{"stamp", o.stamp}, {"frame_id", o.frame_id}, {"child_frame_id", o.child_frame_id}},
          o.pose);
    }
    case logs::StreamKind::kTf: {
      json transforms = json::array();
      for (const logs::TransformMessage& t : logs::DecodeStreamTf(m).transforms) {
        transforms.push_back(
            Pose({{"stamp", t.stamp}, {"parent", t.parent}, {"child", t.child}}, t.X_PC));
      }
      return {{"transforms", transforms}};
    }
    case logs::StreamKind::kPose: {
      const logs::PoseStampedMessage p = logs::DecodeStreamPose(m);
      return Pose({{"stamp", p.stamp}, {"frame_id", p.frame_id}}, p.pose);
    }
    case logs::StreamKind::kNone:
      break;
  }
  return {{"bytes", m.data.size()}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <log>\n", argv[0]);
    return 2;
  }
  try {
    const std::unique_ptr<logs::MessageSource> source = logs::OpenLog(argv[1]);
    logs::RawMessage m;
    while (source->Next(m)) {
      json line = Decoded(m);
      line["topic"] = std::string(m.topic);
      line["type"] = std::string(m.type);
      line["time_ns"] = m.log_time_ns;
      std::cout << line.dump() << "\n";
    }
    for (const std::string& note : source->notes()) std::cerr << "note: " << note << "\n";
  } catch (const core::Error& e) {
    std::cerr << "retrace_log_dump: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
