#pragma once
// The video codec's C interface. OpenCV's video module loads FFmpeg, GStreamer and about 240
// shared libraries, which cost every process that links them 0.25 s at start; so the encoder
// lives in a plugin of its own (viz/video_codec/video_codec_plugin.cpp, libretrace_video_codec.so)
// that viz/video.cpp loads the first time a video is written or read. C, so that nothing but
// this table crosses the boundary.

extern "C" {

struct RetraceVideoCodecApi {
  int version;  ///< kRetraceVideoCodecVersion of the plugin's build
  /// Opens `path` for `fourcc` (4 characters) at `fps` and width x height px: a handle, or null
  /// when no encoder opens.
  void* (*open)(const char* path, const char* fourcc, double fps, int width, int height);
  /// Appends a frame of width x height RGB pixels (top row first). Returns 0 on success.
  int (*write_rgb)(void* video, const unsigned char* rgb);
  /// Finishes the file and frees the handle.
  void (*close)(void* video);
  /// The frame count, size and rate of the video at `path`. Returns 0 when it opens.
  int (*probe)(const char* path, int* frames, int* width, int* height, double* fps);
};

/// The plugin's one exported symbol.
const RetraceVideoCodecApi* retrace_video_codec_api();
}

inline constexpr int kRetraceVideoCodecVersion = 1;
inline constexpr const char* kRetraceVideoCodecSymbol = "retrace_video_codec_api";
