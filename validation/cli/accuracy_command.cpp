#include "boxpile/validation/cli/accuracy_command.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "boxpile/reference/registry.hpp"
#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/io/setting.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/validation/accuracy/accuracy.hpp"
#include "boxpile/validation/cli/activity.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/progress.hpp"
#include "boxpile/validation/cli/report_command.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"
#include "boxpile/validation/stability/stability.hpp"

namespace boxpile::cli {
namespace {

constexpr std::string_view kTruthNames[] = {"analytic", "converged", "self"};
constexpr TruthKind kTruthKinds[] = {TruthKind::Analytic, TruthKind::Converged, TruthKind::Self};

}  // namespace

void add_accuracy_command(CLI::App& app, AccuracyOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "accuracy", "Measure each engine's error against a truth at a series of time steps, its cost and its order "
                  "of convergence (accuracy.json, accuracy.md, log-log plots)");
  cmd->add_option("scenes", options.scenes, "Scene files or directories of them (docs/scene-format.md)")->required();
  cmd->add_option("--engines", options.engines, "Comma-separated engines among " + engine_choices() +
                      " (default: " + engine_list(default_engines(&DefaultLists::compare)) + ")")->delimiter(',');
  cmd->add_option("--dt", options.steps, "Comma-separated time steps, s (default: 1/60, 1/120, 1/240, 1/480)")
      ->delimiter(',');
  cmd->add_option("--iteration-scale", options.iteration_scales,
                  "Comma-separated factors on each engine's iteration and pass counts (default: 1); the order is "
                  "fitted at the first")->delimiter(',');
  cmd->add_option("--truth", options.truth,
                  "analytic (the scene's \"truth\"), converged (the same engine at finer steps, iterations raised, "
                  "Richardson-extrapolated) or self (each engine's finest step); default: analytic where the scene "
                  "states one, else converged");
  cmd->add_option("--repetitions", options.repetitions, "Timed runs per cell, interleaved; the least counts")
      ->capture_default_str();
  add_set_option(*cmd, options.set);
  add_report_option(*cmd, options.report, "accuracy");
  add_limit_options(*cmd, options.limits, false);
  add_starts_options(*cmd, options.starts);
}

int run_accuracy_command(const AccuracyOptions& options) {
  // Every input is checked before the first run: engines, settings, steps, scenes, the report.
  AccuracySettings settings;
  settings.engines = options.engines.empty() ? default_engines(&DefaultLists::compare) : options.engines;
  check_engines(settings.engines, "--engines");
  settings.engine_settings = parse_set_options(options.set, settings.engines);
  for (const auto& [engine, given] : settings.engine_settings) {
    if (given.contains(time_step_setting().key)) {
      throw UsageError("--set: " + engine + "." + time_step_setting().key +
                       ": accuracy runs every engine at each step of --dt (and the outcome statistics at the "
                       "scene's own), so a step of its own would do nothing; give the steps with --dt");
    }
  }
  if (!options.steps.empty()) settings.steps = options.steps;
  for (double dt : settings.steps) {
    if (!(dt > 0.0) || !std::isfinite(dt)) {
      throw UsageError("--dt: every time step must be a positive number of seconds, got " + std::to_string(dt));
    }
  }
  {
    std::vector<double> sorted = settings.steps;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) throw UsageError("--dt: a time step given twice");
  }
  if (!options.iteration_scales.empty()) settings.iteration_scales = options.iteration_scales;
  for (int s : settings.iteration_scales) {
    if (s < 1 || s > 1000) throw UsageError("--iteration-scale: every factor must be a whole number in [1, 1000], got " + std::to_string(s));
  }
  if (!options.truth.empty()) {
    const auto it = std::find(std::begin(kTruthNames), std::end(kTruthNames), options.truth);
    if (it == std::end(kTruthNames)) {
      throw UsageError("--truth: \"" + options.truth + "\" is none of analytic, converged, self");
    }
    settings.truth = kTruthKinds[it - std::begin(kTruthNames)];
  }
  if (options.repetitions < 1 || options.repetitions > 100) {
    throw UsageError("--repetitions: must be in [1, 100], got " + std::to_string(options.repetitions));
  }
  settings.repetitions = options.repetitions;
  settings.outcomes = outcome_settings(options.starts);

  std::vector<Scene> scenes;
  std::vector<std::filesystem::path> inputs;
  for (const std::string& file : catalogue_files(options.scenes)) {
    const Activity loading("loading " + file);
    scenes.push_back(load_checked_scene(file, options.limits.load()));
    inputs.emplace_back(file);
    const Scene& scene = scenes.back();
    if (settings.truth == TruthKind::Analytic && scene.truth.empty()) {
      throw InputError(file, "truth", "states no truth, so --truth analytic cannot measure it (docs/scene-format.md, "
                                      "\"Truth\"; --truth converged or self)");
    }
    check_engines_differ(settings.engines, scene, "--engines");
    // Each step, and the finest references of a converged truth (an eighth of the finest step), within the caps.
    std::vector<double> checked = settings.steps;
    if (settings.truth.value_or(scene.truth.empty() ? TruthKind::Converged : TruthKind::Analytic) == TruthKind::Converged) {
      checked.push_back(*std::min_element(settings.steps.begin(), settings.steps.end()) / 8.0);
    }
    if (settings.outcomes.starts > 0) checked.push_back(scene.time.dt);  // the outcome runs' step
    for (double dt : checked) {
      Scene at = scene;
      apply_time_options(at, dt, std::nullopt, options.limits);
      for (const std::string& engine : settings.engines) {
        check_run_work(at, engine, settings.engine_settings.count(engine) ? settings.engine_settings.at(engine)
                                                                          : nlohmann::json::object(),
                       options.limits, true);
      }
    }
  }
  ReportDirectory dir(options.report, inputs, kAccuracyJson);

  StatusLine line;
  int runs = 0;
  settings.progress = [&](std::string_view what) {
    throw_if_interrupted();
    ++runs;
    if (line.due(runs, 0.0)) line.draw("  " + std::string(what), false);
  };
  std::cerr << "boxpile accuracy: " << scenes.size() << " scenes, " << settings.engines.size() << " engines, "
            << settings.steps.size() << " time steps\n";
  const Activity running("measuring accuracy");
  const std::optional<AccuracyResult> result = run_and_report(
      dir, [&] { return run_accuracy(scenes, settings); }, write_accuracy_report, accuracy_summary, kAccuracyMarkdown);
  if (!result) return kExitInterrupted;
  for (const AccuracyScene& s : result->scenes) {
    for (const AccuracyEngine& e : s.engines) {
      for (const AccuracyCell& c : e.cells) {
        if (!c.finite) std::cerr << "boxpile: warning: " << e.engine << " went non-finite on " << s.name << " at dt " << c.dt << '\n';
      }
    }
  }
  return kExitOk;
}

}  // namespace boxpile::cli
