// ROS map_server YAML files (io/ros_map.hpp), beside a valid 20 x 20 PGM image `map.pgm`.
#include <string>

#include "fuzz/fuzz_input.hpp"
#include "io/ros_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  static const bool image = [] {
    fuzz::WriteFile("maps/map.pgm", "P5\n20 20\n255\n" + std::string(400, '\xfe'));
    return true;
  }();
  (void)image;
  const auto file = fuzz::WriteFile("maps/input.yaml", fuzz::AsText(data, size));
  fuzz::Refusing([&] { io::ReadRosMap(file); });
  return 0;
}
