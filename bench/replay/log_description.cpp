#include "bench/replay/log_description.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "core/config.hpp"
#include "core/format.hpp"

namespace retrace::bench {

namespace {

std::string Degrees(double rad, int digits) {
  return core::FixedText(rad * 180.0 / std::numbers::pi, digits);
}

std::string Duration(double s) {
  const long total = std::lround(s);
  std::string text = core::FixedText(s, 1) + " s";
  if (total >= 3600) {
    text += " (" + std::to_string(total / 3600) + " h " + std::to_string(total / 60 % 60) + " min)";
  } else if (total >= 60) {
    text += " (" + std::to_string(total / 60) + " min " + std::to_string(total % 60) + " s)";
  }
  return text;
}

std::string Rate(std::uint64_t messages, double span_s) {
  if (messages < 2 || span_s <= 0.0) return "";
  return core::FixedText(static_cast<double>(messages - 1) / span_s, 2);
}

std::string Pose(const core::Pose2& p) {
  return "(" + core::FixedText(p.x, 3) + " m, " + core::FixedText(p.y, 3) + " m, " +
         Degrees(p.theta, 1) + " deg)";
}

void WriteTopicTable(std::ostream& out, const logs::LogIndex& index) {
  std::size_t topic_width = 5;
  std::size_t type_width = 4;
  for (const logs::LogTopic& t : index.topics) {
    topic_width = std::max(topic_width, t.topic.size());
    type_width = std::max(type_width, t.type.size());
  }
  char line[512];
  std::snprintf(line, sizeof line, "  %-*s  %-*s  %9s  %9s  %9s  %7s\n",
                static_cast<int>(topic_width), "topic", static_cast<int>(type_width), "type",
                "messages", "first s", "last s", "rate Hz");
  out << line;
  for (const logs::LogTopic& t : index.topics) {
    std::snprintf(line, sizeof line, "  %-*s  %-*s  %9llu  %9.2f  %9.2f  %7s\n",
                  static_cast<int>(topic_width), t.topic.c_str(), static_cast<int>(type_width),
                  t.type.c_str(), static_cast<unsigned long long>(t.messages), t.first_s, t.last_s,
                  Rate(t.messages, t.last_s - t.first_s).c_str());
    out << line;
  }
}

// Every scan topic (a bag may hold the raw and a filtered scan); the one used is marked when
// there are several.
void WriteScanStreams(std::ostream& out, const logs::LogIndex& index) {
  for (const logs::ScanStream& stream : index.scan_streams) {
    const logs::ScanGeometry& s = stream.geometry;
    if (s.scans == 0) continue;
    const bool used = stream.topic == index.scan_topic;
    out << "scans:      " << stream.topic
        << (used && index.scan_streams.size() > 1 ? " (used)" : "") << ": " << s.scans
        << " scans of " << s.beams << " beams over " << Degrees(s.field_of_view(), 1)
        << " deg from " << Degrees(s.angle_min, 1) << " deg, " << Degrees(s.angle_increment, 3)
        << " deg apart; ranges " << core::FixedText(s.range_min, 2) << " to "
        << core::FixedText(s.range_max, 2) << " m; frame "
        << (stream.frame.empty() ? "-" : stream.frame) << "\n";
  }
}

// A log without odometry (a motion-capture bag) is described, and what would stand in is named.
std::string NoOdometryLine(const logs::LogIndex& index) {
  const std::string line = "odometry:   none (" + index.odometry_missing + "): ";
  if (index.reference_topic.empty()) {
    return line +
           "log-teach and log-localize need it, or a reference to draw it from with "
           "--synthetic-odometry (--reference-topic or --reference FILE.tum)";
  }
  return line + "log-teach and log-localize draw it from the reference '" + index.reference_topic +
         "' with --synthetic-odometry";
}

void WriteOdometryAndMount(std::ostream& out, const logs::LogIndex& index) {
  if (!index.odometry_missing.empty()) out << NoOdometryLine(index) << "\n";
  if (!index.odometry_source.empty() && !index.odometry.empty()) {
    out << "odometry:   " << index.odometry_source << ": " << index.odometry.size() << " poses, "
        << core::FixedText(logs::PathLength(index.odometry), 1) << " m driven over "
        << core::FixedText(index.odometry.back().t - index.odometry.front().t, 1)
        << " s; base frame " << (index.base_frame.empty() ? "-" : index.base_frame) << "\n";
  }
  if (!index.mount_source.empty())
    out << "mount:      X_RL " << Pose(index.X_RL) << " from " << index.mount_source << "\n";
}

void WriteReference(std::ostream& out, const logs::LogIndex& index) {
  if (index.reference.empty() && !index.odometry_missing.empty()) {
    out << "reference:  none\n";
  } else if (index.reference.empty() && !index.scan_streams.empty()) {
    out << "reference:  none (a corrected log's odometry is its reference: "
           "--synthetic-odometry draws drifting odometry from it)\n";
  } else if (!index.reference.empty()) {
    out << "reference:  " << index.reference_source << ": " << index.reference.size() << " poses, "
        << core::FixedText(logs::PathLength(index.reference), 1) << " m\n";
  }
}

}  // namespace

std::string DescribeLog(const logs::LogIndex& index) {
  std::ostringstream out;
  std::uint64_t messages = 0;
  for (const logs::LogTopic& t : index.topics) messages += t.messages;
  out << index.name << ": " << logs::LogFormatName(index.format) << ", "
      << Duration(index.duration_s()) << ", " << messages << " messages\n";
  WriteTopicTable(out, index);
  WriteScanStreams(out, index);
  WriteOdometryAndMount(out, index);
  WriteReference(out, index);
  for (const std::string& note : index.notes) out << "note:       " << note << "\n";
  // Several topics of a stream are described; only the commands that use it must choose.
  if (index.needs_choice) {
    std::string choice = index.problem;
    if (choice.starts_with(index.name + ": ")) choice.erase(0, index.name.size() + 2);
    out << "choose:     " << choice << " (log-teach, log-localize)\n";
  }
  std::string text = out.str();
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

}  // namespace retrace::bench
