#pragma once
// The options several commands share, each declared here once: its name, its check and the
// start of its help; a command adds what the option means for it (`what`). Each returns the
// CLI11 option so that a command can mark it required or show its default.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace retrace::bench {

/// --set key=value (repeatable): "Override <what> (repeatable)".
CLI::Option* AddSetOption(CLI::App* cmd, std::vector<std::string>* overrides,
                          const std::string& what = "a scenario key: a.b.c=value");
/// --seed N (0 .. 2^63 - 1): "Seed <what>".
CLI::Option* AddSeedOption(CLI::App* cmd, std::uint64_t* seed, const std::string& what);
CLI::Option* AddSeedOption(CLI::App* cmd, std::optional<std::uint64_t>* seed,
                           const std::string& what);
/// --jobs N (>= 0; 0: one per core).
CLI::Option* AddJobsOption(CLI::App* cmd, int* jobs, const std::string& what = "Worker threads");
/// --out (-o) PATH: `help` says what is written there.
CLI::Option* AddOutOption(CLI::App* cmd, std::filesystem::path* out, const std::string& help);
/// --config FILE: `help` says what the settings file holds.
CLI::Option* AddConfigOption(CLI::App* cmd, std::optional<std::filesystem::path>* config,
                             const std::string& help);
CLI::Option* AddConfigOption(CLI::App* cmd, std::filesystem::path* config, const std::string& help);
/// --no-figures: clears *figures.
CLI::Option* AddNoFiguresFlag(CLI::App* cmd, bool* figures,
                              const std::string& help = "Do not render the figures");
/// --no-report: clears *report.
CLI::Option* AddNoReportFlag(CLI::App* cmd, bool* report, const std::string& help);

}  // namespace retrace::bench
