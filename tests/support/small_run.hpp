#pragma once
// The request of `retrace run scenarios/small.yaml --mode <mode> --repeats 1 --out <out>
// --jobs <jobs>`, for the tests that run the whole command (bench::RunScenario).

#include <filesystem>
#include <string>

#include "bench/run/scenario_run.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::testing {

inline bench::ScenarioRunRequest SmallRunOptions(const std::string& mode,
                                                 const std::filesystem::path& out, int jobs) {
  bench::ScenarioRunRequest options;
  options.scenario = kSource / "scenarios/small.yaml";
  options.modes = {mode};
  options.repeats = 1;
  options.out = out;
  options.jobs = jobs;
  return options;
}

}  // namespace retrace::testing
