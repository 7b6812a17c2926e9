#pragma once
// The subcommands of `retrace`, in one table: each one's name, its line of help, and the
// function that declares its options on the CLI11 subcommand and returns what runs it.

#include <functional>
#include <span>
#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace retrace::bench {

/// Runs a subcommand whose options CLI11 has filled, given the whole command line (for the
/// manifests); its exit code (docs/CLI.md).
using CommandRunner = std::function<int(const std::string& command_line)>;

struct CommandSpec {
  const char* name;
  const char* help;
  /// Declares the options on `command` and returns the runner that reads them.
  CommandRunner (*declare)(CLI::App* command);
};

/// Every subcommand, in the order --help lists them.
std::span<const CommandSpec> Commands();

}  // namespace retrace::bench
