#include "bench/cli/compare_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddCompareOptions(CLI::App* command, CompareOptions* options) {
  ComparisonRequest& request = options->request;
  command->add_option("scenario", request.scenario, "Scenario file (YAML)")->required();
  command->add_option("--modes", request.modes, "Map modes to compare, comma-separated, or all")
      ->delimiter(',')
      ->default_str("all");
  command->add_option("--reference", request.reference, "The mode the others are compared against")
      ->default_str("consistent");
  command
      ->add_option("--stacks", request.stacks,
                   "Navigation stacks to put side by side (playback.stack names), each in every "
                   "mode on the same seeds; the reference is the first stack's (default: the "
                   "scenario's stack)")
      ->delimiter(',');
  command->add_option("--seeds", request.seeds, "Scenario seeds (seed, seed + 1, ...), at least 2")
      ->default_str("5");
  command
      ->add_option("--repeats", request.repeats,
                   "Playback runs per mode and seed (default: the scenario's)")
      ->check(kPositive);
  AddJobsOption(command, &request.jobs);
  AddOutOption(command, &request.out, "Output folder (default: results/compare/<scenario name>)");
  AddSetOption(command, &request.overrides, "a scenario key: a.b.c=value");
  AddNoReportFlag(command, &options->report,
                  "Do not write report.html, the study's page of tables and figures (retrace "
                  "report does it later)");
}

int RunCompareCommand(const CompareOptions& options, const std::string& command_line) {
  ComparisonStudy study;
  {
    ProgressLine progress;
    study = RunComparisonStudy(options.request, command_line, &progress);
  }
  std::cout << ComparisonStudySummary(study) << "\n";
  if (options.report) WriteReportAtEnd(study.out);
  return 0;
}

}  // namespace retrace::bench
