#include "viz/video.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/viz/viz_test_data.hpp"
#include "viz/render_error.hpp"

namespace retrace::viz {
namespace {

using VideoTest = retrace::testing::TempDirTest;
using testing::ColorNear;

VideoFrame SmallFrame(int i) {
  VideoFrame f;
  f.robot_radius = 0.3;
  f.time_s = 10.0 + 0.1 * i;
  f.speed = 0.8;
  f.map_index = 1;
  f.map_count = 3;
  f.map = std::make_shared<const core::OccupancyGrid>(testing::SmallGrid());
  f.path =
      std::make_shared<const std::vector<core::Pose2>>(testing::Densify({{0, 0}, {14, 0}}, 0.5));
  f.truth = core::Pose2(2.0 + 0.08 * i, 0.0, 0.0);
  f.estimate = f.truth * core::Pose2(0.05, 0.02, 0.01);
  f.particles = {f.estimate, f.estimate * core::Pose2(0.1, 0.0, 0.0)};
  f.scan = {{Vec2(4.0, 8.05), false, false}, {Vec2(5.0, 3.0), true, true}};
  f.pedestrians = {{Vec2(5.2, 3.0), 0.3}};
  f.time_since_switch = 0.1 * i;
  f.caption = "test run";
  return f;
}

TEST(VideoFrame, FollowsTheEstimateAndShowsTheMap) {
  VideoFrameOptions o;
  o.width = 640;
  o.height = 480;
  o.pixels_per_meter = 20.0;
  const VideoFrame f = SmallFrame(0);
  const Image img = RenderVideoFrame(f, o);
  ASSERT_EQ(img.width, 640);
  ASSERT_EQ(img.height, 480);
  EXPECT_GT(testing::DistinctColors(img), 20u);
  // Centred on the estimate (its arrow at the centre), free space below the robot, the
  // rejected scan point where it is.
  const View v = View::Centered(f.estimate.translation(), 20.0, 640, 480);
  auto at = [&](const Vec2& p) {
    const Vec2 q = v.ToPixel(p);
    return img.At(static_cast<int>(q.x()), static_cast<int>(q.y()));
  };
  EXPECT_TRUE(ColorNear(at(f.estimate * Vec2(0.2, 0.0)), palette::kEstimate, 60));
  EXPECT_TRUE(ColorNear(at(Vec2(4.0, -2.0)), palette::kMapFree, 6));
  EXPECT_TRUE(ColorNear(at(Vec2(-3.0, -2.0)), palette::kMapUnknown, 6));  // off the map
  EXPECT_TRUE(ColorNear(at(Vec2(5.0, 3.0)), palette::kRejectedPoint, 60));
}

TEST(VideoFrame, OddSizesAreRefused) {
  VideoFrameOptions o;
  o.width = 321;
  EXPECT_THROW(VideoFrameRenderer{o}, RenderError);
}

TEST_F(VideoTest, WritesAPlayableFileWithEveryFrame) {
  VideoFrameOptions o;
  o.width = 320;
  o.height = 240;
  VideoFrameRenderer renderer(o);
  VideoWriter writer(tmp_.path() / "videos" / "run0.mp4", 320, 240, 10.0);
  for (int i = 0; i < 12; ++i) writer.Write(renderer.Render(SmallFrame(i)));
  EXPECT_EQ(writer.frames(), 12);
  writer.Close();
  ASSERT_TRUE(std::filesystem::exists(writer.path())) << writer.path();
  EXPECT_GT(std::filesystem::file_size(writer.path()), 1000u);
  EXPECT_TRUE(writer.codec() == "avc1" || writer.codec() == "mp4v" || writer.codec() == "MJPG");
  const VideoInfo info = ProbeVideo(writer.path());
  EXPECT_EQ(info.frames, 12);
  EXPECT_EQ(info.width, 320);
  EXPECT_EQ(info.height, 240);
  EXPECT_NEAR(info.fps, 10.0, 0.01);
  // Only the finished file is left.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(tmp_.path() / "videos")) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST_F(VideoTest, UnfinishedVideoLeavesNothingBehind) {
  {
    VideoWriter writer(tmp_.path() / "run.mp4", 64, 48, 5.0);
    writer.Write(Image(64, 48, {1, 2, 3}));
    EXPECT_THROW(writer.Write(Image(62, 48)), RenderError);
  }
  EXPECT_TRUE(std::filesystem::is_empty(tmp_.path()));
}

TEST_F(VideoTest, BadArgumentsAndPathsAreTypedErrors) {
  EXPECT_THROW(VideoWriter(tmp_.path() / "a.mp4", 63, 48, 5.0), RenderError);
  EXPECT_THROW(VideoWriter(tmp_.path() / "a.mp4", 64, 48, 0.0), RenderError);
  tmp_.Write("file", "x");
  EXPECT_THROW(VideoWriter(tmp_.path() / "file" / "a.mp4", 64, 48, 5.0), core::Error);
  EXPECT_THROW(ProbeVideo(tmp_.path() / "missing.mp4"), core::IoError);
}

}  // namespace
}  // namespace retrace::viz
