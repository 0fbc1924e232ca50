#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/cli/activity.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/progress.hpp"
#include "boxpile/validation/cli/report_command.hpp"
#include "boxpile/validation/data_directory.hpp"
#include "boxpile/validation/engine_settings.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/output_safety.hpp"
#include "boxpile/validation/stability.hpp"
#include "boxpile/validation/stability_report.hpp"

namespace boxpile::cli {
namespace {

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

// A StatusLine per cell: scene, engine, percent, the time elapsed and the time left.
class StabilityPrinter {
 public:
  void operator()(const StabilityProgress& p) {
    if (!line_.due(p.index, p.fraction)) return;
    char text[200];
    std::snprintf(text, sizeof text, "  [%d/%d] %-22s %-7s %3d%%  elapsed %s, about %s left", p.index + 1, p.total,
                  std::string(p.scene).c_str(), std::string(p.engine).c_str(), static_cast<int>(100.0 * p.fraction),
                  clock_text(p.elapsed).c_str(), clock_text(p.remaining).c_str());
    line_.draw(text, p.fraction >= 1.0);
  }

 private:
  StatusLine line_;
};

}  // namespace

void add_stability_command(CLI::App& app, StabilityOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "stability", "Run the catalogue of hard scenes in every engine and judge each run by the scene's checks "
                   "(stability.json, stability.md, plots of failing cells). Exit 0 when our engine passes every "
                   "scene, 1 when it fails one (the reference engines' failures are reported, never fatal)");
  cmd->add_option("--engines", options.engines, "Comma-separated engines among " + engine_choices() + " (default: " + engine_list(default_engines(&DefaultLists::stability)) + ")")->delimiter(',')->allow_extra_args(false);
  add_set_option(*cmd, options.set);
  cmd->add_option("--scenes", options.scenes, "Scene files or directories of them (default: fixtures/hard/)");
  add_report_option(*cmd, options.report, "stability");
  add_limit_options(*cmd, options.limits, false);
}

int run_stability_command(const StabilityOptions& options) {
  // Every input is checked before the first run: scenes, engines, the report directory.
  StabilitySettings settings;
  if (!options.engines.empty()) settings.engines = options.engines;
  check_engines(settings.engines, "--engines");
  settings.engine_settings = parse_set_options(options.set, settings.engines);
  std::vector<Scene> scenes;
  for (const std::string& file : catalogue_files(options.scenes.empty() ? std::vector<std::string>{data_path("fixtures/hard").string()}
                                                                        : options.scenes)) {
    const Activity loading("loading " + file);
    scenes.push_back(load_scene(file, options.limits.load()));
    // The caps of run and compare: a scene of 2.4e14 steps is refused, not run until killed.
    apply_time_options(scenes.back(), std::nullopt, std::nullopt, options.limits);
    check_engines_differ(settings.engines, scenes.back(), "--engines");
    for (const std::string& engine : settings.engines) {
      check_run_work(scenes.back(), engine, settings.settings_of(engine), options.limits, false);
    }
  }
  ReportDirectory dir(options.report, {}, kStabilityJson);

  StabilityPrinter printer;
  settings.progress = [&printer](const StabilityProgress& p) {
    throw_if_interrupted();
    printer(p);
  };
  std::cerr << "boxpile stability: " << scenes.size() << " scenes in " << settings.engines.size() << " engines\n";
  const Activity running("running the stability catalogue");
  const std::optional<StabilityResult> result = run_and_report(
      dir, [&] { return run_stability(scenes, settings); }, write_stability_report, stability_summary,
      kStabilityMarkdown);
  if (!result) return kExitInterrupted;
  return result->own_passed() ? kExitOk : kExitFailure;
}

}  // namespace boxpile::cli
