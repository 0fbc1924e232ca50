// The boxpile command line as a function: main() calls it, and so does the command-line fuzzer
// (fuzz/fuzz_command_line.cpp), which parses argument vectors without running anything.
#pragma once

namespace boxpile::cli {

enum class CommandLineMode {
  Run,        // parse, then run the command (and install the signal handlers first)
  ParseOnly,  // parse and check the arguments (CLI11's checks, ours in its callbacks), run nothing
};

// The exit code (commands.hpp: 0, 1, 2, 130). Errors are printed on stderr, one line each.
int run_command_line(int argc, const char* const* argv, CommandLineMode mode = CommandLineMode::Run);

}  // namespace boxpile::cli
