#include <iostream>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/sim/time_steps.hpp"
#include "boxpile/validation/cli/activity.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/progress.hpp"
#include "boxpile/validation/cli/report_command.hpp"
#include "boxpile/validation/compare/compare.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/validation/core/data_directory.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/compare/report.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"

namespace boxpile::cli {

// The main job: the registry's main-job list (both of our contact methods beside the references),
// on the bone scene.
CompareOptions default_compare_options() {
  CompareOptions o;
  o.scene = data_path("fixtures/scenes/bone_hits_pile.json").string();
  o.engines = default_engines(&DefaultLists::main_job);
  return o;
}

void add_compare_command(CLI::App& app, CompareOptions& options) {
  CLI::App* cmd = app.add_subcommand("compare", "Run a scene in several engines and write a report comparing them "
                                                "(report.json, report.md, SVG plots)");
  cmd->add_option("scene", options.scene, "Scene file (JSON, docs/scene-format.md)")->required();
  cmd->add_option("--engines", options.engines, "Comma-separated engines among " + engine_choices() +
                      " (own: the scene's solver.method; default: " + engine_list(default_engines(&DefaultLists::compare)) + ")")->delimiter(',')->allow_extra_args(false);
  add_time_options(*cmd, options.dt, options.duration);
  add_threads_option(*cmd, options.threads);
  add_set_option(*cmd, options.set);
  add_report_option(*cmd, options.report, "");
  add_limit_options(*cmd, options.limits, false);
  add_starts_options(*cmd, options.starts);
}

int run_compare_command(const CompareOptions& options) {
  CompareSettings settings;
  if (!options.engines.empty()) settings.engines = options.engines;
  check_engines(settings.engines, "--engines");
  settings.engine_settings = parse_set_options(options.set, settings.engines);
  settings.outcomes = outcome_settings(options.starts);
  // Before the run (before even loading): a report directory that cannot be written fails now,
  // not after minutes.
  ReportDirectory dir(options.report, {options.scene}, kReportJson);
  std::optional<Scene> loaded;
  {
    const Activity loading("loading " + options.scene);
    loaded.emplace(load_checked_scene(options.scene, options.limits.load()));
  }
  Scene& scene = *loaded;
  apply_time_options(scene, options.dt, options.duration, options.limits);
  apply_threads_option(scene, options.threads);
  check_engines_differ(settings.engines, scene, "--engines");
  for (const std::string& engine : settings.engines) {
    check_run_work(scene, engine, settings.settings_of(engine), options.limits, options.dt.has_value());
  }
  const Activity running("comparing " + std::to_string(settings.engines.size()) + " engines on " + options.scene);

  ProgressPrinter progress;
  settings.progress = [&progress](const CompareProgress& p) {
    progress({p.engine, p.baseline ? "(perturbed start)" : "", p.index, p.total, p.fraction});
  };
  StatusLine starts_line;
  int start_runs = 0;
  settings.outcomes.progress = [&](std::string_view what) {
    throw_if_interrupted();
    ++start_runs;
    if (starts_line.due(start_runs, 0.0)) starts_line.draw("  outcomes: " + std::string(what), false);
  };
  std::cerr << "boxpile compare: " << scene.name << " (" << scene.source << "), " << step_count(scene.time)
            << " steps per run, each engine twice";
  if (settings.outcomes.starts > 0) std::cerr << " and from " << settings.outcomes.starts << " perturbed starts";
  std::cerr << '\n';
  const std::optional<CompareResult> result = run_and_report(
      dir, [&] { return run_compare(scene, settings); }, write_report, summary_table, kReportMarkdown);
  if (!result) return kExitInterrupted;
  bool failed = false;
  for (const EngineRun& run : result->runs) {
    if (!run.failure) continue;
    std::cerr << "boxpile: error: " << run.engine << " failed: " << *run.failure << '\n';
    failed = true;
  }
  return failed ? kExitFailure : kExitOk;
}

}  // namespace boxpile::cli
