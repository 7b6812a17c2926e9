#pragma once
// Where a results file's numbers come from: the build (git revision, build type, version), when
// (date), the command line and how it ran (wall time, jobs, --set, --only). One struct, written
// into JSON by one function, for every results file that records it: comparison.json
// (`retrace compare`), report.json and the baseline of a suite (`retrace bench`), sweep.json
// (`retrace sweep`, `retrace merge`).
//
// The keys, in this order (a field not set is not written): "command", "git_revision",
// "build_type", "version", "date", "wall_time_s", "jobs", "set", "only".

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace retrace::bench {

struct Provenance {
  std::optional<std::string> command_line;            ///< "command"
  std::optional<std::string> git_revision;            ///< "git_revision" (BuildRevision())
  std::optional<std::string> build_type;              ///< "build_type" ("Release", ...)
  std::optional<std::string> version;                 ///< "version" (BuildVersion())
  std::optional<std::string> date;                    ///< "date", UTC, ISO 8601 (UtcNow())
  std::optional<double> wall_time_s;                  ///< "wall_time_s"
  std::optional<int> jobs;                            ///< "jobs"
  std::optional<std::vector<std::string>> overrides;  ///< "set": --set of the command line
  std::optional<std::vector<std::string>> only;       ///< "only": --only of the command line
};

/// Sets the provenance's fields in `json` (an object), in the order above.
void WriteProvenance(const Provenance& provenance, nlohmann::json* json);
void WriteProvenance(const Provenance& provenance, nlohmann::ordered_json* json);

/// The git revision this program was built from (see cmake/git_revision.cmake).
std::string BuildRevision();

/// The build type this program was built as ("Release", "Debug", ...).
std::string BuildType();

/// retrace's version, the project's in the top-level CMakeLists.txt ("0.1.0").
std::string BuildVersion();

/// The time now, UTC, ISO 8601 ("2025-06-01T12:00:00Z").
std::string UtcNow();

}  // namespace retrace::bench
