#include "bench/output/video_recorder.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "viz/render_error.hpp"
#include "viz/video.hpp"

namespace retrace::bench {

class VideoRecorder::Impl {
 public:
  Impl(const std::filesystem::path& path, std::string caption, double robot_radius,
       const VideoOptions& o)
      : options_(o),
        caption_(std::move(caption)),
        robot_radius_(robot_radius),
        renderer_(viz::VideoFrameOptions{o.width, o.height, o.pixels_per_meter, 1}),
        writer_(path, o.width, o.height, o.fps) {
    if (!(o.speedup > 0.0) || !std::isfinite(o.speedup)) {
      throw viz::RenderError("video speed-up must be positive, got " + std::to_string(o.speedup));
    }
    period_ = o.speedup / o.fps;
  }

  void OnTick(const PlaybackMoment& m) {
    // Frame k shows the moment k * period: the first tick at or after it.
    if (m.time + 1e-9 < next_frame_time_) return;
    next_frame_time_ = (std::floor(m.time / period_ + 1e-9) + 1.0) * period_;
    writer_.Write(renderer_.Render(Frame(m)));
  }

  void OnEnd() { writer_.Close(); }
  const std::filesystem::path& path() const { return writer_.path(); }
  int frames() const { return writer_.frames(); }

 private:
  viz::VideoFrame Frame(const PlaybackMoment& m) {
    const std::size_t index = m.server.index();
    if (!map_ || index != map_index_) {
      // The map and path change only at a switch: copied once per map, shared by every frame.
      const nav::PartialMap& current = m.server.current();
      map_ = std::make_shared<const core::OccupancyGrid>(current.grid);
      path_ = std::make_shared<const std::vector<core::Pose2>>(current.path.poses());
      map_index_ = index;
    }
    viz::VideoFrame f;
    f.time_s = m.time;
    f.speed = m.speed;
    f.map_index = static_cast<int>(index);
    f.map_count = static_cast<int>(m.server.bundle().maps.size());
    f.map = map_;
    f.path = path_;
    f.estimate = m.localizer.Estimate();
    f.truth = m.X_MR_truth;
    f.robot_radius = robot_radius_;
    f.time_since_switch = m.time_since_switch;
    f.caption = caption_;
    for (const nav::Particle& p : m.localizer.particles()) {
      f.particles.push_back(p.X_MR);
      f.weights.push_back(p.weight);
    }
    // Where the world is in this map according to the local truth: pedestrians drawn there.
    const core::Pose2 X_MW = m.X_MR_truth * m.X_WR.Inverse();
    for (const sim::DynamicCircle& c : m.pedestrians_W)
      f.pedestrians.push_back({X_MW * c.center, c.radius});
    // The scan where the robot believes it is: as the localizer sees it.
    if (m.lidar != nullptr) {
      const core::LaserScan& scan = m.lidar->scan;
      const core::Pose2 X_ML = f.estimate * m.localizer.robot().X_RL;
      const bool labelled = m.update != nullptr && m.update->beams.size() == scan.ranges.size();
      for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
        const double r = scan.ranges[i];
        if (!std::isfinite(r)) continue;
        const double a = scan.Angle(i);
        viz::ScanPoint p;
        p.point = X_ML * core::Vec2(r * std::cos(a), r * std::sin(a));
        p.rejected = labelled && m.update->beams[i] == nav::BeamUse::kRejected;
        p.hits_pedestrian = m.lidar->truth[i].source == sim::BeamSource::kPedestrian;
        f.scan.push_back(p);
      }
    }
    return f;
  }

  VideoOptions options_;
  std::string caption_;
  double robot_radius_;
  viz::VideoFrameRenderer renderer_;
  viz::VideoWriter writer_;
  double period_ = 1.0;
  double next_frame_time_ = -std::numeric_limits<double>::infinity();
  std::shared_ptr<const core::OccupancyGrid> map_;
  std::shared_ptr<const std::vector<core::Pose2>> path_;
  std::size_t map_index_ = 0;
};

VideoRecorder::VideoRecorder(const std::filesystem::path& path, std::string caption,
                             double robot_radius, const VideoOptions& options)
    : impl_(std::make_unique<Impl>(path, std::move(caption), robot_radius, options)) {}
VideoRecorder::~VideoRecorder() = default;
void VideoRecorder::OnTick(const PlaybackMoment& moment) { impl_->OnTick(moment); }
void VideoRecorder::OnEnd() { impl_->OnEnd(); }
const std::filesystem::path& VideoRecorder::path() const { return impl_->path(); }
int VideoRecorder::frames() const { return impl_->frames(); }

}  // namespace retrace::bench
