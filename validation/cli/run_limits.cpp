#include "boxpile/validation/cli/run_limits.hpp"

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/reference/registry.hpp"

namespace boxpile::cli {

void add_limit_options(CLI::App& cmd, RunLimits& limits, bool iterations) {
  cmd.add_option("--max-steps", limits.max_steps, "Refuse a run of more steps than this")
      ->check(CLI::Range(1L, limits::kMaxRepresentableSteps))
      ->capture_default_str();
  cmd.add_option("--max-bodies", limits.max_bodies, "Refuse a scene of more bodies than this")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100'000'000}))
      ->capture_default_str();
  if (iterations) {
    cmd.add_option("--max-iterations", limits.max_iterations, "Refuse more solver iterations than this")
        ->check(CLI::Range(1, 1'000'000'000))
        ->capture_default_str();
  }
}

std::string engine_choices() { return available_engines_text(); }

std::string engine_list(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ",") + name;
  return list;
}

void add_set_option(CLI::App& cmd, std::vector<std::string>& words) {
  cmd.add_option("--set", words,
                 "A setting of an engine as ENGINE.KEY=VALUE, repeatable (e.g. --set ode.erp=0.8 --set bullet.iterations=20; "
                 "the ENGINE. prefix may be left out when one engine runs); `boxpile settings` lists them with units "
                 "and ranges")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

void add_time_options(CLI::App& cmd, std::optional<double>& dt, std::optional<double>& duration) {
  cmd.add_option("--dt", dt, "Time step in s, in (0, 1] (default: the scene's)");
  cmd.add_option("--duration", duration, "Simulated time in s, >= 0 (default: the scene's)");
}

void apply_time_options(Scene& scene, const std::optional<double>& dt, const std::optional<double>& duration,
                        const RunLimits& limits) {
  if (dt) scene.time.dt = *dt;
  if (duration) scene.time.duration = *duration;
  const auto problem = check_time_settings(scene.time.dt, scene.time.duration, limits.max_steps);
  if (!problem) return;
  // A step count over the cap is blamed on the flag that changed it (--dt alone: on --dt).
  const bool on_dt = problem->field == TimeSettingsProblem::Field::Dt || (problem->over_cap && dt && !duration);
  const bool from_flag = on_dt ? dt.has_value() : (duration.has_value() || dt.has_value());
  const std::string hint = problem->over_cap ? " (--max-steps raises it)" : "";
  if (from_flag) throw UsageError((on_dt ? "--dt: " : "--duration: ") + problem->what + hint);
  throw InputError(scene.source, on_dt ? "time.dt" : "time.duration", problem->what + hint);
}

void check_distinct(const std::vector<std::string>& names, std::string_view flag) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (names[i] == names[j]) throw UsageError(std::string(flag) + ": \"" + names[i] + "\" is listed twice");
    }
  }
}

void check_engines(const std::vector<std::string>& names, std::string_view flag) {
  for (const std::string& name : names) check_engine_name(name);
  check_distinct(names, flag);
}

void check_iterations(int iterations, const RunLimits& limits) {
  if (iterations < 1 || iterations > limits.max_iterations) {
    throw UsageError("--iterations: must be in [1, " + std::to_string(limits.max_iterations) + "], got " +
                     std::to_string(iterations) + " (--max-iterations raises the cap)");
  }
}

}  // namespace boxpile::cli
