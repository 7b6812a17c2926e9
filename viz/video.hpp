#pragma once
// Videos of playback runs: frames rendered from above, following the robot (map, taught path,
// scan, particles, pedestrians, estimate vs truth, map switches, time and speed), encoded with
// OpenCV's video writer, loaded as a plugin on first use (viz/video_codec/).

#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "viz/figure_data.hpp"
#include "viz/image.hpp"

namespace retrace::viz {

/// One moment of a playback run, everything in the frame M of the current map.
struct VideoFrame {
  double time_s = 0.0;
  double speed = 0.0;  ///< m/s, of the robot (ground truth or command: the caller's choice)
  int map_index = 0;
  int map_count = 1;
  std::shared_ptr<const core::OccupancyGrid>
      map;  ///< current map in M (shared: not copied per frame)
  std::shared_ptr<const std::vector<core::Pose2>> path;  ///< taught path of this map in M
  core::Pose2 estimate;                                  ///< X_MR
  core::Pose2 truth;                                     ///< local ground truth X_MR
  std::vector<core::Pose2> particles;
  std::vector<double> weights;      ///< one per particle or empty
  std::vector<ScanPoint> scan;      ///< end points in M
  std::vector<Circle> pedestrians;  ///< in M
  double robot_radius = 0.0;        ///< m, the robot's
  /// s since the last map switch; a banner shows for 3 s after one.
  double time_since_switch = std::numeric_limits<double>::infinity();
  std::string caption;  ///< e.g. "partial maps, run 2"
};

struct VideoFrameOptions {
  int width = 1280;                ///< px, even (video codecs want even sizes)
  int height = 720;                ///< px, even
  double pixels_per_meter = 24.0;  ///< zoom: 0.1 m cells are 2.4 px
  int supersample = 1;             ///< 1..4; 2 looks smoother but costs about 3x per frame
};

/// Renders frames with one canvas kept between frames (a context per frame would cost more
/// than the drawing). North up, centred on the estimate.
class VideoFrameRenderer {
 public:
  /// Throws RenderError for an odd or non-positive size or when no OpenGL context can be made.
  explicit VideoFrameRenderer(const VideoFrameOptions& options = {});
  ~VideoFrameRenderer();
  VideoFrameRenderer(VideoFrameRenderer&&) noexcept;
  VideoFrameRenderer& operator=(VideoFrameRenderer&&) noexcept;

  Image Render(const VideoFrame& frame);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// One frame with a temporary renderer (convenient; a VideoFrameRenderer is faster for many).
Image RenderVideoFrame(const VideoFrame& frame, const VideoFrameOptions& options = {});

/// Encodes frames into a video file. The frames go to a temporary file beside the target,
/// renamed over it by Close(), so a reader never sees a half-written video.
class VideoWriter {
 public:
  /// Opens a video of width x height px (even) at `fps`. Codecs tried in order: H.264 ("avc1")
  /// and MPEG-4 part 2 ("mp4v") in an .mp4 container, then Motion JPEG ("MJPG") in .avi; with
  /// MJPG the file name's extension becomes .avi (see path()). Throws RenderError for a bad
  /// size or fps, when the codec plugin does not load or when no codec opens, core::IoError
  /// when the folder cannot be created.
  VideoWriter(const std::filesystem::path& path, int width, int height, double fps);
  /// Without Close(): removes the temporary file, leaving the target untouched.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends a frame; throws RenderError if its size differs from the video's or after Close().
  void Write(const Image& frame);
  /// Finishes the file and renames it into place; throws core::IoError on failure. Call once.
  void Close();

  /// The codec in use: "avc1", "mp4v" or "MJPG".
  const std::string& codec() const { return codec_; }
  /// The file written by Close() (its extension follows the codec).
  const std::filesystem::path& path() const { return path_; }
  int frames() const { return frames_; }

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::string codec_;
  int width_ = 0;
  int height_ = 0;
  int frames_ = 0;
};

/// What a video file holds, as OpenCV reads it back.
struct VideoInfo {
  int frames = 0;
  int width = 0;
  int height = 0;
  double fps = 0.0;
};

/// Reads a video's properties. Throws core::IoError if it cannot be opened.
VideoInfo ProbeVideo(const std::filesystem::path& path);

}  // namespace retrace::viz
