// The engines that are other programs, run over docs/engine-protocol.md: the built-in node-hosted
// ones (jolt, rapier, mujoco-wasm: `node <adapter>` from boxpile's data folder) and the ones a
// user names on the command line (--engine-cmd NAME=COMMAND). engine_factory.hpp lists and
// builds them beside the engines linked in.
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

struct ProcessEngineRow {
  std::string name;
  std::string command;      // run through /bin/sh -c; empty when unavailable
  std::string unavailable;  // why it cannot run here (empty when it can)
  bool built_in = false;    // one of the node-hosted engines, not a --engine-cmd
};

// Every engine run over the protocol, built-in rows first, then the user's in the order given.
const std::vector<ProcessEngineRow>& process_engines();
// The row of `name`, or nullptr when no such engine runs over the protocol.
const ProcessEngineRow* find_process_engine(std::string_view name);
// Changes whenever a row is added (the factory's name lists are rebuilt then).
int process_engines_generation();

// Adds a user's engine from "NAME=COMMAND" (--engine-cmd). EngineCommandError when NAME is not lowercase letters, digits and
// hyphens (starting with a letter), is taken by a built-in engine or an earlier --engine-cmd, or
// COMMAND is empty.
void add_engine_command(std::string_view name_equals_command);

// The timeout of every answer of every engine over the protocol (--engine-timeout), and its
// bounds: positive, and at most a day (a longer wait is a hung engine, not a slow one).
inline constexpr std::chrono::milliseconds kDefaultEngineTimeout{30'000};
inline constexpr double kMaxEngineTimeoutSeconds = 86'400.0;
// EngineCommandError naming --engine-timeout unless `seconds` is finite and in
// (0, kMaxEngineTimeoutSeconds].
void set_engine_timeout(double seconds);
std::chrono::milliseconds engine_timeout();

// The engine `row` running `scene` (its settings empty: the engine's defaults).
std::unique_ptr<Engine> make_process_engine(const ProcessEngineRow& row, const Scene& scene);

}  // namespace boxpile
