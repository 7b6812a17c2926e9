// rosbag2 SQLite files (logs/sqlite_bag_reader.hpp), read as the log commands read them:
// both passes of logs/sensor_log.hpp over every stream the first pass picks.
#include "fuzz/fuzz_input.hpp"
#include "logs/sensor_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  const auto file = fuzz::WriteFile("input.db3", fuzz::AsText(data, size));
  fuzz::Refusing([&] {
    const logs::LogIndex index = logs::IndexLog(file);
    logs::ReadScans(index, -1e300, 1e300, [](const logs::ScanMessage&, double) {});
  });
  return 0;
}
