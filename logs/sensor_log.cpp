#include "logs/sensor_log.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string_view>

#include "core/config.hpp"
#include "core/errors.hpp"
#include "logs/carmen_reader.hpp"
#include "logs/internal/nominal_clock.hpp"
#include "logs/ros1_messages.hpp"
#include "logs/stream_messages.hpp"

namespace retrace::logs {

namespace {

// CARMEN laser messages, in the order a scan topic is chosen automatically (front first).
constexpr std::string_view kCarmenLasers[] = {"FLASER",    "ROBOTLASER1", "RAWLASER1",
                                              "RLASER",    "ROBOTLASER2", "RAWLASER2",
                                              "RAWLASER3", "RAWLASER4"};

bool IsCarmen(const RawMessage& m) { return m.encoding == "carmen"; }

// A laser scan of any topic (NominalClock counts them).
bool IsScanMessage(const RawMessage& m) {
  return IsCarmen(m) ? IsCarmenLaser(m.type) : StreamKindOf(m) == StreamKind::kScan;
}

// A used stream may have at most this share of its messages stamped before the one before them.
constexpr double kMaxBackwardsFraction = 0.01;

std::string Quote(std::string_view s) { return "'" + std::string(s) + "'"; }

// Runs `decode` and prefixes its error with the log, the message's number and its topic.
template <class F>
auto Decoded(const std::string& log, std::uint64_t number, std::string_view topic, F&& decode) {
  try {
    return decode();
  } catch (const core::IoError& e) {
    throw core::IoError(log + ": message " + std::to_string(number) + " on " + Quote(topic) + ": " +
                        e.what());
  }
}

std::string_view Text(const RawMessage& m) {
  return {reinterpret_cast<const char*>(m.data.data()), m.data.size()};
}

// The ipc_timestamp of a CARMEN line as it is spelled: the third field from the end.
std::string_view IpcStampText(std::string_view line) {
  std::size_t end = line.size();
  for (int field = 0; field < 3; ++field) {
    while (end > 0 && std::isspace(static_cast<unsigned char>(line[end - 1]))) --end;
    const std::size_t begin = line.find_last_of(" \t", end == 0 ? 0 : end - 1);
    const std::size_t start = begin == std::string_view::npos ? 0 : begin + 1;
    if (field == 2) return line.substr(start, end - start);
    if (start == 0) return {};
    end = start;
  }
  return {};
}

void SortByStamp(std::vector<StampedPose>& poses) {
  std::stable_sort(poses.begin(), poses.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.t < b.t; });
  // Keep the last of equal stamps: a pose cannot be in two places at one instant.
  std::vector<StampedPose> unique;
  unique.reserve(poses.size());
  for (const StampedPose& p : poses) {
    if (!unique.empty() && unique.back().t == p.t) {
      unique.back() = p;
    } else {
      unique.push_back(p);
    }
  }
  poses = std::move(unique);
}

// Everything the first pass gathers, before choosing.
struct Gathered {
  std::map<std::string, std::size_t, std::less<>> topic_index;
  std::map<std::string, ScanGeometry, std::less<>> scans;  // per scan topic
  std::map<std::string, std::string, std::less<>> scan_frame;
  std::map<std::string, std::vector<StampedPose>, std::less<>> odometry;     // per topic
  std::map<std::string, std::string, std::less<>> odometry_child;            // base frame per topic
  std::map<std::string, std::vector<StampedPose>, std::less<>> tf_odometry;  // per child frame
  std::map<std::string, TransformMessage, std::less<>> tf_static;            // by child frame
  std::map<std::string, std::vector<StampedPose>, std::less<>> poses;        // reference topics
  std::map<std::string, std::optional<core::Pose2>, std::less<>> carmen_mount;  // per laser
  CarmenLaserDefaults carmen_defaults;
  // Per scan topic, for people: where a quirk was first and last seen ("line 12", "message 12").
  struct ScanQuirks {
    std::string angle_max_first;  // the first scan whose angle_max disagrees
    double angle_max = 0.0;       // ... its angle_max (rad)
    double angle_max_expected = 0.0;
    std::string repeat_first;  // the first scan stamped as the one before it
    std::string repeat_last;
    std::string repeat_stamp;  // ... the stamp as the line spells it (CARMEN) or a number
  };
  std::map<std::string, ScanQuirks, std::less<>> scan_quirks;
  // Per topic, the messages with the earliest and the latest log time, to name them when they
  // follow another clock than the scans.
  struct LogTimes {
    std::int64_t min_ns = 0;
    std::int64_t max_ns = 0;
    std::string min_place;
    std::string max_place;
  };
  std::map<std::string, LogTimes, std::less<>> log_times;
  std::string place;  // where the message being gathered is
  // The message's nominal stamp (s) when the log's own are not used (StreamChoice::scan_rate_hz).
  std::optional<double> nominal;
  // The stamp to use for a message whose own stamp is `own`.
  double Stamp(double own) const { return nominal.value_or(own); }
  // Messages stamped before the one before them in their stream (a scan topic's geometry or a
  // pose stream): how many were dropped, and the first as an error. A few are dropped (the
  // Intel Research Lab log's laser lines step back 4 times in 910); a stream that does it often
  // has a broken clock and is refused, if it is used.
  struct Backwards {
    std::uint64_t dropped = 0;
    std::string first;
  };
  std::map<const void*, Backwards> backwards;

