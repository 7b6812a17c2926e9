#include "bench/cli/sweep_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddSweepOptions(CLI::App* command, SweepOptions* options) {
  SweepRequest& request = options->request;
  command->add_option("file", request.file, "Sweep file (YAML, see sweeps/)")->required();
  AddJobsOption(command, &request.jobs, "Cases run at once, one thread each");
  AddOutOption(command, &request.out,
               "Results folder (default: results/sweeps/<name>, or .../<name>/shard-<i>-of-<N>)");
  command->add_option("--shard", request.shard,
                      "Run only shard i of N: the cases with case % N == i - 1");
  AddSetOption(command, &request.overrides, "a scenario key in every case: a.b.c=value");
  command->add_flag("!--no-plot", request.plot, "Do not render sweep.png");
  AddNoReportFlag(command, &options->report,
                  "Do not write report.html, the sweep's page of its plot and results table "
                  "(retrace report does it later)");
}

int RunSweepCommand(const SweepOptions& options, const std::string& command_line) {
  SweepRun run;
  {
    ProgressLine progress;
    run = RunSweep(options.request, command_line, &progress);
  }
  std::cout << SweepRunSummary(run);
  if (options.report) WriteReportAtEnd(run.out);
  return 0;
}

}  // namespace retrace::bench
