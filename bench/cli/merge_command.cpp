#include "bench/cli/merge_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench/cli/progress.hpp"
#include "bench/cli/shared_options.hpp"

namespace retrace::bench {

void AddMergeOptions(CLI::App* command, MergeOptions* options) {
  MergeRequest& request = options->request;
  command
      ->add_option("shards", request.inputs,
                   "The results folders of the shards (retrace sweep --shard i/N)")
      ->required();
  AddOutOption(command, &request.out, "Folder for the joined results")->required();
  command->add_flag("!--no-plot", request.plot, "Do not render sweep.png");
}

int RunMergeCommand(const MergeOptions& options, const std::string& command_line) {
  SweepMerge merged;
  {
    ProgressLine progress;
    merged = MergeSweepShards(options.request, command_line, &progress);
  }
  std::cout << SweepMergeSummary(merged);
  return 0;
}

}  // namespace retrace::bench
