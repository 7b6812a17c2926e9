#pragma once
// The `retrace` program as a function: a program that links the harness (retrace::cli) registers
// stacks of its own (bench/engine/stack_registry.hpp), then hands its command line here, and
// every command runs with them (examples/external_stack).

namespace retrace::bench {

/// Parses and runs one `retrace` command line. Exit codes: 0 success; 1 the runs completed but
/// navigation failed where the scenario requires success; 2 bad input (one clear line on
/// stderr, nothing written); 3 an internal error.
int RunCommandLine(int argc, char** argv);

}  // namespace retrace::bench
