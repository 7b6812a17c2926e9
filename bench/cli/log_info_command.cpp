#include "bench/cli/log_info_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/log_options.hpp"
#include "bench/replay/log_description.hpp"

namespace retrace::bench {

void AddLogInfoOptions(CLI::App* cmd, LogInfoOptions* options) {
  AddLogArgument(cmd, &options->log);
  AddStreamOptions(cmd, &options->streams);
}

int RunLogInfoCommand(const LogInfoOptions& options) {
  const logs::LogIndex index = logs::IndexLog(options.log, options.streams);
  std::cout << DescribeLog(index) << "\n";
  if (!index.needs_choice) logs::RequireUsable(index);
  return 0;
}

}  // namespace retrace::bench
