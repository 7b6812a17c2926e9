#include "bench/cli/log_simulate_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/log_options.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddLogSimulateOptions(CLI::App* cmd, LogSimulateOptions* options) {
  LogRunOptions& run = options->request.run;
  cmd->add_option("log", run.log, "The log (CARMEN, MCAP, rosbag2, ROS 1 bag)")->required();
  cmd->add_option("--teach", options->request.teach_dir,
                  "The consistent map's teach folder (log-teach's consistent/teach): the world")
      ->required();
  AddOutOption(cmd, &run.out, "The simulated log to write (MCAP)")->required();
  cmd->add_option("--from", run.window.from_s, "Start: s since the log's first message");
  cmd->add_option("--to", run.window.to_s, "End: s since the log's first message");
  cmd->add_flag("--synthetic-odometry", run.synthetic_odometry,
                "Drifting odometry drawn from the reference, as for log-teach and log-localize");
  cmd->add_option("--reference", run.reference, "TUM file with a reference trajectory");
  AddConfigOption(cmd, &run.config, "Settings file (YAML), as for log-teach");
  AddSetOption(cmd, &run.overrides, "a setting, e.g. sim.lidar.noise.sigma0=0.02");
  AddSeedOption(cmd, &run.seed, "of the LiDAR noise and the synthetic odometry");
  AddStreamOptions(cmd, &run.streams);
}

int RunLogSimulateCommand(const LogSimulateOptions& options) {
  std::cout << LogSimulateSummary(SimulateLogFile(options.request)) << "\n";
  return 0;
}

}  // namespace retrace::bench
