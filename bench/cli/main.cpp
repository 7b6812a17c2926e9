// The `retrace` command-line program (bench/cli/command_line.hpp has the exit codes).

#include "bench/cli/command_line.hpp"

int main(int argc, char** argv) { return retrace::bench::RunCommandLine(argc, argv); }
