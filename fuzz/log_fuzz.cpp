// Logs as the log commands read them: both passes of logs/sensor_log.hpp over every stream the
// first pass picks. Built once per container (fuzz/CMakeLists.txt) with RETRACE_FUZZ_LOG_FILE
// naming the input file: `input.log` (CARMEN), `input.mcap` (MCAP), `input.db3` (rosbag2
// SQLite), `input.bag` (ROS 1 bag). The reader is chosen by the content, as `retrace log-info`
// chooses it.
#include "fuzz/fuzz_input.hpp"
#include "logs/sensor_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  const auto file = fuzz::WriteFile(RETRACE_FUZZ_LOG_FILE, fuzz::AsText(data, size));
  fuzz::Refusing([&] {
    const logs::LogIndex index = logs::IndexLog(file);
    logs::ReadScans(index, -1e300, 1e300, [](const logs::ScanMessage&, double) {});
  });
  return 0;
}
