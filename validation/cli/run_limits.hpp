// The settings every command that runs a scene shares: the time-step overrides (--dt,
// --duration) checked by the one rule of sim/time_steps.hpp, and the caps on work (--max-steps,
// --max-bodies, --max-iterations; defaults in sim/limits.hpp). A new command that runs scenes
// registers them with add_limit_options() and applies them with these functions.
#pragma once

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/limits.hpp"
#include "boxpile/sim/scene.hpp"

namespace boxpile::cli {

// A flag's value cannot be used (exit 2). The message names the flag.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunLimits {
  long max_steps = limits::kDefaultMaxSteps;
  std::size_t max_bodies = limits::kDefaultMaxBodies;
  int max_iterations = limits::kDefaultMaxIterations;
  LoadLimits load() const { return {max_bodies}; }
};

// --max-steps and --max-bodies (and --max-iterations when `iterations` is true).
void add_limit_options(CLI::App& cmd, RunLimits& limits, bool iterations);

// "own, own-impulse, own-penalty, ode, bullet": the engines make_engine() can build, for help
// texts (reference/registry.hpp), so that they list exactly the names accepted.
std::string engine_choices();
// "own,ode,bullet": a default engine list as a help text shows it.
std::string engine_list(const std::vector<std::string>& names);

// `--set [ENGINE.]KEY=VALUE`, repeatable (validation/engine_settings.hpp reads the words).
void add_set_option(CLI::App& cmd, std::vector<std::string>& words);

// --dt and --duration (no CLI11 check: NaN would pass it; apply_time_options checks).
void add_time_options(CLI::App& cmd, std::optional<double>& dt, std::optional<double>& duration);

// Overrides the scene's dt and duration by the flags given, then checks them and the step count
// against the cap. The error names the flag when one was given, else the scene's field.
void apply_time_options(Scene& scene, const std::optional<double>& dt, const std::optional<double>& duration,
                        const RunLimits& limits);

// Each name once (`--engines own,own` would run and compare an engine with itself): UsageError
// naming `flag` and the repeated name.
void check_distinct(const std::vector<std::string>& names, std::string_view flag);

// Engines that make_engine() can build (UnknownEngine otherwise), each once (check_distinct).
void check_engines(const std::vector<std::string>& names, std::string_view flag);

// Solver iterations within [1, max_iterations].
void check_iterations(int iterations, const RunLimits& limits);

}  // namespace boxpile::cli
