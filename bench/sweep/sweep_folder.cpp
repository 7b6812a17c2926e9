#include "bench/sweep/sweep_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "bench/sweep/sweep_plot.hpp"
#include "core/errors.hpp"
#include "io/json_writer.hpp"

namespace retrace::bench {
namespace {

constexpr const char* kFormat = "retrace sweep 1";

template <class T>
T Field(const nlohmann::json& json, const char* key, const std::filesystem::path& file) {
  if (!json.contains(key)) throw core::IoError(file.string() + ": missing field '" + key + "'");
  try {
    return json.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw core::IoError(file.string() + ": field '" + key + "' has the wrong type");
  }
}

}  // namespace

nlohmann::json SweepJson(const SweepPlan& plan, const SweepShard& shard) {
  const SweepSpec& s = plan.spec;
  nlohmann::json json;
  json["format"] = kFormat;
  json["name"] = s.name;
  json["identity"] = plan.identity;
  json["shard"] = shard.ToString();
  json["sweep_file"] = s.file.string();
  json["scenario_file"] = s.scenario.string();
  json["mode"] = std::string(core::EnumName(s.mode));
  json["repeats"] = s.repeats;
  json["combinations"] = s.combinations.size();
  json["cases"] = s.case_count();
  json["shard_cases"] = shard.CaseCount(s.case_count());
  json["cases_done"] = 0;
  json["complete"] = false;
  json["parameters"] = s.parameters;
  json["labels"] = s.labels;
  json["plot_parameters"] = s.plot_parameters;
  json["metrics"] = s.metrics;
  json["timing_metrics"] = s.timing_metrics;
  return json;
}

SweepRecord ReadSweepRecord(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw core::IoError(file.string() + ": cannot open file");
  SweepRecord r;
  r.json = io::ReadJsonFile(file);
  if (!r.json.is_object() || r.json.value("format", "") != kFormat) {
    throw core::IoError(file.string() + ": not a sweep record (format '" + std::string(kFormat) +
                        "')");
  }
  r.name = Field<std::string>(r.json, "name", file);
  r.identity = Field<std::string>(r.json, "identity", file);
  try {
    r.shard = ParseShard(Field<std::string>(r.json, "shard", file));
  } catch (const core::ConfigError& e) {
    throw core::IoError(file.string() + ": shard: " + e.detail());
  }
  r.cases = Field<std::size_t>(r.json, "cases", file);
  r.cases_done = Field<std::size_t>(r.json, "cases_done", file);
  r.complete = Field<bool>(r.json, "complete", file);
  r.parameters = Field<std::vector<std::string>>(r.json, "parameters", file);
  r.plot_parameters = Field<std::vector<std::string>>(r.json, "plot_parameters", file);
  r.metrics = Field<std::vector<std::string>>(r.json, "metrics", file);
  r.timing_metrics = Field<std::vector<std::string>>(r.json, "timing_metrics", file);
  return r;
}

std::filesystem::path DefaultSweepFolder(const std::string& name, const SweepShard& shard) {
  std::filesystem::path folder = std::filesystem::path("results") / "sweeps" / name;
  if (shard.count > 1)
    folder /= "shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
  return folder;
}

std::string PlotSweepFolder(const std::filesystem::path& folder, const std::string& name,
                            const std::vector<std::string>& parameters,
                            const std::vector<std::string>& metrics) {
  try {
    RenderSweepPlot(folder / "results.csv", parameters, metrics, folder / "sweep.png",
                    "sweep " + name);
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

SweepFolderLock::SweepFolderLock(const std::filesystem::path& folder) {
  fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0)
    throw core::IoError(folder.string() + ": cannot open folder: " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw core::IoError(folder.string() +
                          ": another retrace sweep or merge is writing this folder");
    }
    throw core::IoError(folder.string() + ": cannot lock: " + std::strerror(error));
  }
}

SweepFolderLock::~SweepFolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace retrace::bench
