// CSV tables (io/csv_reader.hpp), as `retrace merge` and the sweeps read them back.
#include "fuzz/fuzz_input.hpp"
#include "io/csv_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  fuzz::Refusing([&] { io::ParseCsv(fuzz::AsText(data, size), "fuzz.csv"); });
  return 0;
}
