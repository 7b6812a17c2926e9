// Map images (PGM, PNG, PBM/PPM; io/ros_map.hpp) under a valid map YAML.
#include "fuzz/fuzz_input.hpp"
#include "io/ros_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  static const auto yaml =
      fuzz::WriteFile("images/map.yaml",
                      "image: input.img\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  fuzz::WriteFile("images/input.img", fuzz::AsText(data, size));
  fuzz::Refusing([&] { io::ReadRosMap(yaml); });
  return 0;
}
