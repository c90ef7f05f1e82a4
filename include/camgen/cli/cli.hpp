#pragma once
// The command line, as a function so that tests can run it in-process.
#include <iosfwd>

namespace camgen {

// Exit codes.
enum ExitCode : int { exit_ok = 0, exit_invalid_input = 1, exit_usage = 2, exit_io = 3 };

// Runs camgen with these arguments; standard streams are passed in.
int run_cli(int argc, const char* const* argv, std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace camgen
