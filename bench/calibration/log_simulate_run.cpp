#include "bench/calibration/log_simulate_run.hpp"

#include <system_error>

#include "bench/output/results_io.hpp"
#include "bench/replay/log_config.hpp"
#include "bench/replay/log_streams.hpp"
#include "core/format.hpp"

namespace retrace::bench {

SimulatedLog SimulateLogFile(const LogSimulateRequest& request) {
  const LogConfig config = LoadLogRunConfig(request.run, {});
  const ModeTeach teach = ReadTeachFolder(request.teach_dir, MapMode::kConsistent);
  const logs::LogIndex index = logs::IndexLog(request.run.log, request.run.streams);
  const LogStreams streams =
      PrepareLogStreams(index, config, request.run.synthetic_odometry, request.run.reference);
  SimulatedLog simulated;
  simulated.request = request;
  simulated.beams = index.scan.beams;
  simulated.reference_source = streams.reference_source;
  // Written beside the target and renamed when complete: the file is whole or absent.
  const std::filesystem::path& out = request.run.out;
  const std::filesystem::path staging = out.string() + ".tmp";
  try {
    simulated.simulation =
        SimulateLog(index, streams, teach, request.teach_dir, config, request.run.window, staging);
    std::filesystem::rename(staging, out);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(staging, ignored);
    throw;
  }
  return simulated;
}

std::string LogSimulateSummary(const SimulatedLog& s) {
  const std::string out = s.request.run.out.string();
  return out + ": " + std::to_string(s.simulation.scans) + " simulated scans of " +
         std::to_string(s.beams) + " beams from " + core::FixedText(s.simulation.first_stamp, 1) +
         " to " + core::FixedText(s.simulation.last_stamp, 1) + " s along " + s.reference_source +
         ", in the map of " + s.request.teach_dir.string() +
         "\nlocalize it as the log itself: retrace log-localize " + out +
         " --teach <teach folder> --out <dir>";
}

}  // namespace retrace::bench
