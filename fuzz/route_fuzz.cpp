// Route files (io/route_file.hpp): `x y` or `x y z qx qy qz qw` per line.
#include "fuzz/fuzz_input.hpp"
#include "io/route_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  const auto file = fuzz::WriteFile("route.txt", fuzz::AsText(data, size));
  fuzz::Refusing([&] { io::ReadRouteFile(file); });
  return 0;
}
