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
// texts (validation/engine_factory.hpp), so that they list exactly the names accepted.
std::string engine_choices();

// A CLI11 check that a value is a whole number >= 0 written in digits (an unsigned option would
// take "-1" as 2^64 - 1).
CLI::Validator whole_number();

// --dt and --duration (no CLI11 check: NaN would pass it; apply_time_options checks). An empty
// value is refused (CLI11 would leave the option unset and the scene's value in force).
void add_time_options(CLI::App& cmd, std::optional<double>& dt, std::optional<double>& duration);

// Overrides the scene's dt and duration by the flags given, then checks them and the step count
// against the cap. The error names the flag when one was given, else the scene's field.
void apply_time_options(Scene& scene, const std::optional<double>& dt, const std::optional<double>& duration,
                        const RunLimits& limits);

// The steps of a run of `engine` on `scene` that --max-steps caps: the scene's steps, times the
// penalty method's substeps when the engine runs it (each substep finds and resolves the contacts,
// a whole step's work: `--set substeps=100000` multiplies the work).
long work_steps(const Scene& scene, std::string_view engine);

// Before a run of `engine` on `scene` (its settings applied): the step count with substeps within
// --max-steps, and, for the penalty method, a dt within its stability bound. `dt_flag` says that
// the command line set dt (--dt, or a grid's "dt"): the refusal names `dt_source` then, else the
// scene's time.dt. UsageError or InputError (exit 2).
void check_run_work(const Scene& scene, std::string_view engine, const RunLimits& limits, bool dt_flag,
                    std::string_view dt_source = "--dt");

// Each name once (`--engines own,own` would run and compare an engine with itself): UsageError
// naming `flag` and the repeated name.
void check_distinct(const std::vector<std::string>& names, std::string_view flag);

// Engines that make_engine() can build (UnknownEngine otherwise), each once (check_distinct).
void check_engines(const std::vector<std::string>& names, std::string_view flag);

// Engines that run the same thing on `scene`: "own" is "own-impulse" or "own-penalty" by the
// scene's solver.method, so `--engines own,own-impulse` would run one engine twice. UsageError
// naming `flag`, both names and the scene.
void check_engines_differ(const std::vector<std::string>& names, const Scene& scene, std::string_view flag);

// Each --set key once (`--set erp=0.2 --set erp=0.8` would keep one silently).
void check_distinct_settings(const std::vector<std::string>& words);

// Solver iterations within [1, max_iterations].
void check_iterations(int iterations, const RunLimits& limits);

}  // namespace boxpile::cli
