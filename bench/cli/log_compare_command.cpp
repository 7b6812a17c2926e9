#include "bench/cli/log_compare_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddLogCompareOptions(CLI::App* cmd, LogCompareOptions* options) {
  LogCompareRequest& request = options->request;
  cmd->add_option("runs", request.runs, "Results folders of retrace log-localize (two or more)")
      ->required();
  cmd->add_option("--labels", request.labels, "Their names in the table and the figure")
      ->delimiter(',');
  AddOutOption(cmd, &request.out, "Folder to write")->required();
}

int RunLogCompareCommand(const LogCompareOptions& options) {
  const LogComparison compared = CompareLogs(options.request);
  const std::vector<std::string> notes = WriteLogCompareFolder(compared);
  std::cout << LogCompareSummary(compared, notes) << "\n";
  return 0;
}

}  // namespace retrace::bench
