#include "bench/cli/log_compare_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/shared_options.hpp"
#include "bench/output/staged_folder.hpp"
#include "bench/replay/log_comparison.hpp"
#include "core/errors.hpp"
#include "viz/render_error.hpp"

namespace retrace::bench {

void AddLogCompareOptions(CLI::App* cmd, LogCompareOptions* options) {
  cmd->add_option("runs", options->runs, "Results folders of retrace log-localize (two or more)")
      ->required();
  cmd->add_option("--labels", options->labels, "Their names in the table and the figure")
      ->delimiter(',');
  AddOutOption(cmd, &options->out, "Folder to write")->required();
}

int RunLogCompareCommand(const LogCompareOptions& options) {
  if (options.runs.size() < 2)
    throw core::ConfigError("runs", "a comparison needs at least two log-localize folders");
  const std::vector<LoggedRun> runs = ReadLoggedRuns(options.runs, options.labels);
  StagedFolder folder(options.out);
  std::string note;
  try {
    WriteLogComparison(folder.path(), runs);
  } catch (const viz::RenderError& e) {
    note = std::string("no figure: ") + e.what() + "\n";
  }
  folder.Commit();
  std::cout << LoggedRunsTable(runs) << note << "results: " << options.out.string() << "\n";
  return 0;
}

}  // namespace retrace::bench
