// World files (sim/world_file.hpp): boxes, circles, polygons, walls, imported maps, pedestrians.
#include "fuzz/fuzz_input.hpp"
#include "sim/world_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  fuzz::CopyShippedWorlds();
  const auto file = fuzz::WriteFile("worlds/input.yaml", fuzz::AsText(data, size));
  fuzz::Refusing([&] { sim::LoadWorld(file); });
  return 0;
}
