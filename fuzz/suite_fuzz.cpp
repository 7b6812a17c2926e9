// Suite files of `retrace bench` (bench/suite/suite_spec.hpp).
#include "bench/suite/suite_spec.hpp"
#include "fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  const auto file = fuzz::WriteFile("suites/input.yaml", fuzz::AsText(data, size));
  fuzz::Refusing([&] { bench::LoadSuiteSpec(file); });
  return 0;
}