  // Throws if `stream` (`kept` messages kept) went back too often, else notes what was dropped.
  void RequireForward(const void* stream, std::uint64_t kept, std::string_view topic,
                      LogIndex& index) const {
    const auto it = backwards.find(stream);
    if (it == backwards.end()) return;
    const std::uint64_t dropped = it->second.dropped;
    if (dropped > kMaxBackwardsFraction * static_cast<double>(dropped + kept)) {
      throw core::IoError(it->second.first + "; " + std::to_string(dropped) + " of " +
                          std::to_string(dropped + kept) + " messages go back");
    }
    const std::string note = std::to_string(dropped) + " of " + std::to_string(dropped + kept) +
                             " messages on " + Quote(topic) +
                             " were stamped before the one before them and are not used";
    // The scans and the odometry of a CARMEN laser line are one message.
    if (std::find(index.notes.begin(), index.notes.end(), note) == index.notes.end())
      index.notes.push_back(note);
  }
};

std::string WentBack(const std::string& log, std::uint64_t number, std::string_view topic,
                     double stamp, double before) {
  return log + ": message " + std::to_string(number) + " on " + Quote(topic) + ": its stamp " +
         core::FormatNumber(stamp) + " s goes back before " + core::FormatNumber(before) +
         " s of the one before in the stream (a clock that runs backwards cannot be "
         "interpolated)";
}

// Appends a pose to its stream, or drops it (counted) if it is stamped before the stream's last
// (equal stamps are kept, the last one wins).
void AddPose(std::vector<StampedPose>& stream, double stamp, const core::Pose2& pose,
             const std::string& log, std::uint64_t number, std::string_view topic, Gathered& g) {
  if (!stream.empty() && stamp < stream.back().t) {
    Gathered::Backwards& b = g.backwards[&stream];
    if (b.dropped++ == 0) b.first = WentBack(log, number, topic, stamp, stream.back().t);
    return;
  }
  stream.push_back({stamp, pose});
}

// Counts a scan of message `number` into its topic's geometry (taken from the first scan), or
// drops it as AddPose does.
void AddScan(ScanGeometry& geometry, const ScanMessage& message, std::int64_t log_time_ns,
             const std::string& log, std::uint64_t number, std::string_view topic,
             Gathered& gathered, std::string_view stamp_text = {}) {
  const core::LaserScan& scan = message.scan;
  ScanGeometry& g = geometry;
  if (g.scans > 0 && scan.stamp < g.last_stamp) {
    Gathered::Backwards& b = gathered.backwards[&g];
    if (b.dropped++ == 0) b.first = WentBack(log, number, topic, scan.stamp, g.last_stamp);
    return;
  }
  Gathered::ScanQuirks& quirks = gathered.scan_quirks[std::string(topic)];
  if (g.scans == 0) {
    g.beams = scan.size();
    g.angle_min = scan.angle_min;
    g.angle_increment = scan.angle_increment;
    g.range_min = scan.range_min;
    g.range_max = scan.range_max;
    g.first_stamp = scan.stamp;
    g.first_log_ns = log_time_ns;
    g.last_log_ns = log_time_ns;
  } else if (scan.stamp == g.last_stamp) {
    if (g.repeated_stamps++ == 0) {
      quirks.repeat_first = gathered.place;
      quirks.repeat_stamp =
          stamp_text.empty() ? core::FormatNumber(scan.stamp) : std::string(stamp_text);
    }
    quirks.repeat_last = gathered.place;
  }
  if (message.angle_max && g.inconsistent_angle_max++ == 0) {
    quirks.angle_max_first = gathered.place;
    quirks.angle_max = *message.angle_max;
    quirks.angle_max_expected = scan.size() > 0 ? scan.Angle(scan.size() - 1) : scan.angle_min;
  }
  g.first_log_ns = std::min(g.first_log_ns, log_time_ns);
  g.last_log_ns = std::max(g.last_log_ns, log_time_ns);
  g.last_stamp = scan.stamp;
  ++g.scans;
}

// Chooses one of `candidates` (topics holding the wanted messages): the one named in `chosen`,
// or the only one.
// Several candidates and none chosen is only a problem for commands that use the stream: the
// error is kept in `ambiguous` (the first one wins) and nothing is chosen, so that the rest of the
// log is still chosen and described.
std::string Choose(const std::string& log, std::string_view what, std::string_view option,
                   const std::string& chosen, const std::vector<std::string>& candidates,
                   const LogIndex& index, std::string& ambiguous) {
  if (!chosen.empty()) {
    if (std::find(candidates.begin(), candidates.end(), chosen) != candidates.end()) return chosen;
    const bool exists = std::any_of(index.topics.begin(), index.topics.end(),
                                    [&](const LogTopic& t) { return t.topic == chosen; });
    throw core::IoError(
        log + ": " + std::string(option) + " " + Quote(chosen) +
        (exists ? " holds no " : " is not in the log, which has no such topic of ") +
        std::string(what));
  }
  if (candidates.size() == 1) return candidates.front();
  if (candidates.empty()) return {};
  std::string list;
  for (const std::string& c : candidates) list += (list.empty() ? "" : ", ") + c;
  if (ambiguous.empty()) {
    ambiguous = log + ": several topics hold " + std::string(what) + " (" + list +
                "); choose one with " + std::string(option);
  }
  return {};
}

template <class Map>
std::vector<std::string> Keys(const Map& map) {
  std::vector<std::string> keys;
  for (const auto& [key, value] : map) keys.push_back(key);
  return keys;
}

// X_{base laser} through the static transforms, walking up from the laser frame.
std::optional<core::Pose2> StaticChain(const Gathered& g, const std::string& base,
                                       const std::string& laser) {
  core::Pose2 X = core::Pose2::Identity();
  std::string frame = laser;
  for (std::size_t depth = 0; depth <= g.tf_static.size(); ++depth) {
    if (frame == base) return X;
    const auto it = g.tf_static.find(frame);
    if (it == g.tf_static.end()) return std::nullopt;
    X = it->second.X_PC * X;
    frame = it->second.parent;
  }
  return std::nullopt;  // a cycle
}

// The types a stream is read from in the log's ROS, for people.
std::string TypeNames(StreamKind kind, const LogIndex& index) {
  return StreamTypeNames(kind, index.format == LogFormat::kRos1Bag);
}

// The type of `topic`'s messages.
std::string TopicType(const LogIndex& index, const std::string& topic) {
  for (const LogTopic& t : index.topics) {
    if (t.topic == topic) return t.type;
  }
  return "";
}

void ChooseRosScans(const StreamChoice& choice, Gathered& g, LogIndex& index,
                    std::string& ambiguous) {
  const std::string& log = index.name;
  const std::string types = TypeNames(StreamKind::kScan, index);
  index.scan_topic = Choose(log, "laser scans (" + types + ")", "--scan-topic", choice.scan_topic,
                            Keys(g.scans), index, ambiguous);
  if (index.scan_topic.empty() && ambiguous.empty())
    throw core::IoError(log + ": no " + types + " topic: nothing to map or localize with");
  if (!index.scan_topic.empty()) {
    g.RequireForward(&g.scans[index.scan_topic], g.scans[index.scan_topic].scans, index.scan_topic,
                     index);
    index.scan = g.scans[index.scan_topic];
    index.laser_frame = g.scan_frame[index.scan_topic];
  }
}

// Without an odometry topic, the odometry is tf's transform from the odom frame to the robot's
// base frame: the one chosen, or the only frame tf moves there. A log without either has no
// odometry: that is kept in odometry_missing, not refused here, for a log with a reference can
// still be driven on odometry drawn from it (--synthetic-odometry, bench/replay/log_streams.hpp).
void ChooseTfOdometry(const StreamChoice& choice, Gathered& g, LogIndex& index) {
  const std::string& log = index.name;
  std::string base = choice.base_frame;
  if (base.empty()) {
    if (g.tf_odometry.size() > 1) {
      throw core::IoError(log + ": no odometry topic, and tf moves several frames in " +
                          Quote(choice.odom_frame) + "; choose the robot's with --base-frame");
    }
    if (!g.tf_odometry.empty()) base = g.tf_odometry.begin()->first;
  }
  const auto it = g.tf_odometry.find(base);
  if (it == g.tf_odometry.end()) {
    index.odometry_missing = "no " + TypeNames(StreamKind::kOdometry, index) +
                             " topic, no tf from " + Quote(choice.odom_frame) +
                             (base.empty() ? std::string() : " to " + Quote(base));
    index.base_frame = base;  // the mount is still found from the base chosen
    return;
  }
  g.RequireForward(&it->second, it->second.size(), "tf", index);
  index.odometry = std::move(it->second);
  index.base_frame = base;
  index.odometry_source = "tf " + choice.odom_frame + " -> " + base;
}

// Returns false when nothing more can be chosen.
bool ChooseRosOdometry(const StreamChoice& choice, Gathered& g, LogIndex& index,
                       std::string& ambiguous) {
  const std::string odometry_topic =
      Choose(index.name, "odometry (" + TypeNames(StreamKind::kOdometry, index) + ")",
             "--odometry-topic", choice.odometry_topic, Keys(g.odometry), index, ambiguous);
  if (!odometry_topic.empty()) {
    g.RequireForward(&g.odometry[odometry_topic], g.odometry[odometry_topic].size(), odometry_topic,
                     index);
    index.odometry = std::move(g.odometry[odometry_topic]);
    index.base_frame = g.odometry_child[odometry_topic];
    index.odometry_source = odometry_topic + " (" + TopicType(index, odometry_topic) + ")";
    return true;
  }
  // Several odometry topics: tf is not the odometry, and nothing more can be chosen.
  if (!ambiguous.empty() && g.odometry.size() > 1) return false;
  ChooseTfOdometry(choice, g, index);
  return true;
}

// The pose topics that can be a reference. Unless one is named, a topic of a single pose (an
// /initialpose set in rviz, a goal) is none: it is noted, not taken, nor counted as a choice.
std::vector<std::string> ReferenceCandidates(const StreamChoice& choice, const Gathered& g,
                                             LogIndex& index) {
  std::vector<std::string> candidates = Keys(g.poses);
  if (!choice.reference_topic.empty()) return candidates;
  std::erase_if(candidates, [&](const std::string& topic) {
    if (g.poses.find(topic)->second.size() > 1) return false;
    index.notes.push_back(Quote(topic) + " holds a single pose: not taken as the reference " +
                          "(--reference-topic takes it)");
    return true;
  });
  return candidates;
}

void ChooseRosReference(const StreamChoice& choice, Gathered& g, LogIndex& index,
                        std::string& ambiguous) {
  const std::string reference_topic =
      Choose(index.name, "poses (" + TypeNames(StreamKind::kPose, index) + ")", "--reference-topic",
             choice.reference_topic, ReferenceCandidates(choice, g, index), index, ambiguous);
  if (!reference_topic.empty()) {
    g.RequireForward(&g.poses[reference_topic], g.poses[reference_topic].size(), reference_topic,
                     index);
    index.reference = std::move(g.poses[reference_topic]);
    index.reference_topic = reference_topic;
    index.reference_source = reference_topic + " (" + TopicType(index, reference_topic) + ")";
  }
}

// The frame at the top of the static chain above `laser`: the robot's base where no odometry
// names it (tf_static hangs the LiDAR on the robot, and nothing the robot moves is static).
// Empty when no static transform leads up from the scans' frame.
std::string StaticRoot(const Gathered& g, const std::string& laser) {
  std::string frame = laser;
  for (std::size_t depth = 0; depth < g.tf_static.size(); ++depth) {  // bounded: a cycle
    const auto it = g.tf_static.find(frame);
    if (it == g.tf_static.end()) break;
    frame = it->second.parent;
  }
  return frame == laser ? std::string() : frame;
}

// The LiDAR's mount on the robot from tf_static; a log without one gets a note, not an error.
void FindRosMount(const Gathered& g, LogIndex& index) {
  const bool base_guessed = index.base_frame.empty();
  if (base_guessed) index.base_frame = StaticRoot(g, index.laser_frame);
  if (index.base_frame.empty()) {
    index.X_RL = core::Pose2::Identity();
    index.mount_source = "assumed at the base";
    index.notes.push_back(
        "no odometry names the robot's base frame and no static transform leads up from the "
        "scans' frame " +
        Quote(index.laser_frame) + ": the LiDAR is assumed at the robot's origin, facing forward");
    return;
  }
  if (const std::optional<core::Pose2> X_RL = StaticChain(g, index.base_frame, index.laser_frame)) {
    index.X_RL = *X_RL;
    index.mount_source = index.base_frame == index.laser_frame
                             ? "the scans are in the base frame"
                             : "tf_static " + index.base_frame + " -> " + index.laser_frame;
    if (base_guessed) {
      index.mount_source +=
          " (the top of the scans' static chain: no odometry names the base; --base-frame "
          "chooses another)";
    }
  } else {
    index.X_RL = core::Pose2::Identity();
    index.mount_source = "assumed at the base";
    index.notes.push_back("no static transform from " + Quote(index.base_frame) +
                          " to the scans' " + "frame " + Quote(index.laser_frame) +
                          ": the LiDAR is assumed at the robot's origin, facing forward");
  }
}

// Chooses the streams of a ROS log; returns the error of an ambiguous choice (empty: none).
std::string ChooseRos(const StreamChoice& choice, Gathered& g, LogIndex& index) {
  std::string ambiguous;
  ChooseRosScans(choice, g, index, ambiguous);
  if (!ChooseRosOdometry(choice, g, index, ambiguous)) return ambiguous;
  ChooseRosReference(choice, g, index, ambiguous);
  if (index.scan_topic.empty()) return ambiguous;  // no scans chosen: no mount to find
  FindRosMount(g, index);
  return ambiguous;
}

// The scan topic of a CARMEN log: the laser messages chosen, else the first of kCarmenLasers
// the log holds.
void ChooseCarmenScans(const StreamChoice& choice, Gathered& g, LogIndex& index) {
  const std::string& log = index.name;
  if (!choice.scan_topic.empty()) {
    if (!g.scans.contains(choice.scan_topic)) {
      throw core::IoError(log + ": --scan-topic " + Quote(choice.scan_topic) +
                          ": the log has no such laser messages");
    }
    index.scan_topic = choice.scan_topic;
  } else {
    for (std::string_view name : kCarmenLasers) {
      if (g.scans.contains(name)) {
        index.scan_topic = std::string(name);
        break;
      }
    }
  }
  if (index.scan_topic.empty()) {
    throw core::IoError(log + ": no laser messages (FLASER, ROBOTLASER1, RAWLASER1..4, RLASER): " +
                        "nothing to map or localize with");
  }
  g.RequireForward(&g.scans[index.scan_topic], g.scans[index.scan_topic].scans, index.scan_topic,
                   index);
  index.scan = g.scans[index.scan_topic];
  index.laser_frame = "laser";
  index.base_frame = "base_link";
}

// Odometry: the robot poses of the chosen laser lines (exactly at the scans), else ODOM. A log
// with neither has no odometry, kept in odometry_missing as for a ROS log (ChooseTfOdometry);
// lines chosen with --odometry-topic that the log lacks are an error.
void ChooseCarmenOdometry(const StreamChoice& choice, Gathered& g, LogIndex& index) {
  std::string odometry = choice.odometry_topic;
  if (odometry.empty()) {
    odometry = g.odometry.contains(index.scan_topic) ? index.scan_topic : "ODOM";
  }
  if (!g.odometry.contains(odometry)) {
    if (!choice.odometry_topic.empty())
      throw core::IoError(index.name + ": no odometry in " + Quote(odometry) + " lines");
    index.odometry_missing = "no ODOM lines, " + index.scan_topic + " lines carry no robot pose";
    return;
  }
  g.RequireForward(&g.odometry[odometry], g.odometry[odometry].size(), odometry, index);
  index.odometry = std::move(g.odometry[odometry]);
  index.odometry_source =
      odometry == "ODOM" ? "ODOM lines" : "the robot pose of the " + odometry + " lines";
}

void ChooseCarmenReference(const StreamChoice& choice, Gathered& g, LogIndex& index) {
  const std::string reference = choice.reference_topic.empty() ? "TRUEPOS" : choice.reference_topic;
  if (g.poses.contains(reference)) {
    g.RequireForward(&g.poses[reference], g.poses[reference].size(), reference, index);
    index.reference = std::move(g.poses[reference]);
    index.reference_topic = reference;
    index.reference_source = reference + " lines";
  } else if (!choice.reference_topic.empty()) {
    throw core::IoError(index.name + ": --reference-topic " + Quote(reference) +
                        ": the log has no such lines (CARMEN's reference is TRUEPOS)");
  }
}

// The LiDAR's mount from the laser lines' laser and robot poses; lines without a laser pose get a
// note, not an error.
void FindCarmenMount(Gathered& g, LogIndex& index) {
  const std::optional<core::Pose2>& mount = g.carmen_mount[index.scan_topic];
  if (mount) {
    index.X_RL = *mount;
    index.mount_source =
        "the laser pose relative to the robot pose in the " + index.scan_topic + " lines";
  } else {
    index.X_RL = core::Pose2::Identity();
    index.mount_source = "assumed at the base";
    index.notes.push_back(index.scan_topic +
                          " lines carry no laser pose: the LiDAR is assumed at " +
                          "the robot's origin, facing forward");
  }
}

// Chooses the streams of a CARMEN log (a choice is never ambiguous: the laser messages have an
// order).
void ChooseCarmen(const StreamChoice& choice, Gathered& g, LogIndex& index) {
  ChooseCarmenScans(choice, g, index);
  ChooseCarmenOdometry(choice, g, index);
  ChooseCarmenReference(choice, g, index);
  FindCarmenMount(g, index);
}

// A ROS message (either ROS) into the stream of its type; other messages are only counted.
void GatherRos(const RawMessage& m, std::uint64_t number, const StreamChoice& choice,
               const std::string& log, Gathered& g) {
  const StreamKind kind = StreamKindOf(m);
  if (kind == StreamKind::kNone) return;
  const std::string topic(m.topic);
  switch (kind) {
    case StreamKind::kScan: {
      ScanMessage scan = Decoded(log, number, m.topic, [&] { return DecodeStreamScan(m); });
      scan.scan.stamp = g.Stamp(scan.scan.stamp);
      ScanGeometry& geometry = g.scans[topic];
      if (geometry.scans == 0) g.scan_frame[topic] = scan.frame_id;
      AddScan(geometry, scan, m.log_time_ns, log, number, m.topic, g);
      break;
    }
    case StreamKind::kOdometry: {
      const OdometryMessage odom =
          Decoded(log, number, m.topic, [&] { return DecodeStreamOdometry(m); });
      AddPose(g.odometry[topic], g.Stamp(odom.stamp), odom.pose, log, number, m.topic, g);
      g.odometry_child.try_emplace(topic, odom.child_frame_id);
      break;
    }
    case StreamKind::kTf: {
      const TfMessage tf = Decoded(log, number, m.topic, [&] { return DecodeStreamTf(m); });
      const bool is_static = m.topic.find("tf_static") != std::string_view::npos;
      for (const TransformMessage& t : tf.transforms) {
        if (is_static) {
          g.tf_static[t.child] = t;
        } else if (t.parent == choice.odom_frame) {
          AddPose(g.tf_odometry[t.child], g.Stamp(t.stamp), t.X_PC, log, number, m.topic, g);
        }
      }
      break;
    }
    case StreamKind::kPose: {
      const PoseStampedMessage pose =
          Decoded(log, number, m.topic, [&] { return DecodeStreamPose(m); });
      AddPose(g.poses[topic], g.Stamp(pose.stamp), pose.pose, log, number, m.topic, g);
      break;
    }
    case StreamKind::kNone:
      break;
  }
}

void Gather(const RawMessage& m, std::uint64_t number, const StreamChoice& choice,
            const std::string& log, Gathered& g) {
  if (IsCarmen(m)) {
    const std::string_view line = Text(m);
    if (m.type == "PARAM") {
      Decoded(log, number, m.topic, [&] { return ApplyCarmenParamLine(line, g.carmen_defaults); });
    } else if (IsCarmenLaser(m.type)) {
      CarmenLaser laser =
          Decoded(log, number, m.topic, [&] { return ParseCarmenLaser(line, g.carmen_defaults); });
      laser.scan.scan.stamp = g.Stamp(laser.scan.scan.stamp);
      g.scan_frame.try_emplace(std::string(m.topic), laser.scan.frame_id);
      AddScan(g.scans[std::string(m.topic)], laser.scan, m.log_time_ns, log, number, m.topic, g,
              IpcStampText(line));
      if (laser.X_OR) {
        AddPose(g.odometry[std::string(m.topic)], laser.scan.scan.stamp, *laser.X_OR, log, number,
                m.topic, g);
        auto& mount = g.carmen_mount[std::string(m.topic)];
        if (!mount && laser.X_OL) mount = laser.X_OR->Inverse() * *laser.X_OL;
      }
    } else if (m.type == "ODOM") {
      const OdometryMessage odom =
          Decoded(log, number, m.topic, [&] { return ParseCarmenOdometry(line); });
      AddPose(g.odometry["ODOM"], g.Stamp(odom.stamp), odom.pose, log, number, m.topic, g);
    } else if (m.type == "TRUEPOS") {
      const PoseStampedMessage truth =
          Decoded(log, number, m.topic, [&] { return ParseCarmenTruePose(line); });
      AddPose(g.poses["TRUEPOS"], g.Stamp(truth.stamp), truth.pose, log, number, m.topic, g);
    }
    return;
  }
  GatherRos(m, number, choice, log, g);
}

// Refuses a scan stream whose scans mostly repeat the stamp before them: stamps printed with too
// few digits (CARMEN logs written with %g: every scan of an hour stamped 1.13486e+09) cannot
// order the scans nor place them on the odometry, and nothing in the log says how far apart
// they were.
void RequireDistinctScanStamps(Gathered& g, const LogIndex& index) {
  const ScanGeometry& scan = index.scan;
  if (scan.scans < 10 || static_cast<double>(scan.repeated_stamps) <=
                             kMaxRepeatedStampFraction * static_cast<double>(scan.scans)) {
    return;
  }
  const Gathered::ScanQuirks& q = g.scan_quirks[index.scan_topic];
  if (scan.repeated_stamps + 1 == scan.scans && scan.first_stamp == 0.0) {  // a log without time
    throw core::IoError(index.name + ": the scans on " + Quote(index.scan_topic) +
                        " carry no time stamps: all " + std::to_string(scan.scans) +
                        " are stamped " + q.repeat_stamp + " s (" + q.repeat_first + " to " +
                        q.repeat_last + "); give them nominal stamps with --scan-rate HZ");
  }
  throw core::IoError(
      index.name + ": " + std::to_string(scan.repeated_stamps) + " of " +
      std::to_string(scan.scans) + " scans on " + Quote(index.scan_topic) +
      " carry the same stamp as the scan before them (" + q.repeat_first + " to " + q.repeat_last +
      ", e.g. " + q.repeat_stamp +
      " s): the stamps were written with too few digits to order the scans and place them on "
      "the odometry; write the log with full-precision stamps (e.g. %.6f), or give the scans "
      "nominal stamps with --scan-rate HZ");
}

std::string StampSpan(const std::vector<StampedPose>& poses) {
  return core::FormatNumber(poses.front().t) + " to " + core::FormatNumber(poses.back().t) + " s";
}

// Odometry that does not overlap the scans in time follows another clock: refused, naming both
// spans. A reference that does not is dropped with a note (the log is still usable without).
void RequireOverlappingClocks(LogIndex& index) {
  const ScanGeometry& scan = index.scan;
  if (scan.scans == 0) return;
  const std::string scans = "the scans (" + index.scan_topic + ", stamps " +
                            core::FormatNumber(scan.first_stamp) + " to " +
                            core::FormatNumber(scan.last_stamp) + " s)";
  const auto apart = [&](const std::vector<StampedPose>& poses) {
    return !poses.empty() &&
           (poses.back().t < scan.first_stamp || poses.front().t > scan.last_stamp);
  };
  if (apart(index.odometry)) {
    throw core::IoError(index.name + ": the odometry (" + index.odometry_source + ", stamps " +
                        StampSpan(index.odometry) + ") and " + scans +
                        " do not overlap in time: they follow two clocks");
  }
  if (apart(index.reference)) {
    index.notes.push_back("the reference (" + index.reference_source + ", stamps " +
                          StampSpan(index.reference) + ") does not overlap " + scans +
                          " in time (two clocks): it is not used");
    index.reference.clear();
    index.reference_topic.clear();
    index.reference_source.clear();
  }
}

std::string AngleMaxNote(const ScanStream& stream, const Gathered::ScanQuirks& q) {
  const ScanGeometry& s = stream.geometry;
  const double off = std::abs(q.angle_max - q.angle_max_expected) / std::abs(s.angle_increment);
  const auto round4 = [](double rad) { return std::round(rad * 1e4) / 1e4; };  // float32 angles
  return Quote(stream.topic) + ": angle_max of " + std::to_string(s.inconsistent_angle_max) +
         " of " + std::to_string(s.scans) + " scans is " +
         core::FormatNumber(std::round(off * 10.0) / 10.0) +
         " increments from angle_min + (n - 1) * angle_increment (the first, " + q.angle_max_first +
         ": " + core::FormatNumber(round4(q.angle_max)) + " rad for " +
         core::FormatNumber(round4(q.angle_max_expected)) +
         " rad): beam i is taken at angle_min + i * angle_increment, as ROS consumers do";
}

// Names the topics whose log times lie more than kOtherClock outside the scans' [from, to]: they
// follow another clock (PARAM lines stamped since the epoch beside scans stamped since the
// logger started, or the other way round). Empty when there are none.
std::string OtherClockNote(const Gathered& g, const LogIndex& index, std::int64_t from_ns,
                           std::int64_t to_ns) {
  const auto margin = static_cast<std::int64_t>(kOtherClock * 1e9);
  std::string list;
  for (const LogTopic& t : index.topics) {
    const Gathered::LogTimes& times = g.log_times.find(t.topic)->second;
    const bool early = times.min_ns < from_ns - margin;
    const bool late = times.max_ns > to_ns + margin;
    if (!early && !late) continue;
    const std::int64_t ns = early ? times.min_ns : times.max_ns;
    list += (list.empty() ? "" : ", ") + Quote(t.topic) + " (" + std::to_string(t.messages) +
            (t.messages == 1 ? " message" : " messages") + "; " +
            (early ? times.min_place : times.max_place) + " at " +
            core::FormatNumber(index.Since(ns)) + " s)";
  }
  if (list.empty()) return {};
  return "log times from two clocks: " + list + " lie more than " +
         core::FormatNumber(kOtherClock) + " s outside the scans' (0 to " +
         core::FormatNumber(static_cast<double>(to_ns - from_ns) * 1e-9) +
         " s): they follow another clock than the scans; times (--from, --to) count from the "
         "first scan";
}

// Counts message `m` into its topic (listed at its first message): how many, its first and last
// log times, and where its earliest and latest log times are.
void CountMessage(const RawMessage& m, Gathered& g, LogIndex& index) {
  auto [it, added] = g.topic_index.try_emplace(std::string(m.topic), index.topics.size());
  if (added) {
    index.topics.push_back({std::string(m.topic), std::string(m.type), 0, 0.0, 0.0});
    index.topics.back().first_s = static_cast<double>(m.log_time_ns);
    g.log_times[std::string(m.topic)] = {m.log_time_ns, m.log_time_ns, g.place, g.place};
  }
  LogTopic& topic = index.topics[it->second];
  ++topic.messages;
  topic.last_s = static_cast<double>(m.log_time_ns);
  Gathered::LogTimes& times = g.log_times.find(m.topic)->second;
  if (m.log_time_ns < times.min_ns) times = {m.log_time_ns, times.max_ns, g.place, times.max_place};
  if (m.log_time_ns > times.max_ns) times = {times.min_ns, m.log_time_ns, times.min_place, g.place};
}

// The first pass over the log: counts every message into its topic and the log's span, and
// gathers the streams to choose from.
void GatherLog(const std::filesystem::path& path, const StreamChoice& choice, Gathered& g,
               LogIndex& index) {
  const std::unique_ptr<MessageSource> source = OpenLog(path);
  const auto* carmen = dynamic_cast<const CarmenReader*>(source.get());
  NominalClock clock(choice.scan_rate_hz);
  RawMessage m;
  std::uint64_t number = 0;
  while (source->Next(m)) {
    ++number;
    g.place = carmen != nullptr ? "line " + std::to_string(carmen->line())
                                : "message " + std::to_string(number);
    if (clock.on()) {
      g.nominal = clock.Next(IsScanMessage(m));
      m.log_time_ns = NominalClock::Nanoseconds(*g.nominal);
    }
    if (number == 1) index.start_ns = m.log_time_ns;
    index.end_ns = std::max(index.end_ns, m.log_time_ns);
    CountMessage(m, g, index);
    Gather(m, number, choice, index.name, g);
  }
  if (number == 0) throw core::IoError(index.name + ": the log holds no message");
  index.start_ns = std::min(index.start_ns, index.end_ns);
  for (std::string& note : source->notes()) index.notes.push_back(std::move(note));
}

// The scan streams, in the order of their topics' first messages.
void ListScanStreams(Gathered& g, LogIndex& index) {
  for (const LogTopic& t : index.topics) {
    const auto scans = g.scans.find(t.topic);
    if (scans != g.scans.end())
      index.scan_streams.push_back({t.topic, g.scan_frame[t.topic], scans->second});
  }
}

// Chooses the streams and checks them. A log that cannot be used is still described: why is kept
// in `problem` (with `needs_choice` when choosing a stream would do).
void ChooseStreams(const StreamChoice& choice, Gathered& g, LogIndex& index) {
  try {
    std::string ambiguous;
    if (choice.scan_rate_hz > 0.0 && index.scan_streams.size() > 1) {
      throw core::IoError(index.name + ": --scan-rate stamps the scans by their order, which " +
                          "needs one scan topic; the log has " +
                          std::to_string(index.scan_streams.size()));
    }
    if (index.format == LogFormat::kCarmen) {
      ChooseCarmen(choice, g, index);
    } else {
      ambiguous = ChooseRos(choice, g, index);
    }
    if (!index.scan_topic.empty()) RequireDistinctScanStamps(g, index);
    SortByStamp(index.odometry);
    SortByStamp(index.reference);
    if (!index.odometry_source.empty() && index.odometry.size() < 2) {
      throw core::IoError(index.name + ": fewer than two odometry poses in " +
                          index.odometry_source);
    }
    if (!index.scan_topic.empty()) RequireOverlappingClocks(index);
    if (!ambiguous.empty()) {
      index.needs_choice = true;
      throw core::IoError(ambiguous);
    }
  } catch (const core::IoError& e) {
    index.problem = e.what();
  }
}

// The log times of the first and the last scan.
struct ScanLogTimes {
  std::int64_t first_ns = 0;
  std::int64_t last_ns = 0;
};

// The log times of the scans of the chosen stream, else of any; none in a log without scans.
std::optional<ScanLogTimes> FindScanLogTimes(const LogIndex& index) {
  std::optional<std::int64_t> scans_from, scans_to;
  for (const ScanStream& stream : index.scan_streams) {
    if (stream.geometry.scans == 0) continue;
    if (!index.scan_topic.empty() && stream.topic != index.scan_topic) continue;
    scans_from =
        std::min(scans_from.value_or(stream.geometry.first_log_ns), stream.geometry.first_log_ns);
    scans_to =
        std::max(scans_to.value_or(stream.geometry.last_log_ns), stream.geometry.last_log_ns);
  }
  if (!scans_from) return std::nullopt;
  return ScanLogTimes{*scans_from, *scans_to};
}

// Counts the topics' first and last log times (gathered in ns) in seconds from `origin_ns`.
void SetLogOrigin(std::int64_t origin_ns, LogIndex& index) {
  index.origin_ns = origin_ns;
  for (LogTopic& t : index.topics) {
    t.first_s = (t.first_s - static_cast<double>(index.origin_ns)) * 1e-9;
    t.last_s = (t.last_s - static_cast<double>(index.origin_ns)) * 1e-9;
  }
}

// Notes the scan streams (the chosen one, else all) whose angle_max disagrees with their beams.
void NoteInconsistentAngleMax(Gathered& g, LogIndex& index) {
  for (const ScanStream& stream : index.scan_streams) {
    if (!index.scan_topic.empty() && stream.topic != index.scan_topic) continue;
    if (stream.geometry.inconsistent_angle_max > 0)
      index.notes.push_back(AngleMaxNote(stream, g.scan_quirks[stream.topic]));
  }
}

// Notes the scan streams (the chosen one, else all) that keep several echoes per beam.
void NoteMultiEchoScans(LogIndex& index) {
  for (const ScanStream& stream : index.scan_streams) {
    if (!index.scan_topic.empty() && stream.topic != index.scan_topic) continue;
    if (TopicType(index, stream.topic) == kRos1MultiEchoLaserScanType) {
      index.notes.push_back(Quote(stream.topic) + " holds " +
                            std::string(kRos1MultiEchoLaserScanType) +
                            ": the first echo of each beam is its range (a beam without echoes "
                            "is no return)");
    }
  }
}

}  // namespace

