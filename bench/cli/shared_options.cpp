#include "bench/cli/shared_options.hpp"

#include <CLI/CLI.hpp>

#include "bench/cli/cli_checks.hpp"

namespace retrace::bench {

CLI::Option* AddSetOption(CLI::App* cmd, std::vector<std::string>* overrides,
                          const std::string& what) {
  return cmd->add_option("--set", *overrides, "Override " + what + " (repeatable)");
}

CLI::Option* AddSeedOption(CLI::App* cmd, std::uint64_t* seed, const std::string& what) {
  return cmd->add_option("--seed", *seed, "Seed " + what)->check(kSeed);
}

CLI::Option* AddSeedOption(CLI::App* cmd, std::optional<std::uint64_t>* seed,
                           const std::string& what) {
  return cmd->add_option("--seed", *seed, "Seed " + what)->check(kSeed);
}

CLI::Option* AddJobsOption(CLI::App* cmd, int* jobs, const std::string& what) {
  return cmd->add_option("--jobs", *jobs, what + " (default: one per core)")->check(kNonNegative);
}

CLI::Option* AddOutOption(CLI::App* cmd, std::filesystem::path* out, const std::string& help) {
  return cmd->add_option("--out,-o", *out, help);
}

CLI::Option* AddConfigOption(CLI::App* cmd, std::optional<std::filesystem::path>* config,
                             const std::string& help) {
  return cmd->add_option("--config", *config, help);
}

CLI::Option* AddConfigOption(CLI::App* cmd, std::filesystem::path* config,
                             const std::string& help) {
  return cmd->add_option("--config", *config, help);
}

CLI::Option* AddNoFiguresFlag(CLI::App* cmd, bool* figures, const std::string& help) {
  return cmd->add_flag("!--no-figures", *figures, help);
}

CLI::Option* AddNoReportFlag(CLI::App* cmd, bool* report, const std::string& help) {
  return cmd->add_flag("!--no-report", *report, help);
}

}  // namespace retrace::bench
