#include "boxpile/validation/cli/run_limits.hpp"

#include <algorithm>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/io/own_settings.hpp"
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
  cmd.add_option("--max-pairs", limits.max_pairs,
                  "Refuse a scene or a step with more pairs of touching bodies than this")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1'000'000'000}))
      ->capture_default_str();
  add_input_limit_option(cmd, limits.max_input_bytes);
  if (iterations) {
    cmd.add_option("--max-iterations", limits.max_iterations, "Refuse more solver iterations than this")
        ->check(CLI::Range(1, 1'000'000'000))
        ->capture_default_str();
  }
}

void add_input_limit_option(CLI::App& cmd, std::size_t& max_input_bytes) {
  cmd.add_option("--max-input-bytes", max_input_bytes, "Refuse an input file larger than this")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 40))
      ->capture_default_str();
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

CLI::Validator whole_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
          return "must be a whole number >= 0 in digits, got " + json_input::in_quotes(text);
        }
        return "";
      },
      "UINT");
}

namespace {

CLI::Validator non_empty() {
  return CLI::Validator(
      [](std::string& text) -> std::string { return text.empty() ? "must be a number, got an empty value" : ""; }, "");
}

}  // namespace

void add_time_options(CLI::App& cmd, std::optional<double>& dt, std::optional<double>& duration) {
  cmd.add_option("--dt", dt, "Time step in s, in (0, 1] (default: the scene's)")->check(non_empty());
  cmd.add_option("--duration", duration, "Simulated time in s, >= 0 (default: the scene's)")->check(non_empty());
}

namespace {
const Setting<Scene>& threads_setting() {
  const Setting<Scene>* row = own_settings_table().find("threads");
  if (row == nullptr) throw std::logic_error("our solver declares no \"threads\" setting");
  return *row;
}
}  // namespace

void add_threads_option(CLI::App& cmd, std::optional<int>& threads) {
  const SettingInfo& info = threads_setting().info;
  cmd.add_option("--threads", threads,
                 "Threads our engine's step runs on (solver.threads: " + info.what + "; default: the scene's, "
                 "else every core)")
      ->check(CLI::Range(static_cast<int>(info.min), static_cast<int>(info.max)));
}

void apply_threads_option(Scene& scene, const std::optional<int>& threads) {
  if (threads) threads_setting().apply(scene, nlohmann::json(*threads));
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

void check_run_work(const Scene& scene_file, std::string_view engine, const nlohmann::json& settings,
                    const RunLimits& limits, bool dt_flag, std::string_view dt_source) {
  // The engine's own time step (`--set ENGINE.dt`), within the cap of steps as --dt is.
  const std::string& dt_key = time_step_setting().key;
  const Scene scene = scene_with_settings(engine, scene_file, settings);
  if (settings.contains(dt_key)) {
    const std::string flag = "--set " + std::string(engine) + "." + dt_key;
    if (dt_flag) throw UsageError(flag + " and " + std::string(dt_source) + " both set the time step of " + std::string(engine) + ": give one");
    if (const auto problem = check_time_settings(scene.time.dt, scene.time.duration, limits.max_steps)) {
      throw UsageError(flag + ": " + problem->what + (problem->over_cap ? " (--max-steps raises it)" : ""));
    }
    dt_flag = true;
    dt_source = flag;
  }
  if (const std::string problem = engine_time_step_problem(engine, scene, settings); !problem.empty()) {
    const std::string what = std::string(engine) + ": " + problem;
    if (dt_flag) throw UsageError(std::string(dt_source) + ": " + what);
    throw InputError(scene.source, "time.dt", what);
  }
  // The plain step count was checked with the time settings.
  const long per_step = engine_work_per_step(engine, scene, settings);
  const long steps = step_count(scene.time);
  if (per_step <= 1 || steps <= limits.max_steps / per_step) return;
  throw UsageError(std::string(engine) + ": " + std::to_string(steps) + " steps of " + std::to_string(per_step) +
                   " penalty substeps each, above the cap of " + std::to_string(limits.max_steps) +
                   " steps (--max-steps raises it; every substep finds and resolves the contacts)");
}

void check_distinct(const std::vector<std::string>& names, std::string_view flag) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (names[i] == names[j]) throw UsageError(std::string(flag) + ": " + json_input::in_quotes(names[i]) + " is listed twice");
    }
  }
}

void check_engines(const std::vector<std::string>& names, std::string_view flag) {
  for (const std::string& name : names) {
    if (name.empty()) throw UsageError(std::string(flag) + ": an empty engine name (two commas together, or one at an end)");
    check_engine_name(name);
  }
  check_distinct(names, flag);
}

void check_engines_differ(const std::vector<std::string>& names, const Scene& scene, std::string_view flag) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string runs_i = engine_runs_as(names[i], scene);
    for (std::size_t j = 0; j < i; ++j) {
      if (engine_runs_as(names[j], scene) != runs_i) continue;
      throw UsageError(std::string(flag) + ": " + json_input::in_quotes(names[j]) + " and " +
                       json_input::in_quotes(names[i]) + " are one engine on " + scene.source + " (" + runs_i +
                       ", by its solver.method): list one of them");
    }
  }
}

void check_has_setting(std::string_view engine, std::string_view key, std::string_view flag) {
  for (const SettingInfo& s : engine_settings(engine))
    if (s.key == key) return;
  throw UsageError(std::string(flag) + ": engine " + json_input::in_quotes(engine) + " has no setting " +
                   json_input::in_quotes(key) + " (`boxpile settings` lists each engine's)");
}

void check_iterations(int iterations, const RunLimits& limits) {
  if (iterations < 1 || iterations > limits.max_iterations) {
    throw UsageError("--iterations: must be in [1, " + std::to_string(limits.max_iterations) + "], got " +
                     std::to_string(iterations) + " (--max-iterations raises the cap)");
  }
}

}  // namespace boxpile::cli