LogIndex IndexLog(const std::filesystem::path& path, const StreamChoice& choice) {
  LogIndex index;
  index.name = path.string();
  index.format = DetectLogFormat(path);
  Gathered g;
  GatherLog(path, choice, g, index);
  ListScanStreams(g, index);
  ChooseStreams(choice, g, index);
  if (choice.scan_rate_hz > 0.0) {
    index.nominal_scan_rate_hz = choice.scan_rate_hz;
    index.notes.push_back("nominal stamps (--scan-rate " + core::FormatNumber(choice.scan_rate_hz) +
                          " Hz): scan k at k / " + core::FormatNumber(choice.scan_rate_hz) +
                          " s, every other message at the last scan's; the log's own stamps are "
                          "not used");
  }

  // Log times for people count from the first scan (of the chosen stream, else of any).
  const std::optional<ScanLogTimes> scans = FindScanLogTimes(index);
  SetLogOrigin(scans ? scans->first_ns : index.start_ns, index);
  NoteInconsistentAngleMax(g, index);
  NoteMultiEchoScans(index);
  if (scans) {
    const std::string note = OtherClockNote(g, index, scans->first_ns, scans->last_ns);
    if (!note.empty()) index.notes.push_back(note);
  }
  return index;
}

void RequireUsable(const LogIndex& index) {
  if (!index.problem.empty()) throw core::IoError(index.problem);
}

