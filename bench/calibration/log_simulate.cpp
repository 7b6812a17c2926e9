#include "bench/calibration/log_simulate.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench/calibration/unmapped_calibration.hpp"
#include "core/angle.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"
#include "io/ros_map.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/raw_message.hpp"
#include "logs/ros_messages.hpp"
#include "sim/lidar.hpp"
#include "sim/world_file.hpp"

namespace retrace::bench {

namespace {

// The smallest range the simulated LiDAR may have (m): a log's 0 means "not given".
constexpr double kMinRangeMin = 0.01;

// The world is the one map of a teach folder built with a reference; the log has a reference to
// drive in it.
void RequireSimulatableLog(const logs::LogIndex& index, const LogStreams& streams,
                           const ModeTeach& world_teach,
                           const std::filesystem::path& world_teach_dir) {
  if (world_teach.bundle.maps.size() != 1 || world_teach.trace.X_WR.empty()) {
    throw core::ConfigError("--teach",
                            "the world is the map of a teach folder of one map built with a "
                            "reference (log-teach's consistent/teach); " +
                                world_teach_dir.string() + " holds " +
                                std::to_string(world_teach.bundle.maps.size()) + " maps" +
                                (world_teach.trace.X_WR.empty() ? " and no reference" : ""));
  }
  if (streams.reference.empty()) {
    throw core::IoError(index.name +
                        ": no reference to drive in the simulator (give --reference FILE, or "
                        "--synthetic-odometry for a corrected log)");
  }
}

// The log's LiDAR. The simulator centres its fan on the LiDAR's x axis; a log's fan may not be
// (the Intel log's runs from -90 to +89 degrees), so the simulated LiDAR is turned by the
// centre's angle and its scans are labelled with the log's angles again.
sim::LidarConfig LoggedLidar(const logs::ScanGeometry& g, const LogStreams& streams,
                             const LogConfig& config) {
  const double fov = g.field_of_view();
  sim::LidarConfig lidar;
  lidar.beams = static_cast<int>(g.beams);
  lidar.fov_deg = core::RadToDeg(fov);
  lidar.range_min = std::max(g.range_min, kMinRangeMin);
  lidar.range_max = g.range_max;
  lidar.noise = config.sim.lidar.noise;
  lidar.mount = streams.robot.X_RL * core::Pose2(0.0, 0.0, g.angle_min + 0.5 * fov);
  return lidar;
}

// The world: the taught map in its frame M, its unknown cells filled at the configured free path
// except along the window's reference, and the clutter drawn beside that reference (standing
// people as discs: the scans are all that is simulated).
sim::StaticGeometry SimulatedWorld(const logs::LogIndex& index, const LogStreams& streams,
                                   const core::Pose2& X_MW, const ModeTeach& world_teach,
                                   const LogConfig& config, const LogWindow& window) {
  const core::Rng rng = core::Rng(config.seed).Split("log-simulate world");
  const double origin_s = 1e-9 * static_cast<double>(index.origin_ns);
  const std::vector<core::Vec2> route =
      RouteInMap(streams.reference, X_MW, origin_s + window.from_s, origin_s + window.to_s);
  const core::OccupancyGrid grid =
      ClearedAlongRoute(world_teach.bundle.maps.front().grid, route, config.clutter);
  const std::string name = "the teach folder's map";
  sim::StaticGeometry geometry;
  if (config.clutter.enabled()) {
    if (route.size() < 2) {
      throw core::IoError(index.name +
                          ": the reference does not move in the window: no route "
                          "to place the clutter beside");
    }
    // The clutter stands in the map's known free space, where calibrate-lidar measured it:
    // placed in the map with every cell that is not known free solid.
    sim::StaticGeometry known_free;
    sim::AddMapGeometry(grid, {name, io::kRosMapKnownFreeBelow}, &known_free);
    Clutter clutter;
    try {
      clutter =
          GenerateClutter(config.clutter, ClutterSite{&route, &known_free}, rng.Split("clutter"));
    } catch (const core::ConfigError& e) {
      throw core::ConfigError("clutter." + e.key_path(), e.detail());
    }
    sim::WorldConfig objects;
    objects.boxes = clutter.boxes;
    objects.circles = clutter.circles;
    for (const core::Vec2& p : clutter.standing)
      objects.circles.push_back({p, config.clutter.person_radius});
    if (!objects.boxes.empty() || !objects.circles.empty())
      geometry = sim::BuildGeometry(objects, {});
  }
  sim::AddMapGeometry(grid, {name, 0.65, config.sim.unknown_free_path, rng.Split("unknown").seed()},
                      &geometry);
  return geometry;
}

// The simulated log being written: the log's odometry and reference, from the first simulated
// scan's stamp on, interleaved with the simulated scans in stamp order.
class SimulatedLogWriter {
 public:
  SimulatedLogWriter(const std::filesystem::path& out, const LogStreams& streams)
      : streams_(streams),
        writer_(out, logs::McapCompression::kZstd),
        scan_channel_(writer_.AddChannel("/scan", "sensor_msgs/msg/LaserScan")),
        odom_channel_(writer_.AddChannel("/odom", "nav_msgs/msg/Odometry")),
        truth_channel_(writer_.AddChannel("/ground_truth", "geometry_msgs/msg/PoseStamped")),
        static_channel_(writer_.AddChannel("/tf_static", "tf2_msgs/msg/TFMessage")) {}

