// Sweep files of `retrace sweep` (bench/sweep/sweep_spec.hpp).
#include "bench/sweep/sweep_spec.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  const auto file = fuzz::WriteFile("sweeps/input.yaml", fuzz::AsText(data, size));
  fuzz::Refusing([&] { bench::LoadSweepSpec(file); });
  return 0;
}
