// Reading logs (logs/): a 60 s recorded drive — 1081-beam scans at 20 Hz, odometry, tf and a
// reference at 50 Hz, as `retrace run --record-log` writes it — through each reader, raw
// (the container only) and decoded (every scan and pose into core types), and the first pass
// of the log commands (logs::IndexLog). Bytes are the file's size on disk. The same messages in
// every container: MCAP (CDR), ROS 1 bags (ROS 1 serialization) and CARMEN (text).
//
//   ./retrace_micro_bench --benchmark_filter=Log --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "bench/micro/campus_map.hpp"
#include "logs/carmen_reader.hpp"
#include "logs/carmen_writer.hpp"
#include "logs/log_source.hpp"
#include "logs/mcap_writer.hpp"
#include "logs/ros1_bag_writer.hpp"
#include "logs/ros1_messages.hpp"
#include "logs/ros_messages.hpp"
#include "logs/sensor_log.hpp"

namespace {

namespace fs = std::filesystem;
using retrace::core::Pose2;

constexpr double kDuration = 60.0;  // s

struct LogFiles {
  fs::path folder;
  fs::path mcap_none, mcap_zstd, bag_none, bag_lz4, bag_bz2, carmen_plain, carmen_gz;
  LogFiles() = default;
  LogFiles(const LogFiles&) = delete;
  LogFiles& operator=(const LogFiles&) = delete;
  ~LogFiles() {  // at exit: the files go with the benchmark
    std::error_code ignored;
    fs::remove_all(folder, ignored);
  }
};

// The drive's scans (10 different ones, repeated), as a campus drive at 1 m/s sees them.
const retrace::bench_micro::CampusDrive& Drive() {
  static const retrace::bench_micro::CampusDrive drive =
      retrace::bench_micro::DriveThroughCampus(static_cast<int>(kDuration * 20.0 / 10.0), 0.02, 11);
  return drive;
}

// The drive as a ROS 1 bag: the MCAP file's messages in ROS 1 serialization and types.
void WriteRos1Bag(const fs::path& file, retrace::logs::Ros1BagCompression compression) {
  namespace logs = retrace::logs;
  logs::Ros1BagWriter w(file, compression);
  const auto scan = w.AddConnection("/scan", "sensor_msgs/LaserScan");
  const auto odom = w.AddConnection("/odom", "nav_msgs/Odometry");
  const auto tf = w.AddConnection("/tf", "tf2_msgs/TFMessage");
  const auto truth = w.AddConnection("/ground_truth", "geometry_msgs/PoseStamped");
  for (int k = 0; k < static_cast<int>(kDuration * 50.0); ++k) {
    const double t = k / 50.0;
    const Pose2 X(t, 0.0, 0.01 * t);
    const auto ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    w.Write(odom, ns, logs::EncodeRos1Odometry({t, "odom", "base_link", X}));
    w.Write(tf, ns, logs::EncodeRos1TfMessage({{{t, "odom", "base_link", X}}}));
    w.Write(truth, ns, logs::EncodeRos1PoseStamped({t, "world", X}));
    if (k % 5 == 0) {
      retrace::core::LaserScan s = Drive().scans[(k / 5) % Drive().scans.size()];
      s.stamp = t;
      w.Write(scan, ns, logs::EncodeRos1LaserScan({s, "laser"}));
    }
  }
  w.Close();
}

// Writes the drive once in every format: real campus scans along a 1 m/s drive.
const LogFiles& GetLogFiles() {
  static const std::unique_ptr<LogFiles> files = [] {
    auto f = std::make_unique<LogFiles>();
    f->folder = fs::temp_directory_path() / ("retrace_log_bench_" + std::to_string(::getpid()));
    fs::create_directories(f->folder);
    f->mcap_none = f->folder / "drive.mcap";
    f->mcap_zstd = f->folder / "drive_zstd.mcap";
    f->bag_none = f->folder / "drive.bag";
    f->bag_lz4 = f->folder / "drive_lz4.bag";
    f->bag_bz2 = f->folder / "drive_bz2.bag";
    f->carmen_plain = f->folder / "drive.log";
    f->carmen_gz = f->folder / "drive.log.gz";
    const retrace::bench_micro::CampusDrive& drive = Drive();
    namespace logs = retrace::logs;
    for (const fs::path& file : {f->mcap_none, f->mcap_zstd}) {
      logs::McapWriter w(
          file, file == f->mcap_none ? logs::McapCompression::kNone : logs::McapCompression::kZstd);
      const auto scan = w.AddChannel("/scan", "sensor_msgs/msg/LaserScan");
      const auto odom = w.AddChannel("/odom", "nav_msgs/msg/Odometry");
      const auto tf = w.AddChannel("/tf", "tf2_msgs/msg/TFMessage");
      const auto truth = w.AddChannel("/ground_truth", "geometry_msgs/msg/PoseStamped");
      for (int k = 0; k < static_cast<int>(kDuration * 50.0); ++k) {
        const double t = k / 50.0;
        const Pose2 X(t, 0.0, 0.01 * t);
        const auto ns = static_cast<std::int64_t>(std::llround(t * 1e9));
        w.Write(odom, ns, logs::EncodeOdometry({t, "odom", "base_link", X}));
        w.Write(tf, ns, logs::EncodeTfMessage({{{t, "odom", "base_link", X}}}));
        w.Write(truth, ns, logs::EncodePoseStamped({t, "world", X}));
        if (k % 5 == 0) {
          retrace::core::LaserScan s = drive.scans[(k / 5) % drive.scans.size()];
          s.stamp = t;
          w.Write(scan, ns, logs::EncodeLaserScan({s, "laser"}));
        }
      }
      w.Close();
    }
    WriteRos1Bag(f->bag_none, logs::Ros1BagCompression::kNone);
    WriteRos1Bag(f->bag_lz4, logs::Ros1BagCompression::kLz4);
    WriteRos1Bag(f->bag_bz2, logs::Ros1BagCompression::kBz2);
    for (const fs::path& file : {f->carmen_plain, f->carmen_gz}) {
      logs::CarmenWriter w(file);
      for (int k = 0; k < static_cast<int>(kDuration * 50.0); ++k) {
        const double t = k / 50.0;
        const Pose2 X(t, 0.0, 0.01 * t);
        w.WriteOdometry(t, X, 1.0, 0.01);
        w.WriteTruePose(t, X, X);
        if (k % 5 == 0) {
          retrace::core::LaserScan s = drive.scans[(k / 5) % drive.scans.size()];
          s.stamp = t;
          w.WriteLaser(s, X, Pose2(), 1.0, 0.01);
        }
      }
      w.Close();
    }
    return f;
  }();
  return *files;
}

// The container alone: every message handed out, nothing decoded.
void RawRead(benchmark::State& state, const fs::path& file) {
  for (auto _ : state) {
    const std::unique_ptr<retrace::logs::MessageSource> source = retrace::logs::OpenLog(file);
    retrace::logs::RawMessage m;
    std::size_t bytes = 0;
    while (source->Next(m)) bytes += m.data.size();
    benchmark::DoNotOptimize(bytes);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(fs::file_size(file)));
}

// What a log command reads: the first pass (all poses, the scans' geometry) and the second (every
// scan decoded). `content` is the same log uncompressed: its size per second is the rate of the
// log's content (bytes_per_second counts the bytes on disk).
void IndexAndScans(benchmark::State& state, const fs::path& file, const fs::path& content) {
  for (auto _ : state) {
    const retrace::logs::LogIndex index = retrace::logs::IndexLog(file);
    std::size_t beams = 0;
    retrace::logs::ReadScans(index, 0.0, 1e300, [&](const retrace::logs::ScanMessage& m, double) {
      beams += m.scan.size();
    });
    benchmark::DoNotOptimize(beams);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(fs::file_size(file)));
  state.counters["content_bytes_per_second"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(fs::file_size(content)),
      benchmark::Counter::kIsRate, benchmark::Counter::kIs1024);
}

void BM_LogReadMcap(benchmark::State& s) { RawRead(s, GetLogFiles().mcap_none); }
void BM_LogReadMcapZstd(benchmark::State& s) { RawRead(s, GetLogFiles().mcap_zstd); }
void BM_LogReadRos1Bag(benchmark::State& s) { RawRead(s, GetLogFiles().bag_none); }
void BM_LogReadRos1BagLz4(benchmark::State& s) { RawRead(s, GetLogFiles().bag_lz4); }
void BM_LogReadRos1BagBz2(benchmark::State& s) { RawRead(s, GetLogFiles().bag_bz2); }
void BM_LogReadCarmen(benchmark::State& s) { RawRead(s, GetLogFiles().carmen_plain); }
void BM_LogReadCarmenGzip(benchmark::State& s) { RawRead(s, GetLogFiles().carmen_gz); }
void BM_LogDecodeMcap(benchmark::State& s) {
  IndexAndScans(s, GetLogFiles().mcap_none, GetLogFiles().mcap_none);
}
void BM_LogDecodeMcapZstd(benchmark::State& s) {
  IndexAndScans(s, GetLogFiles().mcap_zstd, GetLogFiles().mcap_none);
}
void BM_LogDecodeRos1Bag(benchmark::State& s) {
  IndexAndScans(s, GetLogFiles().bag_none, GetLogFiles().bag_none);
}
void BM_LogDecodeRos1BagLz4(benchmark::State& s) {
  IndexAndScans(s, GetLogFiles().bag_lz4, GetLogFiles().bag_none);
}
void BM_LogDecodeRos1BagBz2(benchmark::State& s) {
  IndexAndScans(s, GetLogFiles().bag_bz2, GetLogFiles().bag_none);
}
void BM_LogDecodeCarmen(benchmark::State& s) {
  IndexAndScans(s, GetLogFiles().carmen_plain, GetLogFiles().carmen_plain);
}
void BM_LogDecodeCarmenGzip(benchmark::State& s) {
  IndexAndScans(s, GetLogFiles().carmen_gz, GetLogFiles().carmen_plain);
}
BENCHMARK(BM_LogReadMcap)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogReadMcapZstd)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogReadRos1Bag)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogReadRos1BagLz4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogReadRos1BagBz2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogReadCarmen)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogReadCarmenGzip)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogDecodeMcap)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogDecodeMcapZstd)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogDecodeRos1Bag)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogDecodeRos1BagLz4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogDecodeRos1BagBz2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogDecodeCarmen)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LogDecodeCarmenGzip)->Unit(benchmark::kMillisecond);

}  // namespace
