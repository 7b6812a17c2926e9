// TUM trajectories (io/tum.hpp): `t x y z qx qy qz qw` per line.
#include "fuzz/fuzz_input.hpp"
#include "io/tum.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  const auto file = fuzz::WriteFile("trajectory.tum", fuzz::AsText(data, size));
  fuzz::Refusing([&] { io::ReadTum(file); });
  return 0;
}
