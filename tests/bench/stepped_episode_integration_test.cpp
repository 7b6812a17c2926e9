// The stepping API: retrace's own stack stepped by a caller gives exactly RunPlayback's run and
// metrics; the teaching drive's recording is handed out; misuse is refused with one message.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "bench/engine/playback.hpp"
#include "bench/run/stepped_episode.hpp"
#include "core/errors.hpp"
#include "tests/support/source_dir.hpp"
#include "tests/support/trajectory_hash.hpp"

namespace retrace::bench {
namespace {

TeachingRequest SmallRequest() {
  TeachingRequest r;
  r.scenario = retrace::testing::kSource / "scenarios/small.yaml";
  r.mode = "partial";
  return r;
}

TEST(SteppedEpisode, TheBuiltinStackSteppedByTheCallerGivesRunPlaybacksRunAndMetrics) {
  SteppedEpisode episode(TeachForStepping(SmallRequest()), 1, true);
  int steps = 0;
  std::size_t scans = 0;
  while (!episode.done()) {
    scans += episode.Observe().scans.size();
    episode.Act(std::nullopt);
    ++steps;
  }
  const SteppedTeaching& teaching = episode.teaching();
  const RunTrace reference =
      RunPlayback(teaching.scenario, teaching.teach.bundle, teaching.teach.trace, 1,
                  PlaybackTimeout(teaching.scenario, teaching.duration_s));
  EXPECT_EQ(retrace::testing::TrajectoryHash(episode.trace()),
            retrace::testing::TrajectoryHash(reference));
  EXPECT_EQ(steps, static_cast<int>(reference.samples.size()));
  EXPECT_EQ(episode.trace().updates.size(), reference.updates.size());
  EXPECT_GT(scans, reference.updates.size());
  const RunMetrics a = episode.Metrics();
  const RunMetrics b =
      ComputeRunMetrics(teaching.teach.trace, reference, teaching.scenario.config.metrics);
  EXPECT_EQ(a.success, b.success);
  EXPECT_DOUBLE_EQ(a.tracking_error_m.rms, b.tracking_error_m.rms);
  EXPECT_DOUBLE_EQ(a.localization_error_m.rms, b.localization_error_m.rms);
  EXPECT_EQ(a.collisions.pedestrian_incidents, b.collisions.pedestrian_incidents);
  // The teaching drive's recording: scans, odometry and the reference at each odometry reading.
  const TeachRecording& rec = teaching.recording;
  EXPECT_GT(rec.scans.size(), 100u);
  EXPECT_EQ(rec.odometry.size(), rec.X_WR.size());
  EXPECT_GT(rec.odometry.size(), rec.scans.size());
}

TEST(SteppedEpisode, MisuseIsRefusedWithOneMessage) {
  const std::shared_ptr<const SteppedTeaching> teaching = TeachForStepping(SmallRequest());
  SteppedEpisode episode(teaching, 1, false);
  const auto key = [](const auto& call) {
    try {
      call();
    } catch (const core::ConfigError& e) {
      return e.key_path();
    }
    return std::string("no error");
  };
  EXPECT_EQ(key([&] { episode.Act(StackOutput{}); }), "step");  // act before observe
  EXPECT_GT(episode.Observe().odometry.size(), 0u);
  EXPECT_EQ(key([&] { episode.Observe(); }), "step");  // observe twice
  EXPECT_EQ(key([&] { episode.Act(std::nullopt); }), "answer");
  StackOutput beyond;
  beyond.map = 7;
  EXPECT_EQ(key([&] { episode.Act(beyond); }), "answer");
  StackOutput nan_estimate;
  nan_estimate.X_MR.x = std::nan("");
  EXPECT_EQ(key([&] { episode.Act(nan_estimate); }), "answer");
  EXPECT_EQ(key([&] { episode.trace(); }), "step");  // not done
  StackOutput forward;
  forward.drive.command = {0.3, 0.0};
  EXPECT_FALSE(episode.Act(forward));
  TeachingRequest all = SmallRequest();
  all.mode = "all";
  EXPECT_EQ(key([&] { TeachForStepping(all); }), "mode");
  EXPECT_EQ(key([&] { SteppedEpisode bad(teaching, -1, false); }), "run");
}

TEST(SteppedEpisode, AStackThatClaimsTheGoalFarFromItIsLostNotSuccessful) {
  // The small route ends where it starts: drive 2 m along it, then claim its end.
  TeachingRequest request = SmallRequest();
  request.overrides = {"limits.lost_distance=0.5"};
  SteppedEpisode episode(TeachForStepping(request), 0, false);
  StackOutput answer;
  answer.map = episode.maps() - 1;
  answer.drive.command = {0.4, 0.0};
  while (episode.Observe().time < 5.0) ASSERT_FALSE(episode.Act(answer));
  answer.route_done = true;
  EXPECT_TRUE(episode.Act(answer));
  const RunTrace& trace = episode.trace();
  EXPECT_GT(
      (trace.samples.back().X_WR.translation() - trace.samples.front().X_WR.translation()).norm(),
      1.0);
  EXPECT_EQ(trace.outcome, Outcome::kLost);
}

}  // namespace
}  // namespace retrace::bench
