// The `retrace` command line (bench/cli/command_line.hpp).

#include <CLI/CLI.hpp>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/cli/command_line.hpp"
#include "bench/cli/commands.hpp"
#include "bench/suite/baseline.hpp"
#include "core/errors.hpp"

namespace {

namespace bench = retrace::bench;
namespace core = retrace::core;

constexpr int kExitBadInput = 2;
constexpr int kExitInternalError = 3;  // a bug in retrace, never bad input

std::string CommandLine(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

// Parses the command line; an exit code when it asked for help or the version, or was bad.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "retrace: error: " << e.what() << " (see retrace --help)\n";
    return kExitBadInput;
  }
  return std::nullopt;
}

// Runs a subcommand; bad input is one line on stderr and exit code 2.
int RunReportingErrors(const bench::CommandRunner& run, const std::string& command_line) {
  try {
    return run(command_line);
  } catch (const core::Error& e) {
    std::cerr << "retrace: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "retrace: error: " << e.what()
              << "\n";  // e.g. an output folder that cannot be written
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "retrace: internal error: " << e.what() << "\n";
    return kExitInternalError;
  }
}

}  // namespace

namespace retrace::bench {

int RunCommandLine(int argc, char** argv) {
  CLI::App app{"retrace: teaching-playback navigation without a consistent map, simulated"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "retrace " + bench::BuildVersion());
  std::vector<std::pair<CLI::App*, bench::CommandRunner>> commands;
  for (const bench::CommandSpec& spec : bench::Commands()) {
    CLI::App* command = app.add_subcommand(spec.name, spec.help);
    commands.emplace_back(command, spec.declare(command));
  }
  if (const std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  for (const auto& [command, run] : commands) {
    if (*command) return RunReportingErrors(run, CommandLine(argc, argv));
  }
  return 0;
}

}  // namespace retrace::bench
