#include "viz/video_codec/video_codec_loader.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <vector>

#include "viz/render_error.hpp"

namespace retrace::viz::internal {
namespace {

constexpr const char* kPluginFile = "libretrace_video_codec.so";

std::vector<std::filesystem::path> Candidates() {
  std::vector<std::filesystem::path> places;
  std::error_code ec;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    places.push_back(program.parent_path() / kPluginFile);
    places.push_back(program.parent_path() / RETRACE_VIDEO_CODEC_INSTALL_RELATIVE / kPluginFile);
  }
  const std::filesystem::path built =
      std::filesystem::path(RETRACE_VIDEO_CODEC_BUILD_DIR) / kPluginFile;
  if (places.empty() || places.front() != built) places.push_back(built);
  for (std::filesystem::path& place : places) place = place.lexically_normal();
  return places;
}

const RetraceVideoCodecApi* Load(std::string& failures) {
  for (const std::filesystem::path& place : Candidates()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(place, ec)) {
      failures += "\n  " + place.string() + ": not there";
      continue;
    }
    void* handle = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      failures += "\n  " + place.string() + ": " + dlerror();
      continue;
    }
    using Entry = const RetraceVideoCodecApi* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, kRetraceVideoCodecSymbol));
    const RetraceVideoCodecApi* api = entry != nullptr ? entry() : nullptr;
    if (api != nullptr && api->version == kRetraceVideoCodecVersion) return api;  // kept loaded
    failures += "\n  " + place.string() + ": not this build's video codec";
    dlclose(handle);
  }
  return nullptr;
}

}  // namespace

const RetraceVideoCodecApi& VideoCodec() {
  static std::string failures;
  static const RetraceVideoCodecApi* const api = Load(failures);
  if (api == nullptr) {
    throw RenderError(std::string("videos need the plugin ") + kPluginFile +
                      " (built and installed with retrace), which did not load:" + failures);
  }
  return *api;
}

}  // namespace retrace::viz::internal
