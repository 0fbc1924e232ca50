// The engines that are other programs, run over docs/engine-protocol.md: the built-in node-hosted
// ones (jolt, rapier, mujoco-wasm: `node <adapter>` from boxpile's data folder) and the ones a
// user names on the command line (--engine-cmd NAME=COMMAND). Each is a row of the engine
// registry (reference/registry.hpp), added at run time; its settings are the ones its hello
// declares, asked of the program once, when a list of settings is first needed.
#pragma once

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "boxpile/reference/process/process_engine.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile {

// A --engine-cmd or --engine-timeout that cannot be used (exit 2); what() names the flag.
class EngineCommandError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Registers the node-hosted engines (jolt, rapier, mujoco-wasm) as registry rows, each
// unavailable with its reason when node, its adapter or its npm packages are missing. Called once
// by the command line before any engine list is read; later calls do nothing.
void add_node_engines();

// Adds a user's engine from "NAME=COMMAND" (--engine-cmd). EngineCommandError when NAME is not
// lowercase letters, digits and hyphens (starting with a letter), is taken by another engine
// (built in or an earlier --engine-cmd), or COMMAND is empty.
void add_engine_command(std::string_view name_equals_command);

// The timeout of every answer of every engine over the protocol (--engine-timeout), and its
// bounds: positive, and at most a day (a longer wait is a hung engine, not a slow one).
inline constexpr std::chrono::milliseconds kDefaultEngineTimeout{30'000};
inline constexpr double kMaxEngineTimeoutSeconds = 86'400.0;
// EngineCommandError naming --engine-timeout unless `seconds` is finite and in
// (0, kMaxEngineTimeoutSeconds].
void set_engine_timeout(double seconds);
std::chrono::milliseconds engine_timeout();


}  // namespace boxpile
