// rosbag2 `metadata.yaml` files (logs/rosbag2_metadata.hpp).
#include "fuzz/fuzz_input.hpp"
#include "logs/rosbag2_metadata.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  const auto file = fuzz::WriteFile("bag/metadata.yaml", fuzz::AsText(data, size));
  fuzz::Refusing([&] { logs::ReadRosbag2Metadata(file.parent_path()); });
  return 0;
}
