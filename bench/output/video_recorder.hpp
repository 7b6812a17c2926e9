#pragma once
// `retrace run --video`: a video of one playback run, from above and following the robot,
// rendered while the run drives (viz::VideoFrameRenderer) and encoded as it goes, so that no
// frames are kept in memory.

#include <filesystem>
#include <memory>
#include <string>

#include "bench/engine/playback_observer.hpp"

namespace retrace::bench {

struct VideoOptions {
  double speedup = 10.0;  ///< seconds of the run per second of video
  double fps = 30.0;      ///< frames per second of video
  int width = 1280;       ///< px, even
  int height = 720;       ///< px, even
  double pixels_per_meter = 24.0;
};

class VideoRecorder final : public PlaybackObserver {
 public:
  /// Opens the video at `path` (its extension may change with the codec: see
  /// viz::VideoWriter). `caption` is shown in every frame, e.g. "partial maps, run 0". Throws
  /// viz::RenderError when no OpenGL context or encoder is available.
  VideoRecorder(const std::filesystem::path& path, std::string caption, double robot_radius,
                const VideoOptions& options = {});
  ~VideoRecorder() override;

  void OnTick(const PlaybackMoment& moment) override;
  /// Finishes the file and moves it into place.
  void OnEnd() override;

  /// The file written (after OnEnd) and its frame count.
  const std::filesystem::path& path() const;
  int frames() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace retrace::bench
