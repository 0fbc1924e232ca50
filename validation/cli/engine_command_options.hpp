// --engine-cmd NAME=COMMAND (repeatable) and --engine-timeout SECONDS on every command that runs
// engines (run, compare, stability, sweep): a user's program joins the engines under NAME and
// speaks docs/engine-protocol.md; each answer of any engine over the protocol must arrive within
// the timeout.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace boxpile::cli {

struct EngineCommandOptions {
  std::vector<std::string> commands;  // NAME=COMMAND
  double timeout_seconds = 30.0;      // validation/core/process_engines.hpp: kDefaultEngineTimeout
};

void add_engine_command_options(CLI::App& cmd, EngineCommandOptions& options);

// Adds the engines and sets the timeout (before any engine list is checked). EngineCommandError
// naming the flag when a value cannot be used.
void apply_engine_command_options(const EngineCommandOptions& options);

}  // namespace boxpile::cli
