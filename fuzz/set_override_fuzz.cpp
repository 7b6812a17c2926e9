// `--set a.b.c=value` overrides (io/config_override.hpp), one per input line, applied to the small
// scenario's file and read back as a scenario config.
#include <sstream>
#include <string>
#include <vector>

#include "bench/engine/scenario.hpp"
#include "fuzz/fuzz_input.hpp"
#include "io/config_override.hpp"
#include "io/config_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace retrace;
  static const YAML::Node scenario =
      io::LoadYamlFile(std::filesystem::path(RETRACE_SOURCE_DIR) / "scenarios/small.yaml");
  fuzz::Refusing([&] {
    std::vector<io::ConfigOverride> overrides;
    std::istringstream lines{std::string(fuzz::AsText(data, size))};
    for (std::string line; std::getline(lines, line);) overrides.push_back(io::ParseOverride(line));
    YAML::Node root = YAML::Clone(scenario);
    io::ApplyOverrides(root, overrides);
    io::ReadConfig<bench::ScenarioConfig>(root, "fuzz", overrides);
  });
  return 0;
}
