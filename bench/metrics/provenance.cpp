#include "bench/metrics/provenance.hpp"

#include <chrono>
#include <ctime>

#include "git_revision.hpp"

namespace retrace::bench {
namespace {

template <class Json>
void Write(const Provenance& p, Json* json) {
  Json& j = *json;
  if (p.command_line) j["command"] = *p.command_line;
  if (p.git_revision) j["git_revision"] = *p.git_revision;
  if (p.build_type) j["build_type"] = *p.build_type;
  if (p.version) j["version"] = *p.version;
  if (p.date) j["date"] = *p.date;
  if (p.wall_time_s) j["wall_time_s"] = *p.wall_time_s;
  if (p.jobs) j["jobs"] = *p.jobs;
  if (p.overrides) j["set"] = *p.overrides;
  if (p.only) j["only"] = *p.only;
}

}  // namespace

void WriteProvenance(const Provenance& provenance, nlohmann::json* json) {
  Write(provenance, json);
}

void WriteProvenance(const Provenance& provenance, nlohmann::ordered_json* json) {
  Write(provenance, json);
}

std::string BuildRevision() { return RETRACE_GIT_REVISION; }

std::string BuildType() { return RETRACE_BUILD_TYPE; }

std::string BuildVersion() { return RETRACE_VERSION; }

std::string UtcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace retrace::bench
