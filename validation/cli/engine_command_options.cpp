#include "boxpile/validation/cli/engine_command_options.hpp"

#include "boxpile/validation/core/process_engines.hpp"

namespace boxpile::cli {

static_assert(EngineCommandOptions{}.timeout_seconds * 1000.0 == static_cast<double>(kDefaultEngineTimeout.count()),
              "the flag's default is the table's");

void add_engine_command_options(CLI::App& cmd, EngineCommandOptions& options) {
  cmd.add_option("--engine-cmd", options.commands,
                 "NAME=COMMAND: run COMMAND (through /bin/sh) as the engine NAME, speaking docs/engine-protocol.md; "
                 "NAME (lowercase letters, digits, hyphens) is then usable as an engine name. Repeatable")
      ->allow_extra_args(false);  // one NAME=COMMAND per flag: a scene after it stays the scene
  cmd.add_option("--engine-timeout", options.timeout_seconds,
                 "Seconds an engine over the protocol may take to answer one request, in (0, 86400]")
      ->capture_default_str();
}

void apply_engine_command_options(const EngineCommandOptions& options) {
  set_engine_timeout(options.timeout_seconds);
  for (const std::string& text : options.commands) add_engine_command(text);
}

}  // namespace boxpile::cli
