#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "boxpile/sim/io/input_error.hpp"
#include "boxpile/sim/io/json_input.hpp"
#include "boxpile/sim/io/scene_loader.hpp"
#include "boxpile/validation/cli/activity.hpp"
#include "boxpile/validation/cli/commands.hpp"
#include "boxpile/validation/cli/progress.hpp"
#include "boxpile/validation/cli/report_command.hpp"
#include "boxpile/validation/core/data_directory.hpp"
#include "boxpile/validation/core/engine_settings.hpp"
#include "boxpile/reference/registry.hpp"
#include "boxpile/validation/core/output_safety.hpp"
#include "boxpile/validation/stability/scene_checks.hpp"
#include "boxpile/validation/stability/stability.hpp"
#include "boxpile/validation/stability/stability_report.hpp"

namespace boxpile::cli {
namespace {

namespace fs = std::filesystem;

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
    char text[240];
    if (!p.tuning.empty()) {
      // Each attempt of --tune on its own line: they are few, and each says what it tries.
      std::snprintf(text, sizeof text, "  [%d/%d] %-22s %-7s tuning: %s  elapsed %s, at most about %s left",
                    p.index + 1, p.total, std::string(p.scene).c_str(), std::string(p.engine).c_str(),
                    std::string(p.tuning).c_str(), clock_text(p.elapsed).c_str(), clock_text(p.remaining).c_str());
      line_.draw(text, true);
      return;
    }
    if (!line_.due(p.index, p.fraction)) return;
    std::snprintf(text, sizeof text, "  [%d/%d] %-22s %-7s %3d%%  elapsed %s, about %s left", p.index + 1, p.total,
                  std::string(p.scene).c_str(), std::string(p.engine).c_str(), static_cast<int>(100.0 * p.fraction),
                  clock_text(p.elapsed).c_str(), clock_text(p.remaining).c_str());
    line_.draw(text, p.fraction >= 1.0);
  }

 private:
  StatusLine line_;
};

// The same scene files, however the paths were written (fixtures/hard/ and its files one by one).
bool same_files(std::vector<std::string> a, std::vector<std::string> b) {
  auto canonical = [](std::vector<std::string>& files) {
    for (std::string& f : files) f = std::filesystem::weakly_canonical(f).string();
    std::sort(files.begin(), files.end());
  };
  canonical(a);
  canonical(b);
  return a == b;
}

}  // namespace

void add_stability_command(CLI::App& app, StabilityOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "stability", "Run the catalogue of hard scenes in every engine and judge each run by the scene's checks "
                   "(stability.json, stability.md, plots of failing cells). Exit 0 when our engine passes every "
                   "scene, 1 when it fails one (the reference engines' failures are reported, never fatal)");
  cmd->add_option("--engines", options.engines, "Comma-separated engines among " + engine_choices() + " (default: " + engine_list(default_engines(&DefaultLists::stability)) + ")")->delimiter(',')->allow_extra_args(false);
  add_set_option(*cmd, options.set);
  add_threads_option(*cmd, options.threads);
  cmd->add_option("--scenes", options.scenes, "Scene files or directories of them (default: fixtures/hard/)");
  cmd->add_flag("--tune", options.tune,
                "After each cell, search for the cheapest settings that pass every check (dt halved and solver passes "
                "doubled, then the engine's sleeping switch); stability.json's \"tuned\" and the matrix show them");
  cmd->add_option("--tune-budget", options.tune_budget, "With --tune: seconds of wall time per cell, at most")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  cmd->add_option("--cell-time-limit", options.cell_time_limit,
                  "Seconds of wall time one cell may step (0: no limit); a cell past it stops and fails its "
                  "\"finished\" check, the rest of its checks judging the steps that ran")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  cmd->add_option("--shard", options.shard,
                  "Run shard I of N (I/N, 1-based): the cells whose position k (scene by scene, the engines in order "
                  "within each) has k mod N = I-1; stability-merge joins the shards' reports")
      ->capture_default_str();
  add_report_option(*cmd, options.report, "stability");
  add_limit_options(*cmd, options.limits, false);

  CLI::App* merge = app.add_subcommand("stability-merge", "Merge the reports of a stability run's shards into one report");
  merge->add_option("reports", options.merge_inputs, "Shard report directories (each holding stability.json)")->required();
  merge->add_option("--out,--report", options.report, "Merged report directory (--report is the same)")->capture_default_str();
  add_input_limit_option(*merge, options.limits.max_input_bytes);
}

int run_stability_command(const StabilityOptions& options) {
  // Every input is checked before the first run: scenes, engines, the report directory.
  StabilitySettings settings;
  if (!options.engines.empty()) settings.engines = options.engines;
  check_engines(settings.engines, "--engines");
  settings.engine_settings = parse_set_options(options.set, settings.engines);
  settings.tune = options.tune;
  settings.tune_budget = options.tune_budget;
  settings.cell_time_limit = options.cell_time_limit;
  settings.max_steps = options.limits.max_steps;
  try {
    settings.shard = parse_shard(options.shard);
  } catch (const std::invalid_argument& e) {
    throw InputError("command line", "--shard", e.what());
  }
  std::vector<Scene> scenes;
  const std::vector<std::string> catalogue = catalogue_files({data_path("fixtures/hard").string()});
  const std::vector<std::string> files = options.scenes.empty() ? catalogue : catalogue_files(options.scenes);
  for (const std::string& file : files) {
    const Activity loading("loading " + file);
    scenes.push_back(load_checked_scene(file, options.limits.load()));
    // The caps of run and compare: a scene of 2.4e14 steps is refused, not run until killed.
    apply_time_options(scenes.back(), std::nullopt, std::nullopt, options.limits);
    apply_threads_option(scenes.back(), options.threads);
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
      dir,
      [&] {
        StabilityResult r = run_stability(scenes, settings);
        r.whole_catalogue = same_files(files, catalogue);
        return r;
      },
      write_stability_report, stability_summary,
      kStabilityMarkdown);
  if (!result) return kExitInterrupted;
  return result->own_passed() ? kExitOk : kExitFailure;
}

int run_stability_merge_command(const StabilityOptions& options) {
  // The merged report may be none of its inputs (it would replace one before it is read again).
  std::vector<fs::path> input_files;
  for (const std::string& in : options.merge_inputs) input_files.push_back(fs::path(in) / kStabilityJson);
  ReportDirectory dir(options.report, input_files, kStabilityJson);
  std::vector<StabilityResult> parts;
  for (std::size_t k = 0; k < options.merge_inputs.size(); ++k) {
    const std::string& in = options.merge_inputs[k];
    const std::string path = input_files[k].string();
    std::error_code ec;
    if (!fs::is_regular_file(input_files[k], ec)) throw InputError(in, "", "no stability.json here: not a stability report");
    const nlohmann::json doc =
        json_input::parse(json_input::read_text_file(path, options.limits.max_input_bytes), path);
    try {
      parts.push_back(stability_from_json(doc, [&](const std::string& file) { return load_checked_scene(file, options.limits.load()); }));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(path, "", std::string("not a boxpile stability report: ") + e.what());
    }
  }
  StabilityResult merged;
  try {
    merged = merge_stability(parts, options.merge_inputs);
  } catch (const std::invalid_argument& e) {
    throw InputError("stability-merge", "", e.what());
  }
  report_to(dir, merged, write_stability_report, stability_summary, kStabilityMarkdown);
  return kExitOk;
}

}  // namespace boxpile::cli
