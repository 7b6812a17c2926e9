#pragma once
// Baselines (results/baselines/<suite>.json, committed): the metric values a suite produced
// when someone decided they were right, with what produced them.
//
//   {
//     "format": "retrace-baseline/1",
//     "suite": "ci",                        // the suite's name: a baseline serves one suite
//     "suite_file": "bench/suites/ci.yaml",
//     "suite_digest": "fnv1a64:…",          // of the suite file's bytes when it was recorded
//     "git_revision": "d310e2d…",           // of the build (`git describe --always --dirty`)
//     "build_type": "Release",
//     "date": "2025-06-01T12:00:00Z",       // UTC
//     "entries": [{"name", "scenario", "modes", "seeds", "repeats", "set"}, …],
//     "metrics": {"small.partial.success_rate": 1, …},  // navigation metrics; null: NaN
//     "timing": {"small.partial.cpu.real_time_factor": 84.2, …}   // cpu.*, for information
//   }
//
// The entries are the suite's definitions when the baseline was recorded: comparing a suite
// whose scenarios, modes, seeds, repeats or `set` changed against it would compare different
// experiments, so that is an error (record a new baseline). Tolerances may change freely.

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "bench/metrics/provenance.hpp"
#include "bench/suite/suite_runner.hpp"
#include "bench/suite/suite_spec.hpp"

namespace retrace::bench {

struct Baseline {
  std::string suite;
  std::string suite_file;
  std::string suite_digest;
  std::string git_revision;
  std::string build_type;
  std::string date;
  nlohmann::json entries = nlohmann::json::array();
  std::map<std::string, double> metrics;  ///< NaN where the file has null
  std::map<std::string, double> timing;

  /// The value of a metric or timing, nullopt when the baseline lacks it.
  std::optional<double> Find(const std::string& name) const;
};

/// The baseline of `results` for `spec`, stamped with this build's revision and the time now.
Baseline MakeBaseline(const SuiteSpec& spec, const SuiteResults& results);

/// Reads a baseline. Throws core::IoError (naming the file) when it is missing, not JSON or
/// not a baseline.
Baseline ReadBaseline(const std::filesystem::path& file);

/// Writes it atomically. Throws core::IoError.
void WriteBaseline(const std::filesystem::path& file, const Baseline& baseline);

/// Throws core::ConfigError naming `file` when the baseline was recorded for another suite or
/// for other entry definitions than `spec`'s.
void CheckBaselineMatches(const Baseline& baseline, const SuiteSpec& spec,
                          const std::filesystem::path& file);

/// An entry's definition as the baseline records it.
nlohmann::json EntryDefinition(const SuiteEntry& entry);

}  // namespace retrace::bench
