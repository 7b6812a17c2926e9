#include "viz/video.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <system_error>

#include "core/errors.hpp"
#include "viz/gl_canvas.hpp"
#include "viz/internal/annotate.hpp"
#include "viz/internal/cv_image.hpp"
#include "viz/internal/snapshot_layers.hpp"
#include "viz/render_error.hpp"
#include "viz/video_codec/video_codec_loader.hpp"

namespace retrace::viz {
namespace {

void CheckEvenSize(int width, int height) {
  if (width <= 0 || height <= 0 || width % 2 != 0 || height % 2 != 0) {
    throw RenderError("video frames must have a positive even size, got " + std::to_string(width) +
                      " x " + std::to_string(height) + " px");
  }
}

// A translucent white box behind overlay text.
void Backdrop(cv::Mat& img, cv::Rect r, double opacity = 0.8) {
  r &= cv::Rect(0, 0, img.cols, img.rows);
  if (r.area() == 0) return;
  cv::Mat roi = img(r);
  cv::Mat white(roi.size(), roi.type(), internal::ToScalar(palette::kBackground));
  cv::addWeighted(white, opacity, roi, 1.0 - opacity, 0.0, roi);
}

constexpr double kSwitchBannerTime = 3.0;  // s

// A frame's localization layers (references into `f`; no map or path: empty ones).
internal::LocalizationLayers LayersOf(const VideoFrame& f) {
  static const core::OccupancyGrid kNoMap;
  static const std::vector<core::Pose2> kNoPath;
  return {.grid = f.map ? *f.map : kNoMap,
          .path = f.path ? *f.path : kNoPath,
          .particles = f.particles,
          .weights = f.weights,
          .estimate = f.estimate,
          .truth = f.truth,
          .scan = f.scan,
          .pedestrians = f.pedestrians,
          .robot_radius = f.robot_radius};
}

}  // namespace

class VideoFrameRenderer::Impl {
 public:
  explicit Impl(const VideoFrameOptions& o)
      : options_(o),
        canvas_((CheckEvenSize(o.width, o.height), o.width), o.height, o.supersample) {}

  Image Render(const VideoFrame& f) {
    const VideoFrameOptions& o = options_;
    canvas_.Clear(palette::kMapUnknown);
    canvas_.SetView(
        View::Centered(f.estimate.translation(), o.pixels_per_meter, o.width, o.height));
    internal::DrawLocalizationLayers(canvas_, LayersOf(f), 1.0);
    cv::Mat img = internal::ToMat(canvas_.ReadBack());

    // Status box, top left.
    char line[160];
    std::snprintf(line, sizeof(line), "t = %.1f s   v = %.2f m/s   map %d (of maps 0-%d)", f.time_s,
                  f.speed, f.map_index, std::max(1, f.map_count) - 1);
    char err[96];
    std::snprintf(err, sizeof(err), "estimate vs truth: %.2f m",
                  core::Distance(f.estimate, f.truth));
    std::vector<std::string> lines;
    if (!f.caption.empty()) lines.push_back(f.caption);
    lines.push_back(line);
    lines.push_back(err);
    int box_w = 0;
    int line_h = 0;
    for (const auto& s : lines) {
      const cv::Size e = internal::TextExtent(s, internal::kLabelText);
      box_w = std::max(box_w, e.width);
      line_h = std::max(line_h, e.height);
    }
    Backdrop(img, cv::Rect(8, 8, box_w + 20, static_cast<int>(lines.size()) * (line_h + 8) + 12));
    for (std::size_t i = 0; i < lines.size(); ++i) {
      internal::PutText(img, lines[i], cv::Point(18, 16 + static_cast<int>(i) * (line_h + 8)),
                        internal::Align::kLeft, internal::VAlign::kTop, internal::kLabelText);
    }

    if (f.time_since_switch >= 0.0 && f.time_since_switch < kSwitchBannerTime) {
      const std::string banner = "map switch: now in map " + std::to_string(f.map_index);
      internal::PutLabel(img, banner, cv::Point(img.cols / 2, 16), internal::Align::kCenter,
                         internal::VAlign::kTop, internal::kPanelTitleText, palette::kSwitch, 8);
    }

    // Legend strip at the bottom, scale bar above it; a frame too small for the legend to
    // leave most of the view free goes without it.
    const auto legend = internal::LocalizationLegend();
    int legend_h = internal::LegendHeight(legend, img.cols);
    if (legend_h > img.rows / 5) {
      legend_h = 0;
    } else {
      const cv::Rect strip(0, img.rows - legend_h, img.cols, legend_h);
      Backdrop(img, strip, 0.85);
      internal::DrawLegend(img, legend, strip);
    }
    internal::DrawScaleBar(img, cv::Rect(0, 0, img.cols, img.rows - legend_h), canvas_.view());
    return internal::FromMat(img);
  }

