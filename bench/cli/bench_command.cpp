#include "bench/cli/bench_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/progress.hpp"
#include "bench/cli/report_command.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddBenchOptions(CLI::App* command, BenchOptions* options) {
  BenchRequest& request = options->request;
  command->add_option("suite", request.suite, "Suite file (YAML), e.g. bench/suites/ci.yaml")
      ->required();
  command->add_option("--baseline", request.baseline,
                      "Baseline file (default: results/baselines/<suite name>.json)");
  command->add_flag("--update-baseline", request.update_baseline,
                    "Record the results as the suite's baseline instead of judging them");
  AddJobsOption(command, &request.jobs);
  AddOutOption(command, &request.out, "Report folder (default: results/bench/<suite name>)");
  AddSetOption(command, &request.overrides, "a scenario key in every entry: a.b.c=value");
  command->add_option("--only", request.only,
                      "Run and judge only these entries or modes: <entry>[.<mode>] (repeatable)");
  command->add_option("--junit", request.junit,
                      "Write the verdicts as JUnit XML to FILE: a testcase per gated metric, a "
                      "failure per regression (also written on a regression)");
  command->add_option("--trend", request.trend,
                      "Write every metric of the run to FILE as Bencher Metric Format JSON, "
                      "for trend charts across commits");
  AddNoReportFlag(command, &options->report,
                  "Do not write report.html, the report's page with the regressions in red, "
                  "also written on a regression (retrace report does it later)");
}

int RunBenchCommand(const BenchOptions& options) {
  BenchRun run;
  {
    ProgressLine progress;
    run = RunBench(options.request, &progress);
  }
  std::cout << BenchSummary(run) << "\n";
  if (options.report) WriteReportAtEnd(run.out);
  return run.exit_code;
}

}  // namespace retrace::bench
