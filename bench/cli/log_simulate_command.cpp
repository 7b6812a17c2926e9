#include "bench/cli/log_simulate_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <system_error>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/log_options.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/output/results_io.hpp"
#include "bench/replay/log_simulate.hpp"
#include "core/errors.hpp"
#include "core/format.hpp"

namespace retrace::bench {

void AddLogSimulateOptions(CLI::App* cmd, LogSimulateOptions* options) {
  LogRunOptions& run = options->run;
  cmd->add_option("log", run.log, "The log (CARMEN, MCAP, rosbag2)")->required();
  cmd->add_option("--teach", options->teach_dir,
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
  const LogConfig config = LoadLogRunConfig(options.run, {});
  const ModeTeach teach = ReadTeachFolder(options.teach_dir, MapMode::kConsistent);
  const logs::LogIndex index = logs::IndexLog(options.run.log, options.run.streams);
  const LogStreams streams =
      PrepareLogStreams(index, config, options.run.synthetic_odometry, options.run.reference);
  // Written beside the target and renamed when complete: the file is whole or absent.
  const std::filesystem::path& out = options.run.out;
  const std::filesystem::path staging = out.string() + ".tmp";
  LogSimulation simulation;
  try {
    simulation =
        SimulateLog(index, streams, teach, options.teach_dir, config, options.run.window, staging);
    std::filesystem::rename(staging, out);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(staging, ignored);
    throw;
  }
  std::cout << out.string() << ": " << simulation.scans << " simulated scans of "
            << index.scan.beams << " beams from " << core::FixedText(simulation.first_stamp, 1)
            << " to " << core::FixedText(simulation.last_stamp, 1) << " s along "
            << streams.reference_source << ", in the map of " << options.teach_dir.string()
            << "\nlocalize it as the log itself: retrace log-localize " << out.string()
            << " --teach <teach folder> --out <dir>\n";
  return 0;
}

}  // namespace retrace::bench