  // The LiDAR's mount, once, at the first scan's stamp (from which the poses are written).
  void Start(double stamp) {
    first_stamp_ = stamp;
    writer_.Write(static_channel_, logs::LogTimeNs(stamp),
                  logs::EncodeTfMessage({{{stamp, "base_link", "laser", streams_.robot.X_RL}}}));
  }

  // The poses up to `stamp` not written yet, from the first scan's on.
  void WritePosesUpTo(double stamp) {
    for (;
         next_odometry_ < streams_.odometry.size() && streams_.odometry[next_odometry_].t <= stamp;
         ++next_odometry_) {
      const io::StampedPose& p = streams_.odometry[next_odometry_];
      if (p.t < first_stamp_) continue;
      writer_.Write(odom_channel_, logs::LogTimeNs(p.t),
                    logs::EncodeOdometry({p.t, "odom", "base_link", p.pose}));
    }
    for (; next_reference_ < streams_.reference.size() &&
           streams_.reference[next_reference_].t <= stamp;
         ++next_reference_) {
      const io::StampedPose& p = streams_.reference[next_reference_];
      if (p.t < first_stamp_) continue;
      writer_.Write(truth_channel_, logs::LogTimeNs(p.t),
                    logs::EncodePoseStamped({p.t, "world", p.pose}));
    }
  }

  void WriteScan(double stamp, const core::LaserScan& scan) {
    writer_.Write(scan_channel_, logs::LogTimeNs(stamp), logs::EncodeLaserScan({scan, "laser"}));
  }

  void Close() { writer_.Close(); }

 private:
  const LogStreams& streams_;
  logs::McapWriter writer_;
  std::uint16_t scan_channel_;
  std::uint16_t odom_channel_;
  std::uint16_t truth_channel_;
  std::uint16_t static_channel_;
  double first_stamp_ = 0.0;
  std::size_t next_odometry_ = 0;
  std::size_t next_reference_ = 0;
};

}  // namespace

LogSimulation SimulateScans(const logs::LogIndex& index, const LogStreams& streams,
                            const ModeTeach& world_teach,
                            const std::filesystem::path& world_teach_dir, const LogConfig& config,
                            const LogWindow& window, const SimulatedScanSink& sink) {
  RequireSimulatableLog(index, streams, world_teach, world_teach_dir);
  const TeachMapTrace& trace = world_teach.trace.maps.front();
  const core::Pose2 X_MW = trace.X_MR.front() * trace.X_WR.front().Inverse();
  const sim::StaticGeometry geometry =
      SimulatedWorld(index, streams, X_MW, world_teach, config, window);
  const logs::ScanGeometry& g = index.scan;
  const sim::Lidar sensor(LoggedLidar(g, streams, config), geometry);
  core::Rng rng = core::Rng(config.seed).Split("log-simulate");
  LogSimulation result;
  logs::ReadScans(index, window.from_s, window.to_s, [&](const logs::ScanMessage& m, double) {
    const double stamp = m.scan.stamp;
    const std::optional<core::Pose2> X_WR = logs::PoseAt(streams.reference, stamp);
    if (!X_WR || !logs::PoseAt(streams.odometry, stamp)) return;
    if (result.scans == 0) result.first_stamp = stamp;
    const core::Pose2 X_MR = X_MW * *X_WR;
    sim::LidarReading reading = sensor.Scan(X_MR, {}, stamp, rng);
    reading.scan.angle_min = g.angle_min;
    reading.scan.angle_increment = g.angle_increment;
    sink(stamp, X_MR, reading.scan);
    result.last_stamp = stamp;
    ++result.scans;
  });
  if (result.scans == 0) {
    throw core::IoError(index.name + ": no scan with odometry and reference between " +
                        core::FormatNumber(window.from_s) + " and " +
                        core::FormatNumber(window.to_s) + " s of the log");
  }
  return result;
}

LogSimulation SimulateLog(const logs::LogIndex& index, const LogStreams& streams,
                          const ModeTeach& world_teach,
                          const std::filesystem::path& world_teach_dir, const LogConfig& config,
                          const LogWindow& window, const std::filesystem::path& out) {
  RequireSimulatableLog(index, streams, world_teach, world_teach_dir);
  SimulatedLogWriter writer(out, streams);
  bool started = false;
  const LogSimulation result =
      SimulateScans(index, streams, world_teach, world_teach_dir, config, window,
                    [&](double stamp, const core::Pose2&, const core::LaserScan& scan) {
                      if (!started) writer.Start(stamp);
                      started = true;
                      writer.WritePosesUpTo(stamp);
                      writer.WriteScan(stamp, scan);
                    });
  // The poses up to a little past the last scan, so that its odometry interpolates.
  writer.WritePosesUpTo(result.last_stamp + 1.0);
  writer.Close();
  return result;
}

}  // namespace retrace::bench
