#include "bench/replay/log_config.hpp"

#include "core/errors.hpp"
#include "io/config_yaml.hpp"
#include "sim/world_file.hpp"

namespace retrace::bench {

void LogSimConfig::Validate() const {
  odometry.Validate();
  sim::MapImportConfig map{"map", 0.65, unknown_free_path};
  map.Validate();
}

LogConfig::LogConfig() {
  route.switch_points.word = SwitchPlanning::kOnline;
  // Indoors: no bikes, and a recorded drive passes things closely.
  clutter.kinds = {ClutterKind::kChair, ClutterKind::kBin, ClutterKind::kBox};
  clutter.clearance = 0.1;
}

void LogConfig::Validate() const {
  if (!route.file.empty() || !route.points.empty()) {
    throw core::ConfigError(route.file.empty() ? "route.points" : "route.file",
                            "does not apply to a log: its route is the path it drove");
  }
  const double corridor = ClutterSite{}.robot_radius + clutter.clearance;
  if (!(clutter.band > corridor)) {
    throw core::ConfigError("clutter.band",
                            "must be wider than the corridor kept free along the route, 0.3 m "
                            "(a robot's radius) + clutter.clearance = " +
                                core::FormatNumber(corridor) + " m, not " +
                                core::FormatNumber(clutter.band) + " m");
  }
  const PlaybackConfig defaults;
  if (playback.repeats != defaults.repeats ||
      playback.start_offset_xy != defaults.start_offset_xy ||
      playback.start_offset_yaw_deg != defaults.start_offset_yaw_deg) {
    throw core::ConfigError("playback",
                            "only initial_sigma_xy and initial_sigma_yaw_deg apply to a log: "
                            "repeats and start offsets are the log's own");
  }
  for (std::size_t i = 0; i < modes.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (modes[i] == modes[j]) {
        throw core::ConfigError("modes",
                                "lists '" + std::string(core::EnumName(modes[i])) + "' twice");
      }
    }
  }
}

LogConfig LoadLogConfig(const std::optional<std::filesystem::path>& file,
                        const std::vector<io::ConfigOverride>& overrides) {
  if (file) return io::LoadConfigFile<LogConfig>(*file, overrides);
  YAML::Node root(YAML::NodeType::Map);
  io::ApplyOverrides(root, overrides);
  return io::ReadConfig<LogConfig>(root, "--set", overrides);
}

}  // namespace retrace::bench