 private:
  VideoFrameOptions options_;
  GlCanvas canvas_;
};

VideoFrameRenderer::VideoFrameRenderer(const VideoFrameOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}
VideoFrameRenderer::~VideoFrameRenderer() = default;
VideoFrameRenderer::VideoFrameRenderer(VideoFrameRenderer&&) noexcept = default;
VideoFrameRenderer& VideoFrameRenderer::operator=(VideoFrameRenderer&&) noexcept = default;

Image VideoFrameRenderer::Render(const VideoFrame& frame) { return impl_->Render(frame); }

Image RenderVideoFrame(const VideoFrame& frame, const VideoFrameOptions& options) {
  return VideoFrameRenderer(options).Render(frame);
}

class VideoWriter::Impl {
 public:
  const RetraceVideoCodecApi& codec = internal::VideoCodec();
  void* video = nullptr;  // open between the constructor and Close()

  void Release() {
    codec.close(video);
    video = nullptr;
  }
};

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, double fps)
    : width_(width), height_(height) {
  CheckEvenSize(width, height);
  if (!(fps > 0.0) || !std::isfinite(fps)) {
    throw RenderError("video frame rate must be positive, got " + std::to_string(fps));
  }
  impl_ = std::make_unique<Impl>();
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  if (ec)
    throw core::IoError(path.parent_path().string() + ": cannot create folder: " + ec.message());
  struct Choice {
    const char* fourcc;
    const char* ext;
  };
  // H.264 plays everywhere (browsers included); mp4v and MJPG are fallbacks for OpenCV builds
  // without an H.264 encoder.
  for (const Choice c : {Choice{"avc1", ".mp4"}, Choice{"mp4v", ".mp4"}, Choice{"MJPG", ".avi"}}) {
    std::filesystem::path target = path;
    target.replace_extension(c.ext);
    std::filesystem::path temp = target;
    temp.replace_filename(target.stem().string() + ".partial" + c.ext);
    impl_->video = impl_->codec.open(temp.c_str(), c.fourcc, fps, width, height);
    if (impl_->video != nullptr) {
      path_ = target;
      temp_ = temp;
      codec_ = c.fourcc;
      return;
    }
    std::filesystem::remove(temp, ec);
  }
  throw RenderError(path.string() + ": OpenCV has no video encoder for avc1, mp4v or MJPG");
}

VideoWriter::~VideoWriter() {
  if (impl_ && impl_->video != nullptr) {
    impl_->Release();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void VideoWriter::Write(const Image& frame) {
  if (impl_->video == nullptr) throw RenderError(path_.string() + ": video already closed");
  if (frame.width != width_ || frame.height != height_) {
    throw RenderError(path_.string() + ": frame of " + std::to_string(frame.width) + " x " +
                      std::to_string(frame.height) + " px in a video of " + std::to_string(width_) +
                      " x " + std::to_string(height_) + " px");
  }
  if (impl_->codec.write_rgb(impl_->video, frame.rgb.data()) != 0) {
    throw RenderError(path_.string() + ": the video encoder refused a frame");
  }
  ++frames_;
}

void VideoWriter::Close() {
  if (impl_->video == nullptr) throw RenderError(path_.string() + ": video already closed");
  impl_->Release();
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec) {
    std::filesystem::remove(temp_, ec);
    throw core::IoError(path_.string() + ": cannot move the finished video into place");
  }
}

VideoInfo ProbeVideo(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw core::IoError(path.string() + ": no such video");
  VideoInfo info;
  if (internal::VideoCodec().probe(path.c_str(), &info.frames, &info.width, &info.height,
                                   &info.fps) != 0) {
    throw core::IoError(path.string() + ": cannot open video");
  }
  return info;
}

}  // namespace retrace::viz
