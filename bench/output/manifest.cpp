#include "bench/output/manifest.hpp"

#include <yaml-cpp/yaml.h>

#include "git_revision.hpp"
#include "io/atomic_file.hpp"
#include "io/config_yaml.hpp"

namespace retrace::bench {

namespace {

// What built the program: revision, build type, compiler, library versions.
void EmitBuild(YAML::Emitter& out) {
  out << YAML::Key << "git_revision" << YAML::Value << RETRACE_GIT_REVISION;
  out << YAML::Key << "build_type" << YAML::Value << RETRACE_BUILD_TYPE;
  out << YAML::Key << "compiler" << YAML::Value << __VERSION__;
  out << YAML::Key << "libraries" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "box2d" << YAML::Value << RETRACE_BOX2D_VERSION;
  out << YAML::Key << "eigen" << YAML::Value << RETRACE_EIGEN_VERSION;
  out << YAML::Key << "opencv" << YAML::Value << RETRACE_OPENCV_VERSION;
  out << YAML::Key << "yaml-cpp" << YAML::Value << RETRACE_YAML_CPP_VERSION;
  out << YAML::Key << "nlohmann_json" << YAML::Value << RETRACE_JSON_VERSION;
  out << YAML::EndMap;
}

}  // namespace

std::string ManifestYaml(const Scenario& scenario, const ManifestInfo& info) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "retrace" << YAML::Value << "0.1.0";
  out << YAML::Key << "command" << YAML::Value << info.command_line;
  out << YAML::Key << "scenario_file" << YAML::Value << scenario.source.string();
  out << YAML::Key << "mode" << YAML::Value << std::string(core::EnumName(info.mode));
  out << YAML::Key << "seed" << YAML::Value << scenario.config.seed;
  if (!info.teach_dir.empty())
    out << YAML::Key << "teach_dir" << YAML::Value << info.teach_dir.string();
  EmitBuild(out);
  out << YAML::Key << "wall_time_s" << YAML::Value << info.wall_time_s;
  out << YAML::Key << "warnings" << YAML::Value << scenario.warnings;
  // route.switch_points: auto, resolved at load: config below holds the points it chose.
  out << YAML::Key << "switch_points_auto" << YAML::Value << scenario.switch_points_auto;
  out << YAML::Key << "config" << YAML::Value << YAML::Load(io::ConfigToYaml(scenario.config));
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void WriteManifest(const std::filesystem::path& path, const Scenario& scenario,
                   const ManifestInfo& info) {
  io::WriteFileAtomic(path, ManifestYaml(scenario, info));
}

std::string LogManifestYaml(const LogManifestInfo& info) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "retrace" << YAML::Value << "0.1.0";
  out << YAML::Key << "command" << YAML::Value << info.command_line;
  for (const auto& [key, value] : info.fields) out << YAML::Key << key << YAML::Value << value;
  EmitBuild(out);
  out << YAML::Key << "wall_time_s" << YAML::Value << info.wall_time_s;
  out << YAML::Key << "notes" << YAML::Value << info.notes;
  out << YAML::Key << "config" << YAML::Value << YAML::Load(info.config_yaml);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace retrace::bench
