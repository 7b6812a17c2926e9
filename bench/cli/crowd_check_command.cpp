#include "bench/cli/crowd_check_command.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "bench/cli/cli_checks.hpp"
#include "bench/cli/shared_options.hpp"
#include "bench/crowd/crowd_check.hpp"

namespace retrace::bench {

void AddCrowdCheckOptions(CLI::App* cmd, CrowdCheckOptions* options) {
  AddOutOption(cmd, &options->out, "Output folder")->capture_default_str();
  cmd->add_option("--densities", options->densities,
                  "Densities (persons/m^2), comma-separated, each > 0 and < 5.4")
      ->capture_default_str();
  cmd->add_option("--flows", options->flows,
                  "Flows round the ring, comma-separated: one_way (everyone the same way), two_way "
                  "(half each way)")
      ->capture_default_str();
  AddSeedOption(cmd, &options->seed, "of the start points and desired speeds")
      ->capture_default_str();
  cmd->add_option("--duration", options->duration, "Seconds of measurement (default 40)")
      ->check(kPositive);
  cmd->add_option("--warmup", options->warmup, "Seconds before measuring (default 20)")
      ->check(kNonNegative);
  AddSetOption(cmd, &options->overrides,
               "a key: ring/body/timing keys (width=3, pedestrian_radius=0.25) or the crowd's "
               "(sim.crowd.social_force.relaxation_time=0.4)");
}

int RunCrowdCheckCommand(const CrowdCheckOptions& options) {
  CrowdCheckRequest request;
  request.densities = ParseDensityList(options.densities);
  request.flows = ParseFlowList(options.flows);
  request.seed = options.seed;
  request.duration = options.duration;
  request.warmup = options.warmup;
  request.overrides = options.overrides;
  const bool terminal = isatty(fileno(stderr)) != 0;
  const CrowdCheck check =
      RunCrowdCheck(request, [&](const FundamentalDiagramRow& r, std::size_t done) {
        if (!terminal) return;
        std::fprintf(stderr, "\rcrowd-check: %zu/%zu densities (last %.2f /m2, %d people)   ", done,
                     request.densities.size() * request.flows.size(), r.density, r.count);
        std::fflush(stderr);
      });
  if (terminal) std::fprintf(stderr, "\n");
  WriteCrowdCheckFolder(options.out, check, request);
  std::cout << CrowdCheckSummary(check, options.out);
  return 0;
}

}  // namespace retrace::bench
