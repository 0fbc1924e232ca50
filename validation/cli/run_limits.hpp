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
#include <nlohmann/json.hpp>

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
  std::size_t max_pairs = limits::kDefaultMaxPairs;
  std::size_t max_input_bytes = limits::kDefaultMaxInputBytes;
  int max_iterations = limits::kDefaultMaxIterations;
  LoadLimits load() const { return {max_bodies, max_pairs, max_input_bytes}; }
};

// --max-steps, --max-bodies, --max-pairs, --max-input-bytes (and --max-iterations when
// `iterations` is true): every command that runs a scene registers them all.
void add_limit_options(CLI::App& cmd, RunLimits& limits, bool iterations);
// --max-input-bytes alone, for the commands that read files but run no scene.
void add_input_limit_option(CLI::App& cmd, std::size_t& max_input_bytes);

// "own, own-impulse, own-penalty, ode, bullet": the engines make_engine() can build, for help
// texts (reference/registry.hpp), so that they list exactly the names accepted.
std::string engine_choices();
// "own,ode,bullet": a default engine list as a help text shows it.
std::string engine_list(const std::vector<std::string>& names);

// `--set [ENGINE.]KEY=VALUE`, repeatable (validation/core/engine_settings.hpp reads the words).
void add_set_option(CLI::App& cmd, std::vector<std::string>& words);

// A CLI11 check that a value is a whole number >= 0 written in digits (an unsigned option would
// take "-1" as 2^64 - 1).
CLI::Validator whole_number();

// --dt and --duration (no CLI11 check: NaN would pass it; apply_time_options checks). An empty
// value is refused (CLI11 would leave the option unset and the scene's value in force).
void add_time_options(CLI::App& cmd, std::optional<double>& dt, std::optional<double>& duration);

// --threads N: the threads our engine's impulse method runs on (its `threads` setting, whose
// declaration gives the range and the meaning). Absent, the scene's solver.threads.
void add_threads_option(CLI::App& cmd, std::optional<int>& threads);
// Sets the scene's solver.threads to the flag's value, when given.
void apply_threads_option(Scene& scene, const std::optional<int>& threads);

// Overrides the scene's dt and duration by the flags given, then checks them and the step count
// against the cap. The error names the flag when one was given, else the scene's field.
void apply_time_options(Scene& scene, const std::optional<double>& dt, const std::optional<double>& duration,
                        const RunLimits& limits);

// Before a run of `engine` on `scene` with `settings` (the engine's, checked): a time step the
// engine can run (the penalty method's stability bound) and the steps times the engine's work per
// step (the penalty method's substeps: `--set substeps=100000` multiplies the work) within
// --max-steps. `dt_flag` says that the command line set dt (--dt, or a grid's "dt"): the refusal
// names `dt_source` then, else the scene's time.dt. The engine's own time step (`--set
// ENGINE.dt`) is held to the step cap as --dt is, and refused beside --dt. UsageError or
// InputError (exit 2).
void check_run_work(const Scene& scene, std::string_view engine, const nlohmann::json& settings,
                    const RunLimits& limits, bool dt_flag, std::string_view dt_source = "--dt");

// Each name once (`--engines own,own` would run and compare an engine with itself): UsageError
// naming `flag` and the repeated name.
void check_distinct(const std::vector<std::string>& names, std::string_view flag);

// Engines that make_engine() can build (UnknownEngine otherwise), each once (check_distinct).
void check_engines(const std::vector<std::string>& names, std::string_view flag);

// Engines that run the same thing on `scene` (reference/registry.hpp, EngineRow::runs_as: "own"
// is "own-impulse" or "own-penalty" by the scene's solver.method, so `--engines own,own-impulse`
// would run one engine twice). UsageError naming `flag`, both names and the scene.
void check_engines_differ(const std::vector<std::string>& names, const Scene& scene, std::string_view flag);

// A flag that stands for one setting of the engine (--iterations): UsageError naming `flag` when
// `engine` declares no setting `key`, rather than a flag accepted and ignored.
void check_has_setting(std::string_view engine, std::string_view key, std::string_view flag);

// Solver iterations within [1, max_iterations].
void check_iterations(int iterations, const RunLimits& limits);

}  // namespace boxpile::cli
