// `retrace run --video`: a playback run recorded while it drives. The video has the frames its
// speed-up asks for, and watching a run does not change it.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "bench/engine/playback.hpp"
#include "bench/engine/scenario.hpp"
#include "bench/engine/teach_drive.hpp"
#include "bench/output/video_recorder.hpp"
#include "core/rng.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/trajectory_hash.hpp"
#include "viz/video.hpp"

namespace retrace::bench {
namespace {

using testing::TrajectoryHash;

using retrace::testing::kSource;

// Counts the ticks a recorder saw and checks what it is shown, around a real recorder.
class CountingObserver final : public PlaybackObserver {
 public:
  explicit CountingObserver(PlaybackObserver& inner) : inner_(inner) {}
  void OnTick(const PlaybackMoment& m) override {
    ++ticks;
    EXPECT_GT(m.time, last_time);
    last_time = m.time;
    EXPECT_LT(m.server.index(), m.server.bundle().maps.size());
    if (m.lidar != nullptr) ++ticks_with_scan;
    inner_.OnTick(m);
  }
  void OnEnd() override {
    ++ends;
    inner_.OnEnd();
  }
  int ticks = 0;
  int ticks_with_scan = 0;
  int ends = 0;
  double last_time = -1.0;

 private:
  PlaybackObserver& inner_;
};

TEST(VideoRecorder, RecordsTheRunAtItsSpeedUpWithoutChangingIt) {
  const Scenario scenario = LoadScenario(kSource / "scenarios/small.yaml");
  TeachResult teach = RunTeachDrive(scenario, {MapMode::kPartial});
  const ModeTeach& mode = teach.modes.front();
  const RunTrace plain = RunPlayback(scenario, mode.bundle, mode.trace, 0, 300.0);

  testing::TempDir dir;
  VideoOptions options;
  options.speedup = 20.0;
  options.fps = 10.0;  // a frame every 2 s of the run
  options.width = 320;
  options.height = 240;
  VideoRecorder recorder(dir.path() / "runs" / "0" / "video.mp4", "partial maps, run 0",
                         scenario.config.sim.robot.radius, options);
  CountingObserver observer(recorder);
  const RunTrace watched = RunPlayback(scenario, mode.bundle, mode.trace, 0, 300.0, {}, &observer);

  EXPECT_EQ(TrajectoryHash(watched), TrajectoryHash(plain));
  EXPECT_EQ(watched.outcome, plain.outcome);
  EXPECT_EQ(observer.ticks, static_cast<int>(watched.samples.size()));
  EXPECT_GT(observer.ticks_with_scan, observer.ticks / 2);
  EXPECT_EQ(observer.ends, 1);

  // One frame per 2 s of the run, from t = 0: ceil(duration / 2) frames.
  const double duration = watched.samples.back().time;
  const int expected = static_cast<int>(std::floor(duration / 2.0)) + 1;
  EXPECT_NEAR(recorder.frames(), expected, 1);
  ASSERT_TRUE(std::filesystem::exists(recorder.path()));
  const viz::VideoInfo info = viz::ProbeVideo(recorder.path());
  EXPECT_EQ(info.width, 320);
  EXPECT_EQ(info.height, 240);
  EXPECT_EQ(info.frames, recorder.frames());
  EXPECT_NEAR(info.fps, 10.0, 0.01);
}

}  // namespace
}  // namespace retrace::bench
