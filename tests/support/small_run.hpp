#pragma once
// The options of `retrace run scenarios/small.yaml --mode <mode> --repeats 1 --out <out>
// --jobs <jobs>`, for the tests that run the whole command.

#include <filesystem>
#include <string>

#include "bench/cli/run_command.hpp"
#include "tests/support/source_dir.hpp"

namespace retrace::testing {

inline bench::RunOptions SmallRunOptions(const std::string& mode, const std::filesystem::path& out,
                                         int jobs) {
  bench::RunOptions options;
  options.scenario = kSource / "scenarios/small.yaml";
  options.modes = {mode};
  options.repeats = 1;
  options.out = out;
  options.jobs = jobs;
  return options;
}

}  // namespace retrace::testing
