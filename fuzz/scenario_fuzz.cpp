// Scenario files (bench/engine/scenario.hpp), with the shipped worlds beside them.
#include "bench/engine/scenario.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  fuzz::CopyShippedWorlds();
  const auto file = fuzz::WriteFile("scenarios/input.yaml", fuzz::AsText(data, size));
  fuzz::Refusing([&] { bench::LoadScenario(file); });
  return 0;
}