void ReadScans(const LogIndex& index, double from_s, double to_s,
               const std::function<void(const ScanMessage&, double)>& on_scan) {
  const std::unique_ptr<MessageSource> source = OpenLog(index.name);
  CarmenLaserDefaults carmen_defaults;
  NominalClock clock(index.nominal_scan_rate_hz);  // as IndexLog counted
  RawMessage m;
  std::uint64_t number = 0;
  std::optional<double> last_stamp;
  while (source->Next(m)) {
    ++number;
    const double nominal = clock.on() ? clock.Next(IsScanMessage(m)) : 0.0;
    if (clock.on()) m.log_time_ns = NominalClock::Nanoseconds(nominal);
    if (IsCarmen(m) && m.type == "PARAM") {
      ApplyCarmenParamLine(Text(m), carmen_defaults);
      continue;
    }
    if (m.topic != index.scan_topic) continue;
    const double t = index.Since(m.log_time_ns);
    if (t < from_s) continue;
    if (t > to_s) break;
    ScanMessage scan =
        IsCarmen(m) ? Decoded(index.name, number, m.topic,
                              [&] { return ParseCarmenLaser(Text(m), carmen_defaults).scan; })
                    : Decoded(index.name, number, m.topic, [&] { return DecodeStreamScan(m); });
    if (clock.on()) scan.scan.stamp = nominal;
    // As in IndexLog: a scan stamped before the one before it is not used.
    if (last_stamp && scan.scan.stamp < *last_stamp) continue;
    last_stamp = scan.scan.stamp;
    on_scan(scan, t);
  }
}

std::optional<core::Pose2> PoseAt(const std::vector<StampedPose>& poses, double stamp) {
  if (poses.empty() || stamp < poses.front().t || stamp > poses.back().t) return std::nullopt;
  const auto after = std::lower_bound(poses.begin(), poses.end(), stamp,
                                      [](const StampedPose& p, double s) { return p.t < s; });
  if (after->t == stamp || after == poses.begin()) return after->pose;
  const StampedPose& a = *(after - 1);
  const StampedPose& b = *after;
  return core::Interpolate(a.pose, b.pose, (stamp - a.t) / (b.t - a.t));
}

double PathLength(const std::vector<StampedPose>& poses) {
  double length = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i)
    length += core::Distance(poses[i - 1].pose, poses[i].pose);
  return length;
}

}  // namespace retrace::logs
