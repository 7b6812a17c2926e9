#pragma once
// Loads the video codec plugin (video_codec_api.hpp) once per process, on first use.

#include "viz/video_codec/video_codec_api.hpp"

namespace retrace::viz::internal {

/// The plugin's table. Looked for beside the running program, where `cmake --install` puts it
/// relative to the program (../<libdir>/retrace), and in the build tree it was built in. Throws
/// RenderError naming the places looked in when none loads.
const RetraceVideoCodecApi& VideoCodec();

}  // namespace retrace::viz::internal
