// `retrace` with one more stack: registers `pure_pursuit`, then runs the command line as the
// `retrace` program does (`run`, `compare`, `sweep`, `bench` ... with playback.stack=pure_pursuit).

#include "bench/cli/command_line.hpp"
#include "pure_pursuit_stack.hpp"

int main(int argc, char** argv) {
  external::RegisterPurePursuit();
  return retrace::bench::RunCommandLine(argc, argv);
}
