// libretrace_video_codec.so: OpenCV's video writer and reader behind the C table of
// video_codec_api.hpp, for viz/video.cpp to load when a video is wanted.

#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <vector>

#include "viz/video_codec/video_codec_api.hpp"

namespace {

struct Video {
  cv::VideoWriter writer;
  cv::Mat bgr;
};

// No exception may cross the C table: every entry point catches all (OpenCV's, bad_alloc) and
// answers with its failure value.
void* Open(const char* path, const char* fourcc, double fps, int width, int height) noexcept {
  try {
    auto video = std::make_unique<Video>();
    const int code = cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]);
    const cv::Size size(width, height);
    // FFmpeg first: it reads back what it writes; another backend only if FFmpeg cannot.
    if (!video->writer.open(path, cv::CAP_FFMPEG, code, fps, size) &&
        !video->writer.open(path, code, fps, size)) {
      return nullptr;
    }
    video->bgr.create(height, width, CV_8UC3);
    return video.release();
  } catch (...) {
    return nullptr;
  }
}

int WriteRgb(void* handle, const unsigned char* rgb) noexcept {
  auto* video = static_cast<Video*>(handle);
  const std::size_t pixels = video->bgr.total();
  unsigned char* bgr = video->bgr.ptr<unsigned char>();
  for (std::size_t i = 0; i < pixels; ++i) {
    bgr[3 * i] = rgb[3 * i + 2];
    bgr[3 * i + 1] = rgb[3 * i + 1];
    bgr[3 * i + 2] = rgb[3 * i];
  }
  try {
    video->writer.write(video->bgr);
  } catch (...) {
    return 1;
  }
  return 0;
}

void Close(void* handle) noexcept {
  auto* video = static_cast<Video*>(handle);
  try {
    video->writer.release();
  } catch (...) {  // the caller checks the file
  }
  delete video;
}

int Probe(const char* path, int* frames, int* width, int* height, double* fps) noexcept {
  try {
    // FFmpeg only: it reads what the writer writes, and other backends would probe cameras.
    cv::VideoCapture capture(path, cv::CAP_FFMPEG);
    if (!capture.isOpened()) return 1;
    *frames = static_cast<int>(std::lround(capture.get(cv::CAP_PROP_FRAME_COUNT)));
    *width = static_cast<int>(capture.get(cv::CAP_PROP_FRAME_WIDTH));
    *height = static_cast<int>(capture.get(cv::CAP_PROP_FRAME_HEIGHT));
    *fps = capture.get(cv::CAP_PROP_FPS);
    return 0;
  } catch (...) {
    return 1;
  }
}

constexpr RetraceVideoCodecApi kApi{kRetraceVideoCodecVersion, Open, WriteRgb, Close, Probe};

}  // namespace

extern "C" __attribute__((visibility("default"))) const RetraceVideoCodecApi*
retrace_video_codec_api() {
  return &kApi;
}
